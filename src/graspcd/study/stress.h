// `graspcd stress`: the numerical stress suite. Seeded classes of box pairs and
// triangle pairs at the edges of double precision (sizes 1e-4 to 1e4 m, 1e-3 to 1e5 m from the
// origin, near-parallel faces and edges at 1e-12 to 1e-3 rad, coplanar and near-coplanar
// triangles, slivers of aspect 1e6, zero-area triangles and repeated vertices, touching pairs and
// gaps down to 1e-9 of the size), each answered by every method and judged by the exact twin
// (src/graspcd/exact, CGAL) on the doubles as generated.
//
// Every pair is built around a known contact (a vertex on a face, two crossing edges, two
// touching coplanar triangles) and the second object is then moved by a signed gap g along the
// contact's normal: g > 0 separates them, g < 0 makes them overlap, g = 0 touches, before the
// coordinates are rounded. The rounded doubles are the case; CGAL decides it, so a gap below what
// a double resolves at that distance still has one right answer.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "graspcd/core/geometry.h"
#include "graspcd/core/obb.h"
#include "graspcd/core/separators.h"
#include "graspcd/study/stress_pairs.h"

namespace graspcd::study {

// The cases (the classes and the pairs they generate): stress_pairs.h.

// ---- Methods under test ------------------------------------------------------------------------

struct BoxAnswer {
  bool disjoint = false;  // proven disjoint
  bool capped = false;    // a perceptron used all its passes (its cap, or Neuro-SAT's switch)
};

// A box-pair method: a name for the table and the test. `sat_band`: a "may overlap" of this
// method comes from sat_separating_axis, so every false overlap must lie within the SAT's slack
// (tolerances.h, kSatRelativeSlack and kSatRoundoffFactor) on all 15 axes. `reference`: a
// deliberately inexact variant, reported but exempt from the zero-false-separation contract (none
// of the box methods is one).
struct BoxMethod {
  std::string name;
  std::function<BoxAnswer(const Obb& a, const Obb& b)> test;
  bool sat_band = false;
  bool reference = false;
};

struct TriangleMethod {
  std::string name;
  std::function<bool(const Triangle& t1, const Triangle& t2)> intersect;
  bool reference = false;  // Moller's published epsilon and the epsilon-free variant
};

// Every method of all_methods(), each case on a fresh Detector (so the warm and cached methods
// start cold) with the given cap and switch.
std::vector<BoxMethod> default_box_methods(const DetectorOptions& options = {});

// The core's tri_tri_intersect and tri_tri_intersect_predicates, then the reference variants
// tri_tri_moller_naive and tri_tri_moller_plain (expected to disagree).
std::vector<TriangleMethod> default_triangle_methods();

// ---- The run -----------------------------------------------------------------------------------

struct StressOptions {
  std::uint64_t seed = 1;
  bool quick = false;                // a tenth of the default cases per class (at least 50)
  int cases = 0;                     // cases per class; 0: the class's default (or its quick share)
  std::vector<std::string> classes;  // only these classes (by name); empty: all
  std::vector<BoxMethod> box_methods;            // empty: default_box_methods()
  std::vector<TriangleMethod> triangle_methods;  // empty: default_triangle_methods()
};

// One (class, method) cell of the table.
struct StressRow {
  std::string class_name;
  StressKind kind = StressKind::kBoxes;
  std::string method;
  bool reference = false;
  std::int64_t cases = 0;
  std::int64_t overlapping = 0;      // the truth says overlap / intersect
  std::int64_t false_separated = 0;  // method: disjoint; truth: overlap (must be 0)
  std::int64_t false_overlap = 0;    // method: may overlap; truth: disjoint
  // Over the false overlaps of box methods: the largest exact::box_box_gap divided by the pair's
  // size (both boxes' half-extents summed plus |cB - cA|_1, the scale of kSatRelativeSlack); 0
  // when there is none, and for triangles (no exact distance is computed for them).
  double max_false_overlap_gap_rel = 0.0;
  // False overlaps outside the documented band (must be 0 for non-reference methods): for the
  // SAT family a gap on some axis larger than sat_slack plus the SAT's own rounding; for the
  // exact triangle tests every false overlap. Perceptron-only methods have no band to leave:
  // their "may overlap" is the cap or a refused margin (perceptron.h).
  std::int64_t outside_band = 0;
  std::int64_t perceptron_capped = 0;  // tests that used all their passes (any truth)
};

struct StressReport {
  std::uint64_t seed = 1;
  bool quick = false;
  std::vector<StressRow> rows;  // classes in stress_classes() order, methods in method order
  double seconds = 0.0;         // wall time of the run

  // True when a non-reference method separated an overlapping pair or left its band.
  bool contract_broken() const;
};

// Runs every class against every method. Progress lines (one per class) go to `log`.
StressReport run_stress(const StressOptions& options,
                        const std::function<void(const std::string&)>& log = {});

// The table as aligned text, one row per (class, method), with a header line.
std::string stress_table(const StressReport& report);

// The report as JSON: {"seed", "quick", "seconds", "classes": [{name, kind, description, cases}],
// "rows": [StressRow fields], "tolerances": {...}, "contract_broken"}.
std::string stress_json(const StressReport& report);

}  // namespace graspcd::study
