#include "graspcd/study/box_hand.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <vector>

#include "graspcd/core/clock.h"
#include "graspcd/exact/exact.h"
#include "graspcd/study/replay.h"

namespace graspcd::study {

namespace {

using json = nlohmann::json;

constexpr int kBoxHandCap = 10000;  // the paper's box hand (docs/design.md "Semantics")

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

// The box hand's object boxes at every grasp step, with CGAL's answer and Novikoff's bound per
// (step, pair), indexed step * pairs + pair.
struct BoxHandSteps {
  std::vector<Obb> boxes2;
  std::vector<double> bound;
  std::vector<std::uint8_t> overlap;  // the exact answer (CGAL)
};

BoxHandSteps box_hand_steps(const BoxScene& scene, const Recording& rec) {
  BoxHandSteps d;
  for (int s = 0; s < rec.steps(); ++s) {
    for (const BoxPair& p : scene.pairs()) {
      d.boxes2.push_back(scene.box2(rec, s, p));
      const Obb& b = d.boxes2.back();
      d.bound.push_back(novikoff_bound(p.box1, b, exact::box_box_gap(p.box1, b)));
      d.overlap.push_back(exact::box_box_overlap(p.box1, b));
    }
  }
  return d;
}

struct BoxHandMethod {
  std::string name;
  Method method;
  DetectorOptions options;
};

// One method's replays of the box hand: [kind][repeat][step] ns; from the first repeat,
// [kind][step] passes, the hash of the disjoint answers and their count against CGAL's.
struct BoxReplay {
  std::map<char, std::vector<std::vector<double>>> ns;
  std::map<char, std::vector<double>> passes;
  Fnv1a answers;
  std::uint64_t false_separated = 0;  // "disjoint" for boxes CGAL says overlap: never allowed
  std::uint64_t unproven = 0;         // "may overlap" for boxes CGAL says disjoint: costs only
};

BoxReplay replay_box_method(const BoxHandMethod& bm, const std::vector<BoxPair>& pairs,
                            const BoxHandSteps& d, int steps, int repeats) {
  BoxReplay out;
  std::vector<std::uint8_t> disjoint(pairs.size(), 0);
  for (int r = 0; r < repeats; ++r) {
    std::vector<Detector> detectors;
    for (std::size_t i = 0; i < pairs.size(); ++i) detectors.emplace_back(bm.method, bm.options);
    for (char kind : {'B', 'C'}) out.ns[kind].emplace_back(static_cast<std::size_t>(steps), 0.0);
    for (int s = 0; s < steps; ++s) {
      const std::size_t row = static_cast<std::size_t>(s) * pairs.size();
      for (char kind : {'B', 'C'}) {
        QueryCounters c;
        const Clock::time_point start = Clock::now();
        for (std::size_t i = 0; i < pairs.size(); ++i) {
          if (pairs[i].kind != kind) continue;
          disjoint[i] = detectors[i].box_disjoint(pairs[i].box1, d.boxes2[row + i], c);
        }
        out.ns[kind][static_cast<std::size_t>(r)][static_cast<std::size_t>(s)] =
            static_cast<double>(elapsed_ns(start));
        if (r != 0) continue;
        out.passes[kind].push_back(static_cast<double>(c.perceptron_passes));
        for (std::size_t i = 0; i < pairs.size(); ++i) {
          if (pairs[i].kind != kind) continue;
          out.answers.add(disjoint[i]);
          const bool truth = d.overlap[row + i];
          out.false_separated += disjoint[i] && truth;
          out.unproven += !disjoint[i] && !truth;
        }
      }
    }
  }
  return out;
}

// Per segment kind: the median time of each grasp step over the repeats, the passes, and the
// timing of the totals.
json segments_json(const BoxReplay& replay, int steps) {
  json kinds;
  for (char kind : {'B', 'C'}) {
    const auto& ns = replay.ns.at(kind);
    std::vector<double> med(static_cast<std::size_t>(steps));
    std::vector<double> totals;
    for (int s = 0; s < steps; ++s) {
      std::vector<double> v;
      for (const auto& rep : ns) v.push_back(rep[static_cast<std::size_t>(s)]);
      med[static_cast<std::size_t>(s)] = median(v);
    }
    for (const auto& rep : ns) {
      double t = 0;
      for (double x : rep) t += x;
      totals.push_back(t);
    }
    const auto passes = replay.passes.find(kind);
    kinds[std::string(1, kind)] = {
        {"step_ns_median", med},
        {"passes", passes == replay.passes.end() ? std::vector<double>{} : passes->second},
        {"total", timing_json(totals)}};
  }
  return kinds;
}

// Per step and segment kind: the largest finite Novikoff bound and the number of pairs in
// contact (no finite bound).
json bounds_json(const std::vector<BoxPair>& pairs, const std::vector<double>& bound, int steps) {
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
  return bounds;
}

}  // namespace

json run_box_hand(const StudyOptions& o, const Recording& rec, const Log& log) {
  const BoxScene scene(rec.scene, "BC");
  const auto& pairs = scene.pairs();
  const int steps = rec.steps();
  const BoxHandSteps d = box_hand_steps(scene, rec);
  DetectorOptions perceptron;
  perceptron.cap = kBoxHandCap;
  const std::vector<BoxHandMethod> methods = {{"sat", Method::kSat, {}},
                                              {"perceptron", Method::kPerceptron, perceptron},
                                              {"neurosat", Method::kNeuroSat, {}}};
  json out_methods = json::array();
  bool any_false_separated = false;
  for (const BoxHandMethod& bm : methods) {
    const BoxReplay r = replay_box_method(bm, pairs, d, steps, o.repeats);
    any_false_separated = any_false_separated || r.false_separated > 0;
    out_methods.push_back({{"name", bm.name},
                           {"cap", bm.options.cap},
                           {"switch", bm.options.switch_passes},
                           {"segments", segments_json(r, steps)},
                           {"false_separated", r.false_separated},
                           {"unproven_disjoint", r.unproven},
                           {"answer_hash", hex64(r.answers.value())}});
    log("figures 13-15: box hand " + bm.name + " replayed (" + std::to_string(steps) +
        " grasp steps, " + std::to_string(pairs.size()) + " box pairs)");
  }
  std::uint64_t overlapping = 0;
  for (std::uint8_t v : d.overlap) overlapping += v;
  return {{"scene", rec.scene},
          {"steps", steps},
          {"pairs", pairs.size()},
          {"methods", out_methods},
          {"bounds", bounds_json(pairs, d.bound, steps)},
          {"box_tests", d.overlap.size()},
          {"overlapping_exact", overlapping},
          {"no_false_separated", !any_false_separated}};
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

}  // namespace graspcd::study
