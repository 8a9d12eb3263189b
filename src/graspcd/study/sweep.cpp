#include "graspcd/study/sweep.h"

#include <algorithm>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <utility>

#include "graspcd/core/clock.h"
#include "graspcd/core/tolerances.h"
#include "graspcd/core/tritri.h"
#include "graspcd/study/thread_pool.h"

namespace graspcd::study {

namespace {

using json = nlohmann::json;

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

using MakeQuerier = std::function<std::unique_ptr<Querier>()>;

// A detector method's querier with the given cap, switch and mode.
MakeQuerier detector(Method m, int cap, int sw, QueryMode mode) {
  return [=] {
    DetectorOptions d;
    d.cap = cap;
    d.switch_passes = sw;
    return make_detector_querier(m, d, mode);
  };
}

void add(std::vector<SweepConfig>& v, SweepConfig c, const std::string& table_method = "") {
  c.table_method = table_method;
  v.push_back(std::move(c));
}

// The separators at their defaults, the perceptron's caps and Neuro-SAT's switches.
void add_separator_points(std::vector<SweepConfig>& v, bool quick, bool full) {
  const int cap = tol::kPerceptronDefaultCap;
  const int sw = tol::kNeuroSatDefaultSwitch;
  const auto all = QueryMode::kAllContacts;
  add(v, {"sat", "separator", 0, detector(Method::kSat, cap, sw, all)}, "sat");
  add(v, {"sat-cached", "separator", 0, detector(Method::kSatCached, cap, sw, all)}, "sat-cached");
  if (!quick) {
    add(v, {"perceptron-warm", "separator", 0, detector(Method::kPerceptronWarm, cap, sw, all)},
        "perceptron-warm");
    add(v, {"perceptron-scaled", "separator", 0, detector(Method::kPerceptronScaled, cap, sw, all)},
        "perceptron-scaled");
    add(v, {"perceptron-unproven", "separator", 0, [] {
              return std::make_unique<PolicyQuerier<UnprovenPerceptronSeparator, FilteredTriTest>>(
                  UnprovenPerceptronSeparator{}, QueryMode::kAllContacts);
            }});
  }
  std::vector<int> caps = {10, 100, 300, 1500};
  std::vector<int> switches = {10, 100, 300, 1000, 3000};
  if (full) {
    caps = {10, 30, 100, 300, 1000, 1500, 3000};
    switches = {10, 30, 100, 300, 1000, 3000};
  }
  if (quick) {
    caps = {10};
    switches = {10};
  }
  for (int c : caps) {
    add(v,
        {"perceptron cap " + std::to_string(c), "perceptron cap", static_cast<double>(c),
         detector(Method::kPerceptron, c, sw, all)},
        c == cap ? "perceptron" : "");
  }
  for (int s : switches) {
    add(v,
        {"neurosat switch " + std::to_string(s), "neurosat switch", static_cast<double>(s),
         detector(Method::kNeuroSat, cap, s, all)},
        s == sw ? "neurosat" : "");
    add(v,
        {"neurosat-sticky switch " + std::to_string(s), "neurosat-sticky switch",
         static_cast<double>(s), detector(Method::kNeuroSatSticky, cap, s, all)},
        s == sw ? "neurosat-sticky" : "");
  }
}

// SAT on other trees (leaf sizes, float nodes), with Moller's test in plain or naive floating
// point, and in first-contact mode.
void add_tree_and_mode_points(std::vector<SweepConfig>& v, bool quick) {
  const int cap = tol::kPerceptronDefaultCap;
  const int sw = tol::kNeuroSatDefaultSwitch;
  const auto all = QueryMode::kAllContacts;
  const std::vector<int> leaves = quick ? std::vector<int>{4} : std::vector<int>{2, 4, 8, 16};
  for (int l : leaves) {
    SweepConfig c{"sat leaf " + std::to_string(l), "leaf size", static_cast<double>(l),
                  detector(Method::kSat, cap, sw, all)};
    c.leaf_size = l;
    add(v, c);
  }
  SweepConfig rounded{"sat float nodes", "tree nodes", 0, detector(Method::kSat, cap, sw, all)};
  rounded.float_nodes = FloatNodes::kRounded;
  add(v, rounded);
  SweepConfig padded{"sat float nodes padded", "tree nodes", 0,
                     detector(Method::kSat, cap, sw, all)};
  padded.float_nodes = FloatNodes::kPadded;
  add(v, padded);
  add(v, {"sat moller-plain", "triangle test", 0, [] {
            return std::make_unique<PolicyQuerier<SatSeparator, PlainTriTest>>(
                SatSeparator{}, QueryMode::kAllContacts);
          }});
  add(v, {"sat moller-naive 1e-6", "triangle test", 0, [] {
            return std::make_unique<PolicyQuerier<SatSeparator, NaiveTriTest>>(
                SatSeparator{}, QueryMode::kAllContacts);
          }});
  SweepConfig first{"sat first-contact", "mode", 0,
                    detector(Method::kSat, cap, sw, QueryMode::kFirstContact)};
  first.first_contact = true;
  add(v, first);
  if (!quick) {
    SweepConfig neuro_first{"neurosat first-contact", "mode", 0,
                            detector(Method::kNeuroSat, cap, sw, QueryMode::kFirstContact)};
    neuro_first.first_contact = true;
    add(v, neuro_first);
  }
}

// The sweep's points. Standard: what the default run measures on example 1; full: more knob
// values, for cluster runs; quick: the cheap points only.
std::vector<SweepConfig> sweep_configs(bool quick, bool full) {
  std::vector<SweepConfig> v;
  add_separator_points(v, quick, full);
  add_tree_and_mode_points(v, quick);
  return v;
}

json config_names(const std::vector<SweepConfig>& configs) {
  json names = json::array();
  for (const SweepConfig& c : configs) names.push_back(c.name);
  return names;
}

// The scenes of the sweep's points by (leaf size, float nodes), one per example, with the recorded
// poses in each: built before the workers start.
struct SweepScenes {
  using Key = std::pair<int, int>;
  static Key key_of(const SweepConfig& c) {
    return std::make_pair(c.leaf_size, static_cast<int>(c.float_nodes));
  }
  std::map<Key, std::vector<std::unique_ptr<MeshScene>>> scenes;
  std::map<Key, std::vector<std::vector<Pose>>> poses;
};

SweepScenes sweep_scenes(const std::vector<SweepConfig>& configs,
                         const std::vector<std::size_t>& mine, const std::vector<Example>& ex,
                         const std::vector<Recording>& recs) {
  SweepScenes out;
  for (std::size_t i : mine) {
    const SweepConfig& c = configs[i];
    auto& sc = out.scenes[SweepScenes::key_of(c)];
    if (!sc.empty()) continue;
    ObbTreeOptions to;
    to.leaf_size = c.leaf_size;
    for (std::size_t e = 0; e < ex.size(); ++e) {
      sc.push_back(std::make_unique<MeshScene>(ex[e].scene, to));
      if (c.float_nodes != FloatNodes::kNone) {
        const bool pad = c.float_nodes == FloatNodes::kPadded;
        sc.back()->transform_trees([pad](const ObbTree& t) { return t.rounded_to_float(pad); });
      }
      out.poses[SweepScenes::key_of(c)].push_back(recorded_poses(*sc.back(), recs[e]));
    }
  }
  return out;
}

// A sweep point equal to a Table 1 method on the default trees: Table 1's replays serve it.
bool reuses_table(const SweepConfig& c, const ReplayCache& cache) {
  return !c.table_method.empty() && cache.count(c.table_method) && c.leaf_size == 1 &&
         c.float_nodes == FloatNodes::kNone;
}

// The replays of the points in `mine` that Table 1 does not serve, `o.jobs` at a time (slowest
// families first): [index into mine][example].
std::vector<std::vector<ReplayStats>> replay_points(const StudyOptions& o,
                                                    const std::vector<SweepConfig>& configs,
                                                    const std::vector<std::size_t>& mine,
                                                    const std::vector<Example>& ex,
                                                    const std::vector<Recording>& recs,
                                                    SweepScenes& scenes, const ReplayCache& cache,
                                                    const Log& log) {
  std::vector<std::pair<std::size_t, std::size_t>> jobs;  // (index into mine, example)
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t k = 0; k < mine.size(); ++k) {
      const SweepConfig& c = configs[mine[k]];
      if (reuses_table(c, cache)) continue;
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
    const SweepScenes::Key key = SweepScenes::key_of(c);
    const Clock::time_point start = Clock::now();
    const auto querier = c.make();
    fresh[k][e] =
        replay(*scenes.scenes[key][e], scenes.poses[key][e], recs[e].steps(), *querier, o.repeats);
    const std::lock_guard<std::mutex> lock(log_mutex);
    ++done;
    log("sweep (" + std::to_string(done) + "/" + std::to_string(jobs.size()) + "): " + c.name +
        " on " + ex[e].name + ": median " + fmt(median(fresh[k][e].total_ns) / 1e6, 3) + " ms (" +
        fmt(seconds_since(start), 1) + " s)");
  });
  return fresh;
}

// One sweep point against CGAL: its replays of every example (`stats`), summed.
json point_json(const SweepConfig& c, std::size_t index, bool reuse,
                const std::vector<const ReplayStats*>& stats, const std::vector<Example>& ex,
                const std::vector<Recording>& recs, const std::vector<Answers>& truths,
                const std::vector<std::unique_ptr<MeshScene>>& sc) {
  // The timed repeats every example has: --repeats, or fewer for a point that Table 1's
  // perceptron cells serve (StudyOptions::perceptron_repeats).
  std::size_t repeats = stats.empty() ? 0 : stats.front()->total_ns.size();
  for (const ReplayStats* st : stats) repeats = std::min(repeats, st->total_ns.size());
  std::vector<double> totals(repeats, 0.0);
  ErrorStats sum;
  double position_weighted = 0;
  json per = json::array();
  QueryCounters counters;
  for (std::size_t e = 0; e < ex.size(); ++e) {
    const ReplayStats& st = *stats[e];
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
  j["index"] = index;
  j["repeats"] = repeats;
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
  return j;
}

}  // namespace

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
  SweepScenes scenes = sweep_scenes(configs, mine, ex, recs);
  // The replays, `jobs` at a time, then the comparison with CGAL.
  const std::vector<std::vector<ReplayStats>> fresh =
      replay_points(o, configs, mine, ex, recs, scenes, cache, log);
  json results = json::array();
  for (std::size_t k = 0; k < mine.size(); ++k) {
    const SweepConfig& c = configs[mine[k]];
    const bool reuse = reuses_table(c, cache);
    std::vector<const ReplayStats*> stats;
    for (std::size_t e = 0; e < ex.size(); ++e)
      stats.push_back(reuse ? &cache.at(c.table_method)[e] : &fresh[k][e]);
    results.push_back(point_json(c, mine[k], reuse, stats, ex, recs, truths,
                                 scenes.scenes[SweepScenes::key_of(c)]));
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

}  // namespace graspcd::study
