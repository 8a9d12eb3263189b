// Timed replays of recorded grasps: every method answers the same queries, the poses of a
// Recording, and is timed per grasp step; its answers are kept and hashed so that a timing run also
// proves that the methods agreed, and compared with CGAL's ground truth (src/graspcd/exact) for the
// error sweep.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "graspcd/core/separators.h"
#include "graspcd/core/tree_query.h"
#include "graspcd/study/recording.h"

namespace graspcd::study {

// A collision method as the replay sees it: one query per (grasp step, pair). State carried from
// step to step (caches, warm planes) lives in the querier, per pair, and reset() forgets it.
class Querier {
 public:
  virtual ~Querier() = default;
  // Fresh state for `pairs` pairs (called before every timed repeat).
  virtual void reset(std::size_t pairs) = 0;
  // The query of pair `index` with tree b placed in a's frame; `out` receives the intersecting
  // triangle pairs (face ids) when the mode finds them.
  virtual QueryResult query(std::size_t index, const MeshPair& pair, const ObbTree& a,
                            const ObbTree& b, const Pose& b_in_a, std::vector<TrianglePair>* out,
                            QueryCounters& counters) = 0;
};

// A Detector (core/separators.h) per pair, as a served pair has.
std::unique_ptr<Querier> make_detector_querier(Method method, const DetectorOptions& options,
                                               QueryMode mode);

// Direct tree queries with a separator policy and a triangle test policy (the sweep's variants).
template <class Separator, class TriTest>
class PolicyQuerier : public Querier {
 public:
  PolicyQuerier(Separator prototype, QueryMode mode) : prototype_(prototype), mode_(mode) {}
  void reset(std::size_t pairs) override { separators_.assign(pairs, prototype_); }
  QueryResult query(std::size_t index, const MeshPair&, const ObbTree& a, const ObbTree& b,
                    const Pose& b_in_a, std::vector<TrianglePair>* out,
                    QueryCounters& counters) override {
    return graspcd::collide(a, b, b_in_a, mode_, separators_[index], counters, out, TriTest{});
  }

 private:
  Separator prototype_;
  QueryMode mode_;
  std::vector<Separator> separators_;
};

// The answers of one method over a recording: per (step, pair), step-major.
struct Answers {
  std::size_t pairs = 0;
  std::vector<std::uint8_t> hit;
  std::vector<std::vector<TrianglePair>> tri_pairs;  // sorted; empty in first-contact mode
  std::uint64_t hit_hash = 0;                        // FNV-1a of the hit flags
  std::uint64_t pairs_hash = 0;                      // FNV-1a of hit flags and triangle pairs

  void finish();  // sorts the triangle pairs and computes the hashes
};

struct ReplayStats {
  std::vector<std::vector<double>> step_ns;  // [repeat][step], the queries of the step
  std::vector<double> total_ns;              // [repeat]
  QueryCounters counters;                    // of the first repeat
  std::vector<QueryCounters> step_counters;  // [step], of the first repeat
  Answers answers;                           // of the first repeat
  // (step, pair) queries skipped because the pose held a NaN or an infinity (no contact).
  std::uint64_t nonfinite_skips = 0;
};

// The pose of every (step, pair) of a recording, step-major: what replay() feeds the queries.
std::vector<Pose> recorded_poses(const MeshScene& scene, const Recording& recording);

// Times `repeats` replays of `recording` on `scene` with `querier` (reset before each), the poses
// computed before the clock starts. `progress` (may be empty) is called after each repeat.
ReplayStats replay(const MeshScene& scene, const Recording& recording, Querier& querier,
                   int repeats, const std::function<void(int)>& progress = {});
// The same with the poses given (recorded_poses): touches no shared mutable state, so replays of
// the same scene may run on several threads at once.
ReplayStats replay(const MeshScene& scene, const std::vector<Pose>& poses, int steps,
                   Querier& querier, int repeats, const std::function<void(int)>& progress = {});

// CGAL's answers (exact::mesh_mesh_pairs, all pairs) on the same doubles: the ground truth.
Answers exact_answers(const MeshScene& scene, const Recording& recording);

// Errors of `answers` against `truth`.
struct ErrorStats {
  std::uint64_t missed = 0;  // (step, pair) the truth says intersect, the method not
  std::uint64_t false_contacts = 0;
  // Triangle pairs, where both found the (step, pair) intersecting: pairs the truth has and the
  // answers miss (none are expected in first-contact mode, which reports one pair), and pairs
  // the answers have that the truth does not.
  std::uint64_t missed_tri_pairs = 0;
  std::uint64_t false_tri_pairs = 0;
  int first_contact_error_max = 0;  // grasp steps, over the finger segments
  int first_contact_error_sum = 0;
  double position_error_max = 0;  // metres, contact position (see contact_position)
  double position_error_mean = 0;
};
// `first_contact`: the answers come from first-contact mode (one triangle pair per hit), so
// missing triangle pairs are not errors.
ErrorStats compare(const MeshScene& scene, const Recording& recording, const Answers& answers,
                   const Answers& truth, bool first_contact);

// The first grasp step (1-based) at which each finger segment has an intersecting pair, -1 never.
std::vector<int> first_contact_steps(const MeshScene& scene, const Answers& answers, int steps);

// The median of a sample (the mean of the two middle values for an even count).
double median(std::vector<double> v);

}  // namespace graspcd::study
