#include "graspcd/study/study.h"

#include <sys/utsname.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <ctime>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "graspcd/core/clock.h"
#include "graspcd/core/tritri.h"
#include "graspcd/exact/exact.h"
#include "graspcd/study/fcl_querier.h"
#include "graspcd/study/recording.h"
#include "graspcd/study/replay.h"
#include "graspcd/study/trajectory.h"
#include "graspcd/version.h"
#include "graspcd/version/data_dirs.h"
#include "graspcd/version/envelope.h"

namespace graspcd::study {

namespace {

using json = nlohmann::json;
using Log = std::function<void(const std::string&)>;

constexpr int kSchema = 1;
constexpr int kBoxHandCap = 10000;  // the paper's box hand (docs/design.md "Semantics")

// The paper's Table 1 (MATLAB, seconds over all grasp steps), examples 1-3.
const std::map<std::string, std::vector<double>> kPaperTable1 = {
    {"sat", {75.18, 114.75, 91.37}},
    {"neurosat", {73.10, 112.08, 76.95}},
    {"perceptron", {57.33, 63.87, 67.56}},
};

std::string read_first(const std::string& path, const std::string& key) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(key, 0) == 0) {
      const auto colon = line.find(':');
      if (colon == std::string::npos) continue;
      std::string v = line.substr(colon + 1);
      const auto first = v.find_first_not_of(" \t");
      return first == std::string::npos ? "" : v.substr(first);
    }
  }
  return "unknown";
}

std::string trimmed(const std::string& s) {
  const auto first = s.find_first_not_of(' ');
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(' ') - first + 1);
}

json machine_info() {
  utsname u{};
  uname(&u);
  return {{"cpu", read_first("/proc/cpuinfo", "model name")},
          {"cores", std::thread::hardware_concurrency()},
          {"memory", read_first("/proc/meminfo", "MemTotal")},
          {"kernel", std::string(u.sysname) + " " + u.release},
          {"os", [] {
             // PRETTY_NAME="Debian GNU/Linux 12 (bookworm)" of os-release(5).
             std::ifstream in("/etc/os-release");
             std::string line;
             while (std::getline(in, line)) {
               if (line.rfind("PRETTY_NAME=", 0) != 0) continue;
               std::string pretty = line.substr(12);
               pretty.erase(std::remove(pretty.begin(), pretty.end(), '"'), pretty.end());
               return pretty;
             }
             return std::string("unknown");
           }()}};
}

json build_info() {
  return {{"graspcd", GRASPCD_VERSION},       {"build_type", GRASPCD_BUILD_TYPE},
          {"compiler", GRASPCD_CXX_COMPILER}, {"flags", trimmed(GRASPCD_BUILD_FLAGS)},
          {"mujoco", GRASPCD_MUJOCO_VERSION}, {"eigen", GRASPCD_EIGEN_VERSION},
          {"cgal", GRASPCD_CGAL_VERSION}};
}

std::string now_utc() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof(buf), "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

std::string fmt(double v, int digits = 2) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(digits);
  s << v;
  return s.str();
}

json counters_json(const QueryCounters& c) {
  return {{"box_tests", c.box_tests},         {"perceptron_passes", c.perceptron_passes},
          {"sat_fallbacks", c.sat_fallbacks}, {"cache_hits", c.cache_hits},
          {"tri_tests", c.tri_tests},         {"tri_pairs", c.tri_pairs}};
}

json timing_json(const std::vector<double>& ns) {
  return {{"median_ms", median(ns) / 1e6},
          {"min_ms", *std::min_element(ns.begin(), ns.end()) / 1e6},
          {"max_ms", *std::max_element(ns.begin(), ns.end()) / 1e6},
          {"repeats_ms", [&] {
             std::vector<double> ms;
             for (double v : ns) ms.push_back(v / 1e6);
             return ms;
           }()}};
}

void write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
}

// Runs job(i) for i in [0, count) on `workers` threads, each taking the next job when it is free,
// in the order given. The first exception a job throws is rethrown after every worker stopped.
void run_parallel(std::size_t count, int workers, const std::function<void(std::size_t)>& job) {
  std::atomic<std::size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  const auto work = [&] {
    for (std::size_t i = next++; i < count; i = next++) {
      try {
        job(i);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        next = count;
      }
    }
  };
  std::vector<std::thread> threads;
  for (int w = 1; w < std::max(1, workers); ++w) threads.emplace_back(work);
  work();
  for (std::thread& t : threads) t.join();
  if (error) std::rethrow_exception(error);
}

// The examples of the study, in order.
struct Example {
  std::string name;
  std::string scene;
};

std::vector<Example> examples(const StudyOptions& o) {
  std::vector<Example> v;
  // Example 1 alone when nothing needs the others (--quick, or a default sweep without tables).
  const int n = o.quick || (!o.table && !o.full_sweep) ? 1 : 3;
  for (int i = 1; i <= n; ++i) {
    const std::string name = "example" + std::to_string(i);
    v.push_back({name, (std::filesystem::path(o.mjcf_dir) / (name + ".xml")).string()});
  }
  return v;
}

json recording_json(const Recording& r, const std::vector<int>* truth_first) {
  json j = {{"name", r.name},
            {"scene", r.scene},
            {"recorded_with", r.native ? "native" : "bridge, " + r.grasp.method},
            {"grasp_steps", r.steps()},
            {"gripped", r.grasp.gripped},
            {"held", r.grasp.held},
            {"object_rise_m", r.grasp.object_z_final - r.grasp.object_z_initial},
            {"first_contact", r.grasp.first_contact},
            {"step_wall_ms", r.grasp.step_wall_ms},
            {"pose_hash", hex64(r.pose_hash)}};
  if (truth_first) j["truth_first_contact"] = *truth_first;
  return j;
}

// ---- Table 1 ----------------------------------------------------------------------------------

struct TableMethod {
  std::string name;
  std::function<std::unique_ptr<Querier>(const MeshScene&)> make;
};

std::vector<TableMethod> table_methods(const StudyOptions& o) {
  std::vector<TableMethod> v;
  for (Method m : all_methods()) {
    // The undisplaced perceptron needs its full cap on nearly every box pair of a real mesh (its
    // bias input dwarfs metre coordinates far from the origin): minutes per example. It is
    // measured on box pairs by the core benchmarks instead.
    if (m == Method::kPerceptronNoDisp) continue;
    // --quick is the smoke test (also under the sanitizers): no method whose replay runs the
    // perceptron to its cap of 1,500 (seconds per replay in Release); Neuro-SAT and the sweep's
    // small caps still exercise the perceptron.
    if (o.quick && (m == Method::kPerceptron || m == Method::kPerceptronWarm ||
                    m == Method::kPerceptronScaled))
      continue;
    v.push_back({method_name(m), [m](const MeshScene&) {
                   return make_detector_querier(m, DetectorOptions{}, QueryMode::kAllContacts);
                 }});
  }
  // The peer: FCL's OBB tree (Gottschalk et al. 1996, as ours) and its RSS tree, all contacts.
  for (peer::FclBv bv : {peer::FclBv::kObb, peer::FclBv::kRss}) {
    v.push_back({peer::fcl_bv_name(bv),
                 [bv](const MeshScene& scene) { return make_fcl_querier(scene, bv); }});
  }
  return v;
}

// Table 1's replays by method name, per example: the sweep reuses those of its default points.
using ReplayCache = std::map<std::string, std::vector<ReplayStats>>;

// Table 1: every (method, example) replay is a job; `jobs` run at once, one thread each (each
// replay alone on its core), the perceptron methods first since they take longest.
json run_table(const StudyOptions& o, const std::vector<Example>& ex,
               const std::vector<Recording>& recs, const std::vector<Answers>& truths,
               const std::vector<std::unique_ptr<MeshScene>>& scenes,
               const std::vector<std::vector<Pose>>& poses, ReplayCache& cache, const Log& log) {
  const std::vector<TableMethod> methods = table_methods(o);
  std::vector<std::pair<std::size_t, std::size_t>> jobs;  // (method, example)
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t m = 0; m < methods.size(); ++m) {
      const auto method = parse_method(methods[m].name);
      const bool slow = method && uses_perceptron(*method);
      if ((pass == 0) != slow) continue;
      for (std::size_t e = ex.size(); e-- > 0;) jobs.emplace_back(m, e);
    }
  }
  std::vector<std::vector<ReplayStats>> results(methods.size(),
                                                std::vector<ReplayStats>(ex.size()));
  std::mutex log_mutex;
  std::size_t done = 0;
  run_parallel(jobs.size(), o.jobs, [&](std::size_t i) {
    const auto [m, e] = jobs[i];
    const Clock::time_point start = Clock::now();
    const auto querier = methods[m].make(*scenes[e]);
    ReplayStats& st = results[m][e];
    // Long replays (the perceptron on example 3 takes minutes) report each repeat.
    const auto progress = [&, m = m, e = e](int r) {
      if (seconds_since(start) < 20 || r == o.repeats) return;
      const std::lock_guard<std::mutex> lock(log_mutex);
      log("table 1: " + ex[e].name + " " + methods[m].name + ": repeat " + std::to_string(r) + "/" +
          std::to_string(o.repeats) + " (" + fmt(seconds_since(start), 1) + " s)");
    };
    st = replay(*scenes[e], poses[e], recs[e].steps(), *querier, o.repeats, progress);
    const bool agree = st.answers.pairs_hash == truths[e].pairs_hash;
    const std::lock_guard<std::mutex> lock(log_mutex);
    ++done;
    log("table 1 (" + std::to_string(done) + "/" + std::to_string(jobs.size()) +
        "): " + ex[e].name + " " + methods[m].name + ": median " +
        fmt(median(st.total_ns) / 1e6, 3) + " ms over " + std::to_string(recs[e].steps()) +
        " grasp steps, " + (agree ? "answers = CGAL" : "answers differ from CGAL") + " (" +
        fmt(seconds_since(start), 1) + " s)");
  });
  json out = json::array();
  for (std::size_t m = 0; m < methods.size(); ++m) {
    json per = json::array();
    for (std::size_t e = 0; e < ex.size(); ++e) {
      const ReplayStats& st = results[m][e];
      json j = timing_json(st.total_ns);
      j["counters"] = counters_json(st.counters);
      j["hit_hash"] = hex64(st.answers.hit_hash);
      j["pairs_hash"] = hex64(st.answers.pairs_hash);
      j["agrees_with_cgal"] = st.answers.pairs_hash == truths[e].pairs_hash;
      j["hits_agree_with_cgal"] = st.answers.hit_hash == truths[e].hit_hash;
      j["queries"] = recs[e].steps() * static_cast<int>(scenes[e]->pairs().size());
      per.push_back(j);
    }
    json mj = {{"name", methods[m].name}, {"examples", per}};
    if (kPaperTable1.count(methods[m].name)) mj["paper_s"] = kPaperTable1.at(methods[m].name);
    out.push_back(mj);
    cache[methods[m].name] = std::move(results[m]);
  }
  json names = json::array();
  for (const Example& e : ex) names.push_back(e.name);
  return {{"examples", names}, {"methods", out}, {"mode", "all contacts"}, {"jobs", o.jobs}};
}

// ---- Figures 13-15: the box hand --------------------------------------------------------------

// Novikoff's bound (R / gamma)^2 on the perceptron's updates for a box pair with exact gap g > 0,
// in the displaced frame of paper section 5 with the bias input 1: R^2 = rho^2 + 1 with rho the
// largest corner distance from the midpoint of the centres; a plane through the middle of the gap
// has margin (g / 2) / sqrt(1 + d^2) with |d| <= rho in the augmented space, so the bound is at
// most 4 (1 + rho^2)^2 / g^2. Infinite for touching or overlapping boxes.
double novikoff_bound(const Obb& a, const Obb& b, double gap) {
  if (!(gap > 0)) return INFINITY;
  const Vec3 mid = 0.5 * (a.center + b.center);
  double rho2 = 0;
  for (const Obb* box : {&a, &b}) {
    for (int i = 0; i < 8; ++i) {
      Vec3 u((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1);
      const Vec3 x = box->center + box->axes * box->half.cwiseProduct(u) - mid;
      rho2 = std::max(rho2, x.squaredNorm());
    }
  }
  return 4 * (1 + rho2) * (1 + rho2) / (gap * gap);
}

json run_box_hand(const StudyOptions& o, const Recording& rec, const Log& log) {
  const BoxScene scene(rec.scene, "BC");
  const auto& pairs = scene.pairs();
  const int steps = rec.steps();
  std::vector<Obb> boxes2;
  std::vector<double> bound;
  std::vector<std::uint8_t> overlap;  // the exact answer (CGAL), per (step, pair)
  for (int s = 0; s < steps; ++s) {
    for (const BoxPair& p : pairs) {
      boxes2.push_back(scene.box2(rec, s, p));
      const Obb& b = boxes2.back();
      bound.push_back(novikoff_bound(p.box1, b, exact::box_box_gap(p.box1, b)));
      overlap.push_back(exact::box_box_overlap(p.box1, b));
    }
  }
  struct BoxMethod {
    std::string name;
    Method method;
    DetectorOptions options;
  };
  DetectorOptions perceptron;
  perceptron.cap = kBoxHandCap;
  const std::vector<BoxMethod> methods = {{"sat", Method::kSat, {}},
                                          {"perceptron", Method::kPerceptron, perceptron},
                                          {"neurosat", Method::kNeuroSat, {}}};
  json out_methods = json::array();
  bool any_false_separated = false;
  for (const BoxMethod& bm : methods) {
    std::uint64_t false_separated = 0;  // "disjoint" for boxes CGAL says overlap: never allowed
    std::uint64_t unproven = 0;         // "may overlap" for boxes CGAL says disjoint: costs only
    // [kind][repeat][step] ns, [kind][step] passes and disjoint answers.
    std::map<char, std::vector<std::vector<double>>> ns;
    std::map<char, std::vector<double>> passes;
    Fnv1a answers;
    std::vector<std::uint8_t> disjoint(pairs.size(), 0);
    for (int r = 0; r < o.repeats; ++r) {
      std::vector<Detector> detectors;
      for (std::size_t i = 0; i < pairs.size(); ++i) detectors.emplace_back(bm.method, bm.options);
      for (char kind : {'B', 'C'}) ns[kind].emplace_back(static_cast<std::size_t>(steps), 0.0);
      for (int s = 0; s < steps; ++s) {
        for (char kind : {'B', 'C'}) {
          QueryCounters c;
          const Clock::time_point start = Clock::now();
          for (std::size_t i = 0; i < pairs.size(); ++i) {
            if (pairs[i].kind != kind) continue;
            disjoint[i] = detectors[i].box_disjoint(
                pairs[i].box1, boxes2[static_cast<std::size_t>(s) * pairs.size() + i], c);
          }
          ns[kind][static_cast<std::size_t>(r)][static_cast<std::size_t>(s)] =
              static_cast<double>(elapsed_ns(start));
          if (r == 0) {
            passes[kind].push_back(static_cast<double>(c.perceptron_passes));
            for (std::size_t i = 0; i < pairs.size(); ++i) {
              if (pairs[i].kind != kind) continue;
              answers.add(disjoint[i]);
              const bool truth = overlap[static_cast<std::size_t>(s) * pairs.size() + i];
              false_separated += disjoint[i] && truth;
              unproven += !disjoint[i] && !truth;
            }
          }
        }
      }
    }
    json kinds;
    for (char kind : {'B', 'C'}) {
      std::vector<double> med(static_cast<std::size_t>(steps));
      std::vector<double> totals;
      for (int s = 0; s < steps; ++s) {
        std::vector<double> v;
        for (const auto& rep : ns[kind]) v.push_back(rep[static_cast<std::size_t>(s)]);
        med[static_cast<std::size_t>(s)] = median(v);
      }
      for (const auto& rep : ns[kind]) {
        double t = 0;
        for (double x : rep) t += x;
        totals.push_back(t);
      }
      kinds[std::string(1, kind)] = {
          {"step_ns_median", med}, {"passes", passes[kind]}, {"total", timing_json(totals)}};
    }
    any_false_separated = any_false_separated || false_separated > 0;
    out_methods.push_back({{"name", bm.name},
                           {"cap", bm.options.cap},
                           {"switch", bm.options.switch_passes},
                           {"segments", kinds},
                           {"false_separated", false_separated},
                           {"unproven_disjoint", unproven},
                           {"answer_hash", hex64(answers.value())}});
    log("figures 13-15: box hand " + bm.name + " replayed (" + std::to_string(steps) +
        " grasp steps, " + std::to_string(pairs.size()) + " box pairs)");
  }
  // Per step and segment kind: the largest finite Novikoff bound and the number of pairs in
  // contact (no finite bound).
  json bounds;
  for (char kind : {'B', 'C'}) {
    std::vector<double> worst;
    std::vector<int> touching;
    for (int s = 0; s < steps; ++s) {
      double w = 0;
      int t = 0;
      for (std::size_t i = 0; i < pairs.size(); ++i) {
        if (pairs[i].kind != kind) continue;
        const double b = bound[static_cast<std::size_t>(s) * pairs.size() + i];
        if (std::isfinite(b)) {
          w = std::max(w, b);
        } else {
          ++t;
        }
      }
      worst.push_back(w);
      touching.push_back(t);
    }
    bounds[std::string(1, kind)] = {{"novikoff_max_finite", worst}, {"pairs_in_contact", touching}};
  }
  std::uint64_t overlapping = 0;
  for (std::uint8_t v : overlap) overlapping += v;
  return {{"scene", rec.scene},
          {"steps", steps},
          {"pairs", pairs.size()},
          {"methods", out_methods},
          {"bounds", bounds},
          {"box_tests", overlap.size()},
          {"overlapping_exact", overlapping},
          {"no_false_separated", !any_false_separated}};
}

// ---- The sweep --------------------------------------------------------------------------------

// The paper's perceptron read literally: a converged pass means "separated", no proof that the
// corners clear the plane by more than the rounding error (core/perceptron.h does prove it).
struct UnprovenPerceptronSeparator {
  PerceptronOptions options;
  bool disjoint(const Obb& a, const Obb& b, std::int32_t, std::int32_t, QueryCounters& c) {
    const PerceptronResult r = perceptron_separate(a, b, options);
    c.perceptron_passes += static_cast<std::uint64_t>(r.passes);
    return r.converged;
  }
};
struct PlainTriTest {
  bool operator()(const Triangle& a, const Triangle& b) const { return tri_tri_moller_plain(a, b); }
};
struct NaiveTriTest {
  bool operator()(const Triangle& a, const Triangle& b) const { return tri_tri_moller_naive(a, b); }
};

enum class FloatNodes { kNone, kRounded, kPadded };

struct SweepConfig {
  SweepConfig(std::string name_, std::string family_, double value_,
              std::function<std::unique_ptr<Querier>()> make_)
      : name(std::move(name_)), family(std::move(family_)), value(value_), make(std::move(make_)) {}
  std::string name;
  std::string family;
  double value = 0;  // the knob's value (0 where the family has none)
  std::function<std::unique_ptr<Querier>()> make;
  int leaf_size = 1;
  FloatNodes float_nodes = FloatNodes::kNone;
  std::string table_method;  // the Table 1 method this point equals ("" none): its replays serve
  bool first_contact = false;
};

// The sweep's points (issue 5, item 3). Standard: what the default run measures on example 1;
// full: more knob values, for cluster runs; quick: the cheap points only.
std::vector<SweepConfig> sweep_configs(bool quick, bool full) {
  std::vector<SweepConfig> v;
  const auto detector = [](Method m, int cap, int sw, QueryMode mode) {
    return [=] {
      DetectorOptions d;
      d.cap = cap;
      d.switch_passes = sw;
      return make_detector_querier(m, d, mode);
    };
  };
  const int cap = tol::kPerceptronDefaultCap;
  const int sw = tol::kNeuroSatDefaultSwitch;
  const auto all = QueryMode::kAllContacts;
  const auto add = [&v](SweepConfig c, const std::string& table_method = "") {
    c.table_method = table_method;
    v.push_back(std::move(c));
  };
  add({"sat", "separator", 0, detector(Method::kSat, cap, sw, all)}, "sat");
  add({"sat-cached", "separator", 0, detector(Method::kSatCached, cap, sw, all)}, "sat-cached");
  if (!quick) {
    add({"perceptron-warm", "separator", 0, detector(Method::kPerceptronWarm, cap, sw, all)},
        "perceptron-warm");
    add({"perceptron-scaled", "separator", 0, detector(Method::kPerceptronScaled, cap, sw, all)},
        "perceptron-scaled");
    add({"perceptron-unproven", "separator", 0, [] {
           return std::make_unique<PolicyQuerier<UnprovenPerceptronSeparator, FilteredTriTest>>(
               UnprovenPerceptronSeparator{}, QueryMode::kAllContacts);
         }});
  }
  std::vector<int> caps = {10, 100, 300, 1500};
  std::vector<int> switches = {10, 100, 300, 1000, 3000};
  std::vector<int> leaves = {2, 4, 8, 16};
  if (full) {
    caps = {10, 30, 100, 300, 1000, 1500, 3000};
    switches = {10, 30, 100, 300, 1000, 3000};
  }
  if (quick) {
    caps = {10};
    switches = {10};
    leaves = {4};
  }
  for (int c : caps) {
    add({"perceptron cap " + std::to_string(c), "perceptron cap", static_cast<double>(c),
         detector(Method::kPerceptron, c, sw, all)},
        c == cap ? "perceptron" : "");
  }
  for (int s : switches) {
    add({"neurosat switch " + std::to_string(s), "neurosat switch", static_cast<double>(s),
         detector(Method::kNeuroSat, cap, s, all)},
        s == sw ? "neurosat" : "");
    add({"neurosat-sticky switch " + std::to_string(s), "neurosat-sticky switch",
         static_cast<double>(s), detector(Method::kNeuroSatSticky, cap, s, all)},
        s == sw ? "neurosat-sticky" : "");
  }
  for (int l : leaves) {
    SweepConfig c{"sat leaf " + std::to_string(l), "leaf size", static_cast<double>(l),
                  detector(Method::kSat, cap, sw, all)};
    c.leaf_size = l;
    add(c);
  }
  SweepConfig rounded{"sat float nodes", "tree nodes", 0, detector(Method::kSat, cap, sw, all)};
  rounded.float_nodes = FloatNodes::kRounded;
  add(rounded);
  SweepConfig padded{"sat float nodes padded", "tree nodes", 0,
                     detector(Method::kSat, cap, sw, all)};
  padded.float_nodes = FloatNodes::kPadded;
  add(padded);
  add({"sat moller-plain", "triangle test", 0, [] {
         return std::make_unique<PolicyQuerier<SatSeparator, PlainTriTest>>(
             SatSeparator{}, QueryMode::kAllContacts);
       }});
  add({"sat moller-naive 1e-6", "triangle test", 0, [] {
         return std::make_unique<PolicyQuerier<SatSeparator, NaiveTriTest>>(
             SatSeparator{}, QueryMode::kAllContacts);
       }});
  SweepConfig first{"sat first-contact", "mode", 0,
                    detector(Method::kSat, cap, sw, QueryMode::kFirstContact)};
  first.first_contact = true;
  add(first);
  if (!quick) {
    SweepConfig neuro_first{"neurosat first-contact", "mode", 0,
                            detector(Method::kNeuroSat, cap, sw, QueryMode::kFirstContact)};
    neuro_first.first_contact = true;
    add(neuro_first);
  }
  return v;
}

json config_names(const std::vector<SweepConfig>& configs) {
  json names = json::array();
  for (const SweepConfig& c : configs) names.push_back(c.name);
  return names;
}

json run_sweep(const StudyOptions& o, const std::vector<Example>& all_examples,
               const std::vector<Recording>& recs, const std::vector<Answers>& truths,
               const ReplayCache& cache, const Log& log) {
  const std::vector<SweepConfig> configs = sweep_configs(o.quick, o.full_sweep);
  // The default sweep runs on example 1 only; --full-sweep on every example.
  const std::size_t n_ex = o.full_sweep ? all_examples.size() : 1;
  const std::vector<Example> ex(all_examples.begin(),
                                all_examples.begin() + static_cast<long>(n_ex));
  const Shard shard = o.shard.value_or(Shard{});
  std::vector<std::size_t> mine;
  for (std::size_t i = 0; i < configs.size(); ++i) {
    if (static_cast<int>(i) % shard.count == shard.index) mine.push_back(i);
  }
  // Scenes by (leaf size, float nodes) with their poses, built before the workers start.
  std::map<std::pair<int, int>, std::vector<std::unique_ptr<MeshScene>>> scenes;
  std::map<std::pair<int, int>, std::vector<std::vector<Pose>>> poses;
  const auto key_of = [](const SweepConfig& c) {
    return std::make_pair(c.leaf_size, static_cast<int>(c.float_nodes));
  };
  for (std::size_t i : mine) {
    const SweepConfig& c = configs[i];
    auto& sc = scenes[key_of(c)];
    if (!sc.empty()) continue;
    ObbTreeOptions to;
    to.leaf_size = c.leaf_size;
    for (std::size_t e = 0; e < ex.size(); ++e) {
      sc.push_back(std::make_unique<MeshScene>(ex[e].scene, to));
      if (c.float_nodes != FloatNodes::kNone) {
        const bool pad = c.float_nodes == FloatNodes::kPadded;
        sc.back()->transform_trees([pad](const ObbTree& t) { return t.rounded_to_float(pad); });
      }
      poses[key_of(c)].push_back(recorded_poses(*sc.back(), recs[e]));
    }
  }
  const auto reuses = [&](const SweepConfig& c) {
    return !c.table_method.empty() && cache.count(c.table_method) && c.leaf_size == 1 &&
           c.float_nodes == FloatNodes::kNone;
  };
  // The replays, `jobs` at a time (slowest families first), then the comparison with CGAL.
  std::vector<std::pair<std::size_t, std::size_t>> jobs;  // (index into mine, example)
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t k = 0; k < mine.size(); ++k) {
      const SweepConfig& c = configs[mine[k]];
      if (reuses(c)) continue;
      const bool slow = c.family.rfind("perceptron", 0) == 0 || c.name.rfind("perceptron", 0) == 0;
      if ((pass == 0) != slow) continue;
      for (std::size_t e = 0; e < ex.size(); ++e) jobs.emplace_back(k, e);
    }
  }
  std::vector<std::vector<ReplayStats>> fresh(mine.size(), std::vector<ReplayStats>(ex.size()));
  std::mutex log_mutex;
  std::size_t done = 0;
  run_parallel(jobs.size(), o.jobs, [&](std::size_t j) {
    const auto [k, e] = jobs[j];
    const SweepConfig& c = configs[mine[k]];
    const Clock::time_point start = Clock::now();
    const auto querier = c.make();
    fresh[k][e] =
        replay(*scenes[key_of(c)][e], poses[key_of(c)][e], recs[e].steps(), *querier, o.repeats);
    const std::lock_guard<std::mutex> lock(log_mutex);
    ++done;
    log("sweep (" + std::to_string(done) + "/" + std::to_string(jobs.size()) + "): " + c.name +
        " on " + ex[e].name + ": median " + fmt(median(fresh[k][e].total_ns) / 1e6, 3) + " ms (" +
        fmt(seconds_since(start), 1) + " s)");
  });

  json results = json::array();
  for (std::size_t k = 0; k < mine.size(); ++k) {
    const std::size_t i = mine[k];
    const SweepConfig& c = configs[i];
    const auto& sc = scenes[key_of(c)];
    std::vector<double> totals(static_cast<std::size_t>(o.repeats), 0.0);
    ErrorStats sum;
    double position_weighted = 0;
    json per = json::array();
    QueryCounters counters;
    const bool reuse = reuses(c);
    for (std::size_t e = 0; e < ex.size(); ++e) {
      const ReplayStats& st = reuse ? cache.at(c.table_method)[e] : fresh[k][e];
      for (std::size_t r = 0; r < totals.size(); ++r) totals[r] += st.total_ns[r];
      const ErrorStats err = compare(*sc[e], recs[e], st.answers, truths[e], c.first_contact);
      sum.missed += err.missed;
      sum.false_contacts += err.false_contacts;
      sum.missed_tri_pairs += err.missed_tri_pairs;
      sum.false_tri_pairs += err.false_tri_pairs;
      sum.first_contact_error_max =
          std::max(sum.first_contact_error_max, err.first_contact_error_max);
      sum.first_contact_error_sum += err.first_contact_error_sum;
      sum.position_error_max = std::max(sum.position_error_max, err.position_error_max);
      position_weighted += err.position_error_mean;
      counters += st.counters;
      per.push_back({{"example", ex[e].name},
                     {"median_ms", median(st.total_ns) / 1e6},
                     {"missed", err.missed},
                     {"false_contacts", err.false_contacts},
                     {"hit_hash", hex64(st.answers.hit_hash)},
                     {"pairs_hash", hex64(st.answers.pairs_hash)}});
    }
    json j = timing_json(totals);
    j["name"] = c.name;
    j["family"] = c.family;
    j["first_contact_mode"] = c.first_contact;
    j["value"] = c.value;
    j["index"] = i;
    j["missed"] = sum.missed;
    j["false_contacts"] = sum.false_contacts;
    j["first_contact_step_error_max"] = sum.first_contact_error_max;
    j["first_contact_step_error_sum"] = sum.first_contact_error_sum;
    j["missed_tri_pairs"] = sum.missed_tri_pairs;
    j["false_tri_pairs"] = sum.false_tri_pairs;
    j["position_error_max_mm"] = sum.position_error_max * 1e3;
    j["position_error_mean_mm"] = position_weighted / static_cast<double>(ex.size()) * 1e3;
    j["counters"] = counters_json(counters);
    j["examples"] = per;
    j["from_table1"] = reuse;
    results.push_back(j);
  }
  log("sweep: " + std::to_string(mine.size()) + " points compared with CGAL");
  json recordings = json::array();
  for (std::size_t e = 0; e < ex.size(); ++e)
    recordings.push_back({{"name", recs[e].name}, {"pose_hash", hex64(recs[e].pose_hash)}});
  return {{"schema", kSchema},
          {"quick", o.quick},
          {"full", o.full_sweep},
          {"repeats", o.repeats},
          {"shard", {{"index", shard.index}, {"count", shard.count}}},
          {"config_names", config_names(configs)},
          {"recordings", recordings},
          {"configs", results}};
}

std::string sweep_csv(const json& sweep) {
  std::ostringstream s;
  s << "index,name,family,value,median_ms,min_ms,max_ms,missed,false_contacts,"
       "first_contact_step_error_max,first_contact_step_error_sum,missed_tri_pairs,false_tri_pairs,"
       "position_error_max_mm,position_error_mean_mm,box_tests,perceptron_passes,tri_tests\n";
  for (const json& c : sweep["configs"]) {
    s << c["index"].get<int>() << ",\"" << c["name"].get<std::string>() << "\",\""
      << c["family"].get<std::string>() << "\"," << c["value"].get<double>() << ","
      << c["median_ms"].get<double>() << "," << c["min_ms"].get<double>() << ","
      << c["max_ms"].get<double>() << "," << c["missed"].get<std::uint64_t>() << ","
      << c["false_contacts"].get<std::uint64_t>() << ","
      << c["first_contact_step_error_max"].get<int>() << ","
      << c["first_contact_step_error_sum"].get<int>() << ","
      << c["missed_tri_pairs"].get<std::uint64_t>() << ","
      << c["false_tri_pairs"].get<std::uint64_t>() << ","
      << c["position_error_max_mm"].get<double>() << ","
      << c["position_error_mean_mm"].get<double>() << ","
      << c["counters"]["box_tests"].get<std::uint64_t>() << ","
      << c["counters"]["perceptron_passes"].get<std::uint64_t>() << ","
      << c["counters"]["tri_tests"].get<std::uint64_t>() << "\n";
  }
  return s.str();
}

std::string table_csv(const json& table) {
  std::ostringstream s;
  s << "method,example,median_ms,min_ms,max_ms,box_tests,perceptron_passes,tri_tests,pairs_hash,"
       "agrees_with_cgal,paper_s\n";
  for (const json& m : table["methods"]) {
    for (std::size_t e = 0; e < m["examples"].size(); ++e) {
      const json& x = m["examples"][e];
      s << m["name"].get<std::string>() << "," << table["examples"][e].get<std::string>() << ","
        << x["median_ms"].get<double>() << "," << x["min_ms"].get<double>() << ","
        << x["max_ms"].get<double>() << "," << x["counters"]["box_tests"].get<std::uint64_t>()
        << "," << x["counters"]["perceptron_passes"].get<std::uint64_t>() << ","
        << x["counters"]["tri_tests"].get<std::uint64_t>() << ","
        << x["pairs_hash"].get<std::string>() << "," << (x["agrees_with_cgal"].get<bool>() ? 1 : 0)
        << ",";
      if (m.contains("paper_s")) s << m["paper_s"][e].get<double>();
      s << "\n";
    }
  }
  return s.str();
}

std::string box_csv(const json& box) {
  std::ostringstream s;
  s << "method,segment,step,ns_median,passes\n";
  for (const json& m : box["methods"]) {
    for (const std::string kind : {"B", "C"}) {
      const json& k = m["segments"][kind];
      for (std::size_t i = 0; i < k["passes"].size(); ++i) {
        s << m["name"].get<std::string>() << "," << kind << "," << i + 1 << ","
          << k["step_ns_median"][i].get<double>() << "," << k["passes"][i].get<double>() << "\n";
      }
    }
  }
  return s.str();
}

// The viewer's and the figures' data (trajectory.h): each example with the per-step detection
// times of Table 1's replays, and the box hand.
void write_trajectories(const std::filesystem::path& dir, const std::vector<Example>& ex,
                        const std::vector<Recording>& recs,
                        const std::vector<std::unique_ptr<MeshScene>>& scenes,
                        const ReplayCache& cache, const Recording& box, const Log& log) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error(dir.string() + ": cannot create the folder: " + ec.message());
  for (std::size_t e = 0; e < ex.size(); ++e) {
    StepTimes times;
    for (const auto& [method, stats] : cache)
      times.emplace_back(method, step_medians(stats[e].step_ns));
    write_trajectory((dir / (ex[e].name + ".json")).string(), recs[e], scenes[e].get(), times);
  }
  write_trajectory((dir / "hand_boxes.json").string(), box, nullptr, {});
  log("wrote " + std::to_string(ex.size() + 1) + " trajectories into " + dir.string());
}

}  // namespace

json read_shard_file(const std::string& file, const std::string& kind,
                     const std::vector<std::string>& keys) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file + ": cannot open the shard file");
  json j;
  try {
    in >> j;
  } catch (const json::exception& e) {
    throw std::runtime_error(file + ": not " + kind + " (" + e.what() + ")");
  }
  const bool complete = j.is_object() && std::all_of(keys.begin(), keys.end(),
                                                     [&j](const auto& k) { return j.contains(k); });
  if (!complete) {
    std::string names;
    for (std::size_t i = 0; i < keys.size(); ++i) {
      names += (i == 0 ? "" : i + 1 == keys.size() ? " or " : ", ") + keys[i];
    }
    throw std::runtime_error(file + ": not " + kind + " (no " + names + ")");
  }
  return j;
}

Shard parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  std::size_t p1 = 0;
  std::size_t p2 = 0;
  Shard s;
  try {
    if (slash == std::string::npos) throw std::invalid_argument("");
    s.index = std::stoi(text.substr(0, slash), &p1);
    s.count = std::stoi(text.substr(slash + 1), &p2);
  } catch (const std::exception&) {
    throw std::invalid_argument("--shard expects i/n, e.g. 0/4, not '" + text + "'");
  }
  if (p1 != slash || p2 != text.size() - slash - 1 || s.count < 1 || s.index < 0 ||
      s.index >= s.count)
    throw std::invalid_argument("--shard expects i/n with 0 <= i < n, not '" + text + "'");
  return s;
}

void run_study(const StudyOptions& options, const Log& log) {
  StudyOptions o = options;
  if (o.mjcf_dir.empty()) o.mjcf_dir = graspcd::mjcf_dir();
  if (o.repeats < 1) throw std::runtime_error("--repeats must be >= 1");
  if (o.jobs < 1) o.jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (o.shard) o.table = false;
  const Clock::time_point start = Clock::now();
  const std::filesystem::path out(o.out_dir);
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec)
    throw std::runtime_error(o.out_dir + ": cannot create the output folder: " + ec.message());

  const std::vector<Example> ex = examples(o);
  std::vector<Recording> recs;
  for (const Example& e : ex) {
    const Clock::time_point t = Clock::now();
    recs.push_back(record_grasp(e.name, e.scene, false, o.max_steps));
    const Recording& r = recs.back();
    log("recorded " + e.name + " with the bridge (sat): " + std::to_string(r.steps()) +
        " grasp steps, " + (r.grasp.held ? "held" : "NOT held") + ", rise " +
        fmt(100 * (r.grasp.object_z_final - r.grasp.object_z_initial), 1) + " cm (" +
        fmt(seconds_since(t), 1) + " s)");
  }
  std::vector<std::unique_ptr<MeshScene>> scenes;
  std::vector<Answers> truths;
  for (std::size_t e = 0; e < ex.size(); ++e) {
    const Clock::time_point t = Clock::now();
    scenes.push_back(std::make_unique<MeshScene>(ex[e].scene));
    truths.push_back(exact_answers(*scenes.back(), recs[e]));
    log("CGAL ground truth for " + ex[e].name + ": " + std::to_string(recs[e].steps()) +
        " steps x " + std::to_string(scenes.back()->pairs().size()) + " pairs (" +
        fmt(seconds_since(t), 1) + " s)");
  }

  ReplayCache cache;
  if (o.table) {
    json study = {{"schema", kSchema},    {"created", now_utc()},      {"quick", o.quick},
                  {"repeats", o.repeats}, {"machine", machine_info()}, {"build", build_info()}};
    json recordings = json::array();
    for (std::size_t e = 0; e < ex.size(); ++e) {
      const std::vector<int> truth_first =
          first_contact_steps(*scenes[e], truths[e], recs[e].steps());
      json r = recording_json(recs[e], &truth_first);
      r["pairs"] = scenes[e]->pairs().size();
      r["faces"] = scenes[e]->face_count();
      r["truth_pairs_hash"] = hex64(truths[e].pairs_hash);
      recordings.push_back(r);
    }
    study["recordings"] = recordings;
    std::vector<std::vector<Pose>> poses;
    for (std::size_t e = 0; e < ex.size(); ++e)
      poses.push_back(recorded_poses(*scenes[e], recs[e]));
    study["table1"] = run_table(o, ex, recs, truths, scenes, poses, cache, log);
    write_file(out / "table1.csv", table_csv(study["table1"]));

    const std::string box_scene = (std::filesystem::path(o.mjcf_dir) / "hand_boxes.xml").string();
    const Clock::time_point t = Clock::now();
    const Recording box = record_grasp("hand_boxes", box_scene, false, o.max_steps);
    log("recorded hand_boxes with the bridge (sat, exact box-box): " + std::to_string(box.steps()) +
        " grasp steps (" + fmt(seconds_since(t), 1) + " s)");
    study["box_hand"] = run_box_hand(o, box, log);
    study["box_hand"]["recording"] = recording_json(box, nullptr);
    write_file(out / "box_hand.csv", box_csv(study["box_hand"]));
    write_trajectories(out / "trajectories", ex, recs, scenes, cache, box, log);
    study["seconds"] = seconds_since(start);
    add_envelope(study);
    write_file(out / "study.json", study.dump(1) + "\n");
    log("wrote " + (out / "study.json").string() + ", table1.csv, box_hand.csv");
  }
  if (o.sweep) {
    json sweep = run_sweep(o, ex, recs, truths, cache, log);
    add_envelope(sweep);
    const std::string base = o.shard ? "sweep.shard-" + std::to_string(o.shard->index) + "-of-" +
                                           std::to_string(o.shard->count)
                                     : std::string("sweep");
    write_file(out / (base + ".json"), sweep.dump(1) + "\n");
    write_file(out / (base + ".csv"), sweep_csv(sweep));
    log("wrote " + (out / (base + ".json")).string() + " and .csv");
  }
  log("done in " + fmt(seconds_since(start), 1) + " s");
}

void merge_shards(const std::vector<std::string>& files, const std::string& out_dir,
                  const Log& log) {
  if (files.empty()) throw std::runtime_error("--merge needs at least one shard file");
  json merged;
  std::map<int, json> by_index;
  int count = -1;
  for (const std::string& f : files) {
    json j = read_shard_file(f, "a sweep shard", {"configs", "config_names", "shard"});
    if (merged.is_null()) {
      merged = j;
      merged["configs"] = json::array();
      count = j["shard"]["count"].get<int>();
    } else {
      if (j["config_names"] != merged["config_names"])
        throw std::runtime_error(f + ": another sweep (its configuration list differs)");
      if (j["recordings"] != merged["recordings"])
        throw std::runtime_error(f + ": recorded other grasps (pose hashes differ)");
      if (j["repeats"] != merged["repeats"] || j["quick"] != merged["quick"] ||
          j["full"] != merged["full"])
        throw std::runtime_error(f + ": run with other --repeats, --quick or --full-sweep");
      if (j["shard"]["count"].get<int>() != count)
        throw std::runtime_error(f + ": a shard of another split");
    }
    for (const json& c : j["configs"]) {
      const int i = c["index"].get<int>();
      if (by_index.count(i))
        throw std::runtime_error(f + ": configuration " + std::to_string(i) + " appears twice");
      by_index[i] = c;
    }
  }
  const std::size_t n = merged["config_names"].size();
  for (std::size_t i = 0; i < n; ++i) {
    if (by_index.count(static_cast<int>(i))) continue;
    // Shard k of n holds configurations k, k + n, ...: name the shard file that is missing.
    const int shard = static_cast<int>(i % static_cast<std::size_t>(count));
    throw std::runtime_error(
        "shard " + std::to_string(shard) + " of " + std::to_string(count) + " (sweep.shard-" +
        std::to_string(shard) + "-of-" + std::to_string(count) +
        ".json) is missing: configuration " + std::to_string(i) + " (" +
        merged["config_names"][i].get<std::string>() + ") is in no shard given");
  }
  for (auto& [i, c] : by_index) merged["configs"].push_back(c);
  merged["shard"] = {{"index", 0}, {"count", 1}};
  merged["merged_from"] = files.size();
  const std::filesystem::path out(out_dir);
  std::filesystem::create_directories(out);
  add_envelope(merged);
  write_file(out / "sweep.json", merged.dump(1) + "\n");
  write_file(out / "sweep.csv", sweep_csv(merged));
  log("merged " + std::to_string(files.size()) + " shards (" + std::to_string(n) +
      " configurations) into " + (out / "sweep.json").string());
}

}  // namespace graspcd::study
