// Our tree query against FCL on the same coherent pose sequences: ns per mesh-mesh query for
// graspcd (sat, sat-cached; all contacts and first contact) and FCL 0.7 (OBB and RSS trees, the
// same two modes), and the time to build each tree. Compare within one run, as ratios.
//
// FCL: J. Pan, S. Chitta, D. Manocha, "FCL: A General Purpose Library for Collision and Proximity
// Queries", IEEE ICRA 2012. OBB trees: S. Gottschalk, M. C. Lin, D. Manocha, "OBBTree: A
// Hierarchical Structure for Rapid Interference Detection", SIGGRAPH 1996.
//
// Scenes: finger_C against cup.obj (mjcf/meshes, always) and the real mug against cube_cup_hi
// (../shared/models, when present). Run:
//   graspcd_fcl_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/obb_tree.h"
#include "core/separators.h"
#include "core/tree_query.h"
#include "io/mesh_io.h"
#include "peer/fcl_peer.h"
#include "support/random_geometry.h"

namespace graspcd {
namespace {

constexpr int kSteps = 512;           // poses per trajectory, replayed cyclically
constexpr double kStepAngle = 0.003;  // rad per step: the paper's grasp step

// A mesh pair: A at the identity, B placed by the poses. The trajectories are computed on first
// use (setup, outside the timed loop).
struct Scene {
  std::string name;
  TriangleMesh a, b;
  ObbTree ta, tb;
  std::unique_ptr<peer::FclMesh> fa_obb, fb_obb, fa_rss, fb_rss;
  // contact[i]: the offset along `dir` at which B, turned to step i, first touches A coming from
  // far away (the last offset our query answers "intersect", to 40 bisections).
  std::vector<double> contact;
  std::vector<Mat3> rotation;
  Vec3 dir;          // the approach direction, in A's frame
  double scale = 0;  // A's size: twice its root box's largest half-extent

  Scene(std::string scene_name, TriangleMesh mesh_a, TriangleMesh mesh_b)
      : name(std::move(scene_name)),
        a(std::move(mesh_a)),
        b(std::move(mesh_b)),
        ta(ObbTree::build(a)),
        tb(ObbTree::build(b)),
        fa_obb(std::make_unique<peer::FclMesh>(a, peer::FclBv::kObb)),
        fb_obb(std::make_unique<peer::FclMesh>(b, peer::FclBv::kObb)),
        fa_rss(std::make_unique<peer::FclMesh>(a, peer::FclBv::kRss)),
        fb_rss(std::make_unique<peer::FclMesh>(b, peer::FclBv::kRss)) {}

  Pose pose_at(int step, double s) const {
    Pose p;
    p.R = rotation[static_cast<std::size_t>(step)];
    p.t = ta.root().box.center - p.R * tb.root().box.center + s * dir;
    return p;
  }

  // B turns by kStepAngle a step about a fixed random axis, and approaches along a fixed random
  // direction; for each step the first contact along that direction is found by a scan from
  // outside inwards and bisection.
  void make_trajectory() {
    if (!contact.empty()) return;
    testing::Rng rng(5);
    const Mat3 r0 = testing::random_rotation(rng);
    const Vec3 axis = testing::random_unit_vector(rng);
    dir = testing::random_unit_vector(rng);
    scale = 2 * ta.root().box.half.maxCoeff();
    const double reach = 2 * (ta.root().box.half.norm() + tb.root().box.half.norm());
    const auto hits = [&](int step, double s) {
      SatSeparator sat;
      QueryCounters counters;
      return collide(ta, tb, pose_at(step, s), QueryMode::kFirstContact, sat, counters).intersect;
    };
    for (int i = 0; i < kSteps; ++i) {
      rotation.push_back(Eigen::AngleAxisd(kStepAngle * i, axis).toRotationMatrix() * r0);
      // At `reach` B's bounding sphere is clear of A's; scan inwards (through A's centre and
      // beyond) in steps of reach / 256 for the first offset that intersects.
      double hi = reach, lo = reach;
      bool found = false;
      for (int k = 1; k <= 512 && !found; ++k) {
        const double s = reach * (1 - k / 256.0);
        found = hits(i, s);
        (found ? lo : hi) = s;
      }
      if (!found) {
        std::fprintf(stderr, "%s: B never touches A along the direction\n", name.c_str());
        std::exit(1);
      }
      for (int k = 0; k < 40; ++k) {
        const double mid = 0.5 * (lo + hi);
        (hits(i, mid) ? lo : hi) = mid;
      }
      contact.push_back(lo);
    }
  }

  // The trajectory at a distance class: B at `gap` x scale beyond the first contact (0: touching,
  // negative: overlapping).
  std::vector<Pose> poses(double gap) {
    make_trajectory();
    std::vector<Pose> out;
    for (int i = 0; i < kSteps; ++i) {
      out.push_back(pose_at(i, contact[static_cast<std::size_t>(i)] + gap * scale));
    }
    return out;
  }
};

enum class Who { kOursSat, kOursSatCached, kFclObb, kFclRss };

const char* who_name(Who w) {
  switch (w) {
    case Who::kOursSat:
      return "ours-sat";
    case Who::kOursSatCached:
      return "ours-sat-cached";
    case Who::kFclObb:
      return "fcl-obb";
    case Who::kFclRss:
      return "fcl-rss";
  }
  return "?";
}

// ns per query along one trajectory, replayed cyclically (one jump back to the start every
// kSteps queries; the cached detector keeps its state throughout). Counters, from one extra
// untimed pass over the whole trajectory after the timed loop, so they are the same for every
// method up to FCL's rounding at touching poses: share of poses intersecting and pairs per pose;
// for ours also box and triangle tests per pose.
void BM_Query(benchmark::State& state, Scene* scene, Who who, bool first_contact, double gap) {
  const std::vector<Pose> poses = scene->poses(gap);
  Detector detector(who == Who::kOursSatCached ? Method::kSatCached : Method::kSat);
  const QueryMode mode = first_contact ? QueryMode::kFirstContact : QueryMode::kAllContacts;
  const bool ours = who == Who::kOursSat || who == Who::kOursSatCached;
  const peer::FclMesh& fa = who == Who::kFclRss ? *scene->fa_rss : *scene->fa_obb;
  const peer::FclMesh& fb = who == Who::kFclRss ? *scene->fb_rss : *scene->fb_obb;
  QueryCounters counters;
  // One query: (intersect, pairs).
  const auto query = [&](const Pose& pose) -> std::pair<bool, std::uint64_t> {
    if (ours) {
      const QueryResult r = detector.collide(scene->ta, scene->tb, pose, mode, counters);
      return {r.intersect, r.pair_count};
    }
    const peer::FclQueryResult r = peer::fcl_collide(fa, fb, pose, first_contact);
    return {r.intersect, r.pair_count};
  };
  std::size_t i = 0;
  for (auto _ : state) {
    const auto r = query(poses[i++ % poses.size()]);
    benchmark::DoNotOptimize(r);
  }
  counters = QueryCounters{};
  std::uint64_t hits = 0, pairs = 0;
  for (const Pose& pose : poses) {
    const auto [hit, count] = query(pose);
    hits += hit;
    pairs += count;
  }
  const double n = static_cast<double>(poses.size());
  state.counters["hit_share"] = static_cast<double>(hits) / n;
  state.counters["pairs"] = static_cast<double>(pairs) / n;
  if (ours) {
    state.counters["box_tests"] = static_cast<double>(counters.box_tests) / n;
    state.counters["tri_tests"] = static_cast<double>(counters.tri_tests) / n;
  }
}

// Tree build from the mesh: ours (covariance fit, one triangle a leaf) and FCL's.
void BM_Build(benchmark::State& state, const TriangleMesh* mesh, int who) {
  for (auto _ : state) {
    if (who == 0) {
      const ObbTree tree = ObbTree::build(*mesh);
      benchmark::DoNotOptimize(tree.nodes().data());
    } else {
      const peer::FclMesh m(*mesh, who == 1 ? peer::FclBv::kObb : peer::FclBv::kRss);
      benchmark::DoNotOptimize(&m);
    }
  }
  state.counters["faces"] = static_cast<double>(mesh->faces.size());
}

// One OBB test, ours (SAT, core/sat.h) against FCL's fcl::obbDisjoint, on the same 65,536 random
// box pairs: A at the identity, B rotated uniformly with its centre at a distance uniform in
// [lo, hi] times the sum of the two boxes' half-diagonals (disjoint-heavy: [0.6, 1.2];
// overlap-heavy: [0, 0.6]). Each iteration tests the next pair (cycling); "disjoint" counts the
// answers, which must agree between the two (the pairs are random: no touching ones, where rounding
// differs).
struct BoxPairSet {
  std::vector<Obb> a, b;
  double disjoint_ours = 0, disjoint_fcl = 0;
};

BoxPairSet make_box_pairs(double lo, double hi, std::uint64_t seed) {
  testing::Rng rng(seed);
  BoxPairSet set;
  for (int i = 0; i < 65536; ++i) {
    Obb a = testing::random_box(rng, Vec3::Zero(), 0.2, 1.0);
    a.axes = Mat3::Identity();
    Obb b = testing::random_box(rng, Vec3::Zero(), 0.2, 1.0);
    const double reach = a.half.norm() + b.half.norm();
    b.center = testing::random_unit_vector(rng) * reach * testing::uniform(rng, lo, hi);
    set.disjoint_ours += sat_separating_axis(a, b) != kSatNoAxis;
    set.disjoint_fcl += peer::fcl_obb_disjoint(b.axes, b.center, a.half, b.half);
    set.a.push_back(a);
    set.b.push_back(b);
  }
  return set;
}

void BM_ObbTest(benchmark::State& state, const BoxPairSet* set, bool fcl) {
  std::size_t i = 0;
  const std::size_t n = set->a.size();
  for (auto _ : state) {
    const Obb& a = set->a[i];
    const Obb& b = set->b[i];
    const bool disjoint = fcl ? peer::fcl_obb_disjoint(b.axes, b.center, a.half, b.half)
                              : sat_separating_axis(a, b) != kSatNoAxis;
    benchmark::DoNotOptimize(disjoint);
    i = i + 1 == n ? 0 : i + 1;
  }
  state.counters["disjoint_share"] =
      (fcl ? set->disjoint_fcl : set->disjoint_ours) / static_cast<double>(n);
  state.counters["answers_differ"] = std::fabs(set->disjoint_fcl - set->disjoint_ours);
}

// With --benchmark_repetitions, min and max over the repetitions beside Google Benchmark's mean,
// median and stddev.
double min_of(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }
double max_of(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }
void add_min_max(benchmark::internal::Benchmark* b) {
  b->ComputeStatistics("min", min_of)->ComputeStatistics("max", max_of);
}

std::vector<std::unique_ptr<Scene>> load_scenes() {
  std::vector<std::unique_ptr<Scene>> scenes;
  const std::filesystem::path meshes(GRASPCD_MESHES_DIR);
  scenes.push_back(std::make_unique<Scene>("finger_C-cup",
                                           io::load_mesh((meshes / "cup.obj").string()),
                                           io::load_mesh((meshes / "finger_C.obj").string())));
  const std::filesystem::path real = std::filesystem::path(GRASPCD_MODELS_DIR) / "objects/mujoco";
  if (std::filesystem::exists(real / "mug.obj") &&
      std::filesystem::exists(real / "cube_cup_hi.obj")) {
    TriangleMesh mug = io::load_mesh((real / "mug.obj").string());
    for (Vec3& v : mug.vertices) v *= 0.01;  // centimetres to metres (models/README)
    scenes.push_back(std::make_unique<Scene>(
        "mug-cube_cup_hi", io::load_mesh((real / "cube_cup_hi.obj").string()), std::move(mug)));
  } else {
    std::fprintf(stderr, "note: real models not found at %s; the cup/mug scene is skipped\n",
                 real.string().c_str());
  }
  return scenes;
}

}  // namespace
}  // namespace graspcd

int main(int argc, char** argv) {
  using namespace graspcd;
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  const BoxPairSet disjoint_heavy = make_box_pairs(0.6, 1.2, 11);
  const BoxPairSet overlap_heavy = make_box_pairs(0.0, 0.6, 12);
  for (const auto& [label, set] :
       {std::pair<const char*, const BoxPairSet*>{"disjoint-heavy", &disjoint_heavy},
        {"overlap-heavy", &overlap_heavy}}) {
    for (const bool fcl : {false, true}) {
      const std::string name = std::string("BM_ObbTest/") + label + (fcl ? "/fcl" : "/ours");
      add_min_max(benchmark::RegisterBenchmark(name.c_str(), BM_ObbTest, set, fcl));
    }
  }
  const std::vector<std::unique_ptr<Scene>> scenes = load_scenes();
  // Distance classes as a fraction of A's size, as BM_BoxPair in core_bench.cpp.
  const std::pair<const char*, double> gaps[] = {
      {"far", 1.0}, {"near", 0.1}, {"very_near", 0.01}, {"touching", 0.0}, {"overlap", -0.2}};
  for (const auto& scene : scenes) {
    for (const auto& [gap_name, gap] : gaps) {
      for (const bool first : {false, true}) {
        for (const Who who : {Who::kOursSat, Who::kOursSatCached, Who::kFclObb, Who::kFclRss}) {
          const std::string name = "BM_Query/" + scene->name + "/" + gap_name + "/" +
                                   (first ? "first/" : "all/") + who_name(who);
          add_min_max(
              benchmark::RegisterBenchmark(name.c_str(), BM_Query, scene.get(), who, first, gap));
        }
      }
    }
    const std::pair<const char*, const TriangleMesh*> meshes[] = {{"a", &scene->a},
                                                                  {"b", &scene->b}};
    for (const auto& [which, mesh] : meshes) {
      for (int who = 0; who < 3; ++who) {
        const char* who_label = who == 0 ? "ours" : (who == 1 ? "fcl-obb" : "fcl-rss");
        const std::string name = "BM_Build/" + scene->name + "/" + which + "/" + who_label;
        add_min_max(benchmark::RegisterBenchmark(name.c_str(), BM_Build, mesh, who)
                        ->Unit(benchmark::kMillisecond));
      }
    }
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
