#include "graspcd/study/replay.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "graspcd/core/clock.h"
#include "graspcd/exact/exact.h"

namespace graspcd::study {

namespace {

class DetectorQuerier : public Querier {
 public:
  DetectorQuerier(Method method, const DetectorOptions& options, QueryMode mode)
      : method_(method), options_(options), mode_(mode) {}
  void reset(std::size_t pairs) override {
    detectors_.clear();
    for (std::size_t i = 0; i < pairs; ++i) detectors_.emplace_back(method_, options_);
  }
  QueryResult query(std::size_t index, const MeshPair&, const ObbTree& a, const ObbTree& b,
                    const Pose& b_in_a, std::vector<TrianglePair>* out,
                    QueryCounters& counters) override {
    return detectors_[index].collide(a, b, b_in_a, mode_, counters, out);
  }

 private:
  Method method_;
  DetectorOptions options_;
  QueryMode mode_;
  std::vector<Detector> detectors_;
};

// The contact position of a (step, pair): the mean of the centroids of every intersecting
// triangle pair (both triangles, B posed into A's frame), in geom1's frame.
Vec3 contact_position(const MeshScene& scene, const MeshPair& pair, const Pose& pose,
                      const std::vector<TrianglePair>& tri_pairs) {
  Vec3 sum = Vec3::Zero();
  const auto& fa = scene.faces(pair.mesh1);
  const auto& fb = scene.faces(pair.mesh2);
  for (const TrianglePair& tp : tri_pairs) {
    const Triangle& ta = fa[static_cast<std::size_t>(tp.a)];
    const Triangle tb = apply_pose(pose, fb[static_cast<std::size_t>(tp.b)]);
    const Vec3 c = (ta.v[0] + ta.v[1] + ta.v[2] + tb.v[0] + tb.v[1] + tb.v[2]) / 6.0;
    sum += c;
  }
  return sum / static_cast<double>(tri_pairs.size());
}

}  // namespace

std::unique_ptr<Querier> make_detector_querier(Method method, const DetectorOptions& options,
                                               QueryMode mode) {
  return std::make_unique<DetectorQuerier>(method, options, mode);
}

void Answers::finish() {
  Fnv1a hits;
  Fnv1a all;
  for (std::size_t i = 0; i < hit.size(); ++i) {
    hits.add(hit[i]);
    all.add(hit[i]);
    auto& v = tri_pairs[i];
    std::sort(v.begin(), v.end());
    const std::uint64_t n = v.size();
    all.add(n);
    for (const TrianglePair& p : v) {
      all.add(p.a);
      all.add(p.b);
    }
  }
  hit_hash = hits.value();
  pairs_hash = all.value();
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::vector<Pose> recorded_poses(const MeshScene& scene, const Recording& recording) {
  std::vector<Pose> poses;
  poses.reserve(static_cast<std::size_t>(recording.steps()) * scene.pairs().size());
  for (int s = 0; s < recording.steps(); ++s) {
    for (const MeshPair& p : scene.pairs()) poses.push_back(scene.pose(recording, s, p));
  }
  return poses;
}

ReplayStats replay(const MeshScene& scene, const Recording& recording, Querier& querier,
                   int repeats, const std::function<void(int)>& progress) {
  return replay(scene, recorded_poses(scene, recording), recording.steps(), querier, repeats,
                progress);
}

ReplayStats replay(const MeshScene& scene, const std::vector<Pose>& poses, int steps,
                   Querier& querier, int repeats, const std::function<void(int)>& progress) {
  const auto& pairs = scene.pairs();
  const std::size_t np = pairs.size();
  if (poses.size() != static_cast<std::size_t>(steps) * np)
    throw std::invalid_argument("replay: poses do not match steps x pairs");
  ReplayStats stats;
  stats.answers.pairs = np;
  stats.answers.hit.assign(static_cast<std::size_t>(steps) * np, 0);
  stats.answers.tri_pairs.assign(static_cast<std::size_t>(steps) * np, {});
  stats.step_counters.assign(static_cast<std::size_t>(steps), QueryCounters{});
  std::vector<std::vector<TrianglePair>> scratch(np);
  std::vector<std::uint8_t> hits(np);
  for (int r = 0; r < repeats; ++r) {
    querier.reset(np);
    std::vector<double> step_ns(static_cast<std::size_t>(steps));
    double total = 0;
    for (int s = 0; s < steps; ++s) {
      QueryCounters counters;
      for (auto& v : scratch) v.clear();
      const Pose* step_poses = &poses[static_cast<std::size_t>(s) * np];
      const Clock::time_point start = Clock::now();
      for (std::size_t i = 0; i < np; ++i) {
        const MeshPair& p = pairs[i];
        // A non-finite pose (a simulation gone bad): no query, no contact, counted.
        if (!finite_pose(step_poses[i])) {
          hits[i] = 0;
          if (r == 0) ++stats.nonfinite_skips;
          continue;
        }
        hits[i] = querier
                      .query(i, p, scene.tree(p.mesh1), scene.tree(p.mesh2), step_poses[i],
                             &scratch[i], counters)
                      .intersect;
      }
      const double ns = static_cast<double>(elapsed_ns(start));
      step_ns[static_cast<std::size_t>(s)] = ns;
      total += ns;
      if (r == 0) {
        for (std::size_t i = 0; i < np; ++i) {
          const std::size_t k = static_cast<std::size_t>(s) * np + i;
          stats.answers.hit[k] = hits[i];
          stats.answers.tri_pairs[k] = scratch[i];
        }
        stats.step_counters[static_cast<std::size_t>(s)] = counters;
        stats.counters += counters;
      }
    }
    stats.step_ns.push_back(std::move(step_ns));
    stats.total_ns.push_back(total);
    if (progress) progress(r + 1);
  }
  stats.answers.finish();
  return stats;
}

Answers exact_answers(const MeshScene& scene, const Recording& recording) {
  const auto& pairs = scene.pairs();
  Answers a;
  a.pairs = pairs.size();
  const std::size_t n = static_cast<std::size_t>(recording.steps()) * pairs.size();
  a.hit.assign(n, 0);
  a.tri_pairs.assign(n, {});
  for (int s = 0; s < recording.steps(); ++s) {
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const MeshPair& p = pairs[i];
      const Pose pose = scene.pose(recording, s, p);
      if (!finite_pose(pose)) continue;  // skipped as replay() skips it: no contact
      std::vector<Triangle> b = scene.faces(p.mesh2);
      for (Triangle& t : b) t = apply_pose(pose, t);
      const std::size_t k = static_cast<std::size_t>(s) * pairs.size() + i;
      a.tri_pairs[k] = exact::mesh_mesh_pairs(scene.faces(p.mesh1), b);
      a.hit[k] = !a.tri_pairs[k].empty();
    }
  }
  a.finish();
  return a;
}

std::vector<int> first_contact_steps(const MeshScene& scene, const Answers& answers, int steps) {
  std::vector<int> first(grasp::finger_segment_names().size(), -1);
  const auto& pairs = scene.pairs();
  for (int s = 0; s < steps; ++s) {
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const int seg = pairs[i].segment;
      if (seg < 0 || first[static_cast<std::size_t>(seg)] >= 0) continue;
      if (answers.hit[static_cast<std::size_t>(s) * pairs.size() + i])
        first[static_cast<std::size_t>(seg)] = s + 1;
    }
  }
  return first;
}

ErrorStats compare(const MeshScene& scene, const Recording& recording, const Answers& answers,
                   const Answers& truth, bool first_contact) {
  ErrorStats e;
  const auto& pairs = scene.pairs();
  const int steps = recording.steps();
  double position_sum = 0;
  std::uint64_t positions = 0;
  for (int s = 0; s < steps; ++s) {
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const std::size_t k = static_cast<std::size_t>(s) * pairs.size() + i;
      if (truth.hit[k] && !answers.hit[k]) ++e.missed;
      if (!truth.hit[k] && answers.hit[k]) ++e.false_contacts;
      if (truth.hit[k] && answers.hit[k]) {
        // Both sorted: count the set differences.
        const auto& want = truth.tri_pairs[k];
        const auto& got = answers.tri_pairs[k];
        std::size_t a = 0;
        std::size_t b = 0;
        while (a < want.size() || b < got.size()) {
          if (b == got.size() || (a < want.size() && want[a] < got[b])) {
            if (!first_contact) ++e.missed_tri_pairs;
            ++a;
          } else if (a == want.size() || got[b] < want[a]) {
            ++e.false_tri_pairs;
            ++b;
          } else {
            ++a;
            ++b;
          }
        }
      }
      if (truth.hit[k] && answers.hit[k] && !answers.tri_pairs[k].empty()) {
        const Pose pose = scene.pose(recording, s, pairs[i]);
        const Vec3 want = contact_position(scene, pairs[i], pose, truth.tri_pairs[k]);
        const Vec3 got = contact_position(scene, pairs[i], pose, answers.tri_pairs[k]);
        const double d = (want - got).norm();
        e.position_error_max = std::max(e.position_error_max, d);
        position_sum += d;
        ++positions;
      }
    }
  }
  e.position_error_mean = positions ? position_sum / static_cast<double>(positions) : 0.0;
  const std::vector<int> got = first_contact_steps(scene, answers, steps);
  const std::vector<int> want = first_contact_steps(scene, truth, steps);
  for (std::size_t j = 0; j < got.size(); ++j) {
    if (got[j] == want[j]) continue;
    // A segment one of them never saw in contact counts from the end of the recording.
    const int g = got[j] < 0 ? steps + 1 : got[j];
    const int w = want[j] < 0 ? steps + 1 : want[j];
    const int d = std::abs(g - w);
    e.first_contact_error_max = std::max(e.first_contact_error_max, d);
    e.first_contact_error_sum += d;
  }
  return e;
}

}  // namespace graspcd::study
