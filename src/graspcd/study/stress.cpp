#include "graspcd/study/stress.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>

#include "graspcd/core/tolerances.h"
#include "graspcd/core/tritri.h"
#include "graspcd/exact/exact.h"
#include "graspcd/study/stress_cases.h"
#include "graspcd/version/envelope.h"

namespace graspcd::study {
namespace {

// The cases' generators (stress_cases.h).
using stress_cases::ClassId;
using stress_cases::make_box_case;
using stress_cases::make_triangle_case;
using stress_cases::Rng;

// ---- The classes ------------------------------------------------------------------------------

const std::vector<StressClass> kClasses = {
    {"box_scale", StressKind::kBoxes,
     "sizes 1e-4..1e4 m near the origin; vertex-face or edge-edge contact, gap +-1e-9..1e-1 of "
     "the size or touching",
     15000},
    {"box_far", StressKind::kBoxes,
     "sizes 1e-4..1e4 m, 1e-3..1e5 m from the origin; contacts and gaps as box_scale", 15000},
    {"box_parallel_faces", StressKind::kBoxes,
     "face on face, B turned 1e-12..1e-3 rad from A's axes; gaps as box_scale", 10000},
    {"box_parallel_edges", StressKind::kBoxes,
     "edge across edge at 1e-12..1e-3 rad (separated only by their cross-product axis)", 20000},
    {"box_sliver", StressKind::kBoxes,
     "slivers and flat boxes: half-extents of aspect 1e6, some zero; contacts as box_scale", 10000},
    {"box_gap", StressKind::kBoxes,
     "size 0.1..10 m: touching, or gap/penetration +-1e-9..1e-6 of the size; vertex-face, "
     "edge-edge, parallel faces",
     15000},
    {"tri_scale", StressKind::kTriangles,
     "sizes 1e-4..1e4 m near the origin; vertex-face or edge-edge contact, gap +-1e-9..1e-1 or "
     "touching",
     200000},
    {"tri_far", StressKind::kTriangles,
     "sizes 1e-4..1e4 m, 1e-3..1e5 m from the origin; contacts and gaps as tri_scale", 200000},
    {"tri_parallel_edges", StressKind::kTriangles,
     "edge across edge at 1e-12..1e-3 rad, gaps as tri_scale", 200000},
    {"tri_coplanar", StressKind::kTriangles,
     "exactly coplanar (vertex or edge against an edge, in-plane gap) and parallel planes at a "
     "tiny distance",
     200000},
    {"tri_near_coplanar", StressKind::kTriangles,
     "planes 1e-12..1e-3 rad apart: in-plane contact tilted, or overlapping triangles crossing "
     "near their common centre",
     200000},
    {"tri_sliver", StressKind::kTriangles,
     "slivers of aspect 1e6: a vertex on a sliver, a needle on a face, crossing sliver edges",
     200000},
    {"tri_degenerate", StressKind::kTriangles,
     "zero-area triangles: repeated vertices and collinear points (segments), three equal "
     "vertices (points), against triangles and segments",
     200000},
    {"tri_gap", StressKind::kTriangles,
     "size 0.1..10 m: touching, or gap/penetration +-1e-9..1e-6 of the size", 200000},
};

// Each class its own stream: splitmix64 of (seed, class) seeds the engine.
Rng class_rng(std::size_t index, std::uint64_t seed) {
  std::uint64_t z = seed * 0x9E3779B97F4A7C15ull + (index + 1) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return Rng(z ^ (z >> 31));
}

ClassId class_id(std::size_t index, StressKind kind) {
  if (index >= kClasses.size() || kClasses[index].kind != kind) {
    throw std::invalid_argument("stress: class index out of range or of the other kind");
  }
  return static_cast<ClassId>(index);
}

// ---- Evaluation -------------------------------------------------------------------------------

// The pair's size for relative gaps: the scale kSatRelativeSlack multiplies.
double pair_size(const Obb& a, const Obb& b) {
  return a.half.sum() + b.half.sum() + (b.center - a.center).lpNorm<1>();
}

// The slack of sat.h as tolerances.h documents it: an axis separates only when its gap
// (unnormalised, metres times |L|) exceeds it.
double sat_slack(const Obb& a, const Obb& b) {
  return tol::kSatRelativeSlack * pair_size(a, b) +
         tol::kSatRoundoffFactor * (a.center.lpNorm<1>() + b.center.lpNorm<1>());
}

// True when the exact gap on each of the 15 SAT axes (unnormalised, as sat.cpp measures it) is
// at most sat_slack plus the rounding of the SAT's own arithmetic (kSatRoundoffFactor times the
// pair's size): a "may overlap" the documented slack explains.
bool within_sat_band(const Obb& a, const Obb& b) {
  const double band = sat_slack(a, b) + tol::kSatRoundoffFactor * pair_size(a, b);
  for (int axis = 1; axis <= 15; ++axis) {
    if (exact::sat_axis_gap(a, b, axis) > band) return false;
  }
  return true;
}

void run_box_class(std::size_t index, int count, std::uint64_t seed,
                   const std::vector<BoxMethod>& methods, std::vector<StressRow>& rows) {
  const std::vector<BoxPairCase> cases = make_box_cases(index, count, seed);
  std::vector<char> truth(cases.size());
  for (std::size_t c = 0; c < cases.size(); ++c) {
    truth[c] = exact::box_box_overlap(cases[c].a, cases[c].b);
  }
  // Per case, computed the first time a method needs it.
  std::vector<std::optional<double>> gap_rel(cases.size());
  std::vector<std::optional<bool>> in_band(cases.size());
  for (const BoxMethod& m : methods) {
    StressRow row;
    row.class_name = kClasses[index].name;
    row.kind = StressKind::kBoxes;
    row.method = m.name;
    row.reference = m.reference;
    for (std::size_t c = 0; c < cases.size(); ++c) {
      const BoxPairCase& pair = cases[c];
      const BoxAnswer answer = m.test(pair.a, pair.b);
      ++row.cases;
      row.overlapping += truth[c];
      row.perceptron_capped += answer.capped;
      if (truth[c] && answer.disjoint) ++row.false_separated;
      if (truth[c] || answer.disjoint) continue;
      ++row.false_overlap;
      if (!gap_rel[c]) gap_rel[c] = exact::box_box_gap(pair.a, pair.b) / pair_size(pair.a, pair.b);
      row.max_false_overlap_gap_rel = std::max(row.max_false_overlap_gap_rel, *gap_rel[c]);
      if (m.sat_band) {
        if (!in_band[c]) in_band[c] = within_sat_band(pair.a, pair.b);
        if (!*in_band[c]) ++row.outside_band;
      }
    }
    rows.push_back(row);
  }
}

void run_triangle_class(std::size_t index, int count, std::uint64_t seed,
                        const std::vector<TriangleMethod>& methods, std::vector<StressRow>& rows) {
  const std::vector<TrianglePairCase> cases = make_triangle_cases(index, count, seed);
  std::vector<char> truth(cases.size());
  for (std::size_t c = 0; c < cases.size(); ++c) {
    truth[c] = exact::tri_tri_intersect(cases[c].t1, cases[c].t2);
  }
  for (const TriangleMethod& m : methods) {
    StressRow row;
    row.class_name = kClasses[index].name;
    row.kind = StressKind::kTriangles;
    row.method = m.name;
    row.reference = m.reference;
    for (std::size_t c = 0; c < cases.size(); ++c) {
      const bool answer = m.intersect(cases[c].t1, cases[c].t2);
      ++row.cases;
      row.overlapping += truth[c];
      if (truth[c] && !answer) ++row.false_separated;
      if (!truth[c] && answer) ++row.false_overlap;
    }
    row.outside_band = row.false_overlap;  // the triangle tests are exact: no band
    rows.push_back(row);
  }
}

int cases_for(const StressClass& cls, const StressOptions& options) {
  if (options.cases > 0) return options.cases;
  return options.quick ? std::max(50, cls.default_cases / 50) : cls.default_cases;
}

std::string format_double(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

}  // namespace

const std::vector<StressClass>& stress_classes() { return kClasses; }

std::vector<BoxPairCase> make_box_cases(std::size_t index, int count, std::uint64_t seed) {
  const ClassId id = class_id(index, StressKind::kBoxes);
  Rng rng = class_rng(index, seed);
  std::vector<BoxPairCase> cases;
  cases.reserve(static_cast<std::size_t>(std::max(count, 0)));
  for (int i = 0; i < count; ++i) cases.push_back(make_box_case(id, rng));
  return cases;
}

std::vector<TrianglePairCase> make_triangle_cases(std::size_t index, int count,
                                                  std::uint64_t seed) {
  const ClassId id = class_id(index, StressKind::kTriangles);
  Rng rng = class_rng(index, seed);
  std::vector<TrianglePairCase> cases;
  cases.reserve(static_cast<std::size_t>(std::max(count, 0)));
  for (int i = 0; i < count; ++i) cases.push_back(make_triangle_case(id, rng));
  return cases;
}

std::vector<BoxMethod> default_box_methods(const DetectorOptions& options) {
  std::vector<BoxMethod> methods;
  for (const Method m : all_methods()) {
    BoxMethod bm;
    bm.name = method_name(m);
    const bool neurosat = m == Method::kNeuroSat || m == Method::kNeuroSatSticky;
    bm.sat_band = m == Method::kSat || m == Method::kSatCached || neurosat;
    const int limit = neurosat ? options.switch_passes : options.cap;
    DetectorOptions fresh = options;
    fresh.cache_slots = 1;  // a fresh detector per case: no state to carry
    bm.test = [m, fresh, limit](const Obb& a, const Obb& b) {
      Detector detector(m, fresh);
      QueryCounters counters;
      BoxAnswer answer;
      answer.disjoint = detector.box_disjoint(a, b, counters);
      answer.capped =
          uses_perceptron(m) && counters.perceptron_passes >= static_cast<std::uint64_t>(limit);
      return answer;
    };
    methods.push_back(std::move(bm));
  }
  return methods;
}

std::vector<TriangleMethod> default_triangle_methods() {
  return {
      {"tri_tri_intersect",
       [](const Triangle& a, const Triangle& b) { return tri_tri_intersect(a, b); }},
      // tri_tri_intersect_predicates under its 0.1 label, so stress.json stays comparable.
      {"tri_tri_intersect_exact",
       [](const Triangle& a, const Triangle& b) { return tri_tri_intersect_predicates(a, b); }},
      {"moller_naive",
       [](const Triangle& a, const Triangle& b) { return tri_tri_moller_naive(a, b); }, true},
      {"moller_plain",
       [](const Triangle& a, const Triangle& b) { return tri_tri_moller_plain(a, b); }, true},
  };
}

bool StressReport::contract_broken() const {
  return std::any_of(rows.begin(), rows.end(), [](const StressRow& r) {
    return !r.reference && (r.false_separated > 0 || r.outside_band > 0);
  });
}

StressReport run_stress(const StressOptions& options,
                        const std::function<void(const std::string&)>& log) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<BoxMethod> box_methods =
      options.box_methods.empty() ? default_box_methods() : options.box_methods;
  const std::vector<TriangleMethod> triangle_methods =
      options.triangle_methods.empty() ? default_triangle_methods() : options.triangle_methods;
  StressReport report;
  report.seed = options.seed;
  report.quick = options.quick;
  for (const std::string& name : options.classes) {
    if (std::none_of(kClasses.begin(), kClasses.end(),
                     [&](const StressClass& cls) { return name == cls.name; })) {
      throw std::invalid_argument("stress: no class named '" + name + "'");
    }
  }
  for (std::size_t index = 0; index < kClasses.size(); ++index) {
    const StressClass& cls = kClasses[index];
    if (!options.classes.empty() && std::find(options.classes.begin(), options.classes.end(),
                                              cls.name) == options.classes.end()) {
      continue;
    }
    const int count = cases_for(cls, options);
    const auto class_start = std::chrono::steady_clock::now();
    if (cls.kind == StressKind::kBoxes) {
      run_box_class(index, count, options.seed, box_methods, report.rows);
    } else {
      run_triangle_class(index, count, options.seed, triangle_methods, report.rows);
    }
    if (log) {
      const std::chrono::duration<double> took = std::chrono::steady_clock::now() - class_start;
      log(std::string(cls.name) + ": " + std::to_string(count) + " cases, " +
          format_double(took.count()) + " s");
    }
  }
  const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
  report.seconds = took.count();
  return report;
}

std::string stress_table(const StressReport& report) {
  const std::vector<std::string> header = {"class",
                                           "method",
                                           "cases",
                                           "overlapping",
                                           "false_separated",
                                           "false_overlap",
                                           "max_false_overlap_gap_rel",
                                           "outside_band",
                                           "perceptron_capped"};
  std::vector<std::vector<std::string>> lines = {header};
  for (const StressRow& r : report.rows) {
    const bool boxes = r.kind == StressKind::kBoxes;
    lines.push_back(
        {r.class_name, r.reference ? r.method + " (reference)" : r.method, std::to_string(r.cases),
         std::to_string(r.overlapping), std::to_string(r.false_separated),
         std::to_string(r.false_overlap), boxes ? format_double(r.max_false_overlap_gap_rel) : "-",
         std::to_string(r.outside_band), boxes ? std::to_string(r.perceptron_capped) : "-"});
  }
  std::vector<std::size_t> width(header.size(), 0);
  for (const auto& line : lines) {
    for (std::size_t k = 0; k < line.size(); ++k) width[k] = std::max(width[k], line[k].size());
  }
  std::ostringstream out;
  for (const auto& line : lines) {
    for (std::size_t k = 0; k < line.size(); ++k) {
      // Names left-aligned, numbers right-aligned.
      const std::size_t pad = width[k] - line[k].size();
      if (k < 2) {
        out << line[k] << std::string(pad, ' ');
      } else {
        out << std::string(pad, ' ') << line[k];
      }
      out << (k + 1 < line.size() ? "  " : "\n");
    }
  }
  return out.str();
}

std::string stress_json(const StressReport& report) {
  using nlohmann::json;
  json classes = json::array();
  for (const StressClass& cls : kClasses) {
    classes.push_back({{"name", cls.name},
                       {"kind", cls.kind == StressKind::kBoxes ? "boxes" : "triangles"},
                       {"description", cls.description}});
  }
  json rows = json::array();
  for (const StressRow& r : report.rows) {
    const bool boxes = r.kind == StressKind::kBoxes;
    rows.push_back(
        {{"class", r.class_name},
         {"kind", boxes ? "boxes" : "triangles"},
         {"method", r.method},
         {"reference", r.reference},
         {"cases", r.cases},
         {"overlapping", r.overlapping},
         {"false_separated", r.false_separated},
         {"false_overlap", r.false_overlap},
         {"max_false_overlap_gap_rel", boxes ? json(r.max_false_overlap_gap_rel) : json(nullptr)},
         {"outside_band", r.outside_band},
         {"perceptron_capped", boxes ? json(r.perceptron_capped) : json(nullptr)}});
  }
  const json tolerances = {{"sat_relative_slack", tol::kSatRelativeSlack},
                           {"sat_roundoff_factor", tol::kSatRoundoffFactor},
                           {"perceptron_corner_factor", tol::kPerceptronCornerFactor},
                           {"perceptron_cap", tol::kPerceptronDefaultCap},
                           {"neurosat_switch", tol::kNeuroSatDefaultSwitch}};
  json j = {{"seed", report.seed},
            {"quick", report.quick},
            {"seconds", report.seconds},
            {"tolerances", tolerances},
            {"classes", classes},
            {"rows", rows},
            {"contract_broken", report.contract_broken()}};
  add_envelope(j);
  return j.dump(1) + "\n";
}

}  // namespace graspcd::study
