// Core micro-benchmarks: ns per SAT box test and per triangle-triangle test, each variant timed
// on the same seeded inputs in the same run (compare as ratios). Every benchmark also reports a
// hash of its answers ("answers") so a timing run shows that the variants agreed.
#include <benchmark/benchmark.h>

#include <random>
#include <string>
#include <vector>

#include "graspcd/core/obb.h"
#include "graspcd/core/sat.h"
#include "graspcd/core/separators.h"
#include "graspcd/core/tree_query.h"
#include "graspcd/core/tritri.h"
#include "graspcd/support/meshes.h"
#include "graspcd/support/random_geometry.h"

namespace graspcd {
namespace {

constexpr int kInputs = 1 << 16;

// Random box pairs of size ~1 with the centre distance drawn so that `overlap_share` of them
// roughly overlap.
std::vector<std::pair<Obb, Obb>> make_box_pairs(double spread, std::uint64_t seed) {
  testing::Rng rng(seed);
  std::vector<std::pair<Obb, Obb>> pairs(kInputs);
  for (auto& [a, b] : pairs) {
    a.axes = testing::random_rotation(rng);
    b.axes = testing::random_rotation(rng);
    a.half = testing::uniform_vec3(rng, 0.1, 1.0);
    b.half = testing::uniform_vec3(rng, 0.1, 1.0);
    b.center = testing::uniform_vec3(rng, -spread, spread);
  }
  return pairs;
}

// Triangle pairs of size ~1 cm whose centres are within `spread` (hit rate ~40 % at 0.01).
std::vector<std::pair<Triangle, Triangle>> make_triangle_pairs(double spread, std::uint64_t seed) {
  testing::Rng rng(seed);
  std::vector<std::pair<Triangle, Triangle>> pairs(kInputs);
  for (auto& [a, b] : pairs) {
    const Vec3 offset = testing::uniform_vec3(rng, -spread, spread);
    for (Vec3& v : a.v) v = testing::uniform_vec3(rng, -0.01, 0.01);
    for (Vec3& v : b.v) v = offset + testing::uniform_vec3(rng, -0.01, 0.01);
  }
  return pairs;
}

void BM_Sat(benchmark::State& state) {
  const auto pairs = make_box_pairs(static_cast<double>(state.range(0)) / 10.0, 1);
  std::size_t i = 0;
  std::uint64_t hash = 0, separated = 0;
  for (auto _ : state) {
    const auto& [a, b] = pairs[i++ & (kInputs - 1)];
    const SatAxis axis = sat_separating_axis(a, b);
    benchmark::DoNotOptimize(axis);
    hash = hash * 31 + static_cast<std::uint64_t>(axis);
    separated += axis != kSatNoAxis;
  }
  state.counters["separated_share"] =
      static_cast<double>(separated) / static_cast<double>(state.iterations());
  state.counters["answers"] = static_cast<double>(hash % 1000003);
}
// Centre spread 4.0 (mostly disjoint) and 1.0 (mostly overlapping).
BENCHMARK(BM_Sat)->Arg(40)->Arg(10);

template <bool (*Test)(const Triangle&, const Triangle&)>
void BM_TriTri(benchmark::State& state) {
  const auto pairs = make_triangle_pairs(static_cast<double>(state.range(0)) / 1000.0, 2);
  std::size_t i = 0;
  std::uint64_t hits = 0;
  for (auto _ : state) {
    const auto& [a, b] = pairs[i++ & (kInputs - 1)];
    const bool hit = Test(a, b);
    benchmark::DoNotOptimize(hit);
    hits += hit;
  }
  state.counters["hit_rate"] = static_cast<double>(hits) / static_cast<double>(state.iterations());
}
// Centre spread 10 mm (~30-40 % hits) and 30 mm (mostly disjoint).
BENCHMARK_TEMPLATE(BM_TriTri, tri_tri_intersect)->Name("BM_TriTri/exact_moller")->Arg(10)->Arg(30);
BENCHMARK_TEMPLATE(BM_TriTri, tri_tri_moller_plain)
    ->Name("BM_TriTri/plain_moller")
    ->Arg(10)
    ->Arg(30);
BENCHMARK_TEMPLATE(BM_TriTri, tri_tri_moller_naive)
    ->Name("BM_TriTri/naive_moller")
    ->Arg(10)
    ->Arg(30);
BENCHMARK_TEMPLATE(BM_TriTri, tri_tri_intersect_predicates)
    ->Name("BM_TriTri/predicates_only")
    ->Arg(10)
    ->Arg(30);

// Box pairs along a slow trajectory, at a fixed distance class: B turns by 0.003 rad a step (the
// paper's grasp step) about a fixed axis, and is re-placed each step so that its lowest vertex
// along a unit direction n lies `gap_fraction` x (A's size) beyond A's highest vertex along n.
// So the boxes' true distance is exactly that gap (0: touching at one vertex; negative:
// overlapping). Boxes of ~2 cm at 0.3 m from the origin: grasp scale. Consecutive calls are
// coherent, so the cached and warm methods are measured as a grasp would use them.
std::vector<std::pair<Obb, Obb>> make_trajectory(double gap_fraction, std::uint64_t seed) {
  testing::Rng rng(seed);
  Obb a;
  a.center = Vec3(0.3, -0.1, 0.2);
  a.axes = testing::random_rotation(rng);
  a.half = Vec3(0.01, 0.008, 0.006);
  Obb b;
  b.half = Vec3(0.012, 0.007, 0.005);
  const Mat3 b0 = testing::random_rotation(rng);
  const Vec3 n = testing::random_unit(rng);
  const Vec3 axis = testing::random_unit(rng);
  // The corner of `box` furthest along `dir`, relative to its centre.
  const auto extreme = [](const Obb& box, const Vec3& dir) -> Vec3 {
    const Vec3 s = (box.axes.transpose() * dir).cwiseSign();
    return box.axes * s.cwiseProduct(box.half);
  };
  const Vec3 top_a = a.center + extreme(a, n);
  std::vector<std::pair<Obb, Obb>> steps(4096);
  for (std::size_t i = 0; i < steps.size(); ++i) {
    b.axes = Eigen::AngleAxisd(0.003 * static_cast<double>(i), axis).toRotationMatrix() * b0;
    b.center = top_a + gap_fraction * 2 * a.half.maxCoeff() * n - extreme(b, -n);
    steps[i] = {a, b};
  }
  return steps;
}

// ns per box test for one method at one gap class; counters: perceptron passes per call, share
// proven disjoint, SAT fallbacks and cache hits per call.
void BM_BoxPair(benchmark::State& state, Method method, double gap_fraction) {
  const auto steps = make_trajectory(gap_fraction, 3);
  Detector detector(method);
  QueryCounters counters;
  std::size_t i = 0;
  std::uint64_t disjoint = 0;
  for (auto _ : state) {
    const auto& [a, b] = steps[i++ % steps.size()];
    const bool d = detector.box_disjoint(a, b, counters);
    benchmark::DoNotOptimize(d);
    disjoint += d;
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["passes"] = static_cast<double>(counters.perceptron_passes) / n;
  state.counters["disjoint"] = static_cast<double>(disjoint) / n;
  state.counters["sat_fallbacks"] = static_cast<double>(counters.sat_fallbacks) / n;
  state.counters["cache_hits"] = static_cast<double>(counters.cache_hits) / n;
}

// Distance classes as a fraction of the box size: far (1.0), near (0.1), very near (0.01),
// touching (0) and overlapping (-0.2).
const int kBoxPairBenchmarks = [] {
  const std::pair<const char*, double> gaps[] = {
      {"far", 1.0}, {"near", 0.1}, {"very_near", 0.01}, {"touching", 0.0}, {"overlap", -0.2}};
  for (Method m : all_methods()) {
    for (const auto& [gap_name, gap] : gaps) {
      const std::string name = std::string("BM_BoxPair/") + method_name(m) + "/" + gap_name;
      benchmark::RegisterBenchmark(name.c_str(), BM_BoxPair, m, gap);
    }
  }
  return 0;
}();

// Tree query: two 3,968-triangle spheres (radius 5 cm) at a 0.5 mm gap and at 1 mm overlap.
void BM_SphereSpheres(benchmark::State& state) {
  const TriangleMesh sphere = testing::make_uv_sphere(0.05, 32, 64);
  const ObbTree tree = ObbTree::build(sphere);
  const double gap = static_cast<double>(state.range(0)) * 1e-4;  // metres
  Pose pose;
  pose.t = Vec3(0.1 + gap, 0, 0);
  const QueryMode mode = state.range(1) ? QueryMode::kAllContacts : QueryMode::kFirstContact;
  QueryCounters counters;
  std::uint64_t pairs = 0;
  for (auto _ : state) {
    SatSeparator sat;
    const QueryResult r = collide(tree, tree, pose, mode, sat, counters);
    pairs = r.pair_count;
  }
  state.counters["box_tests"] =
      static_cast<double>(counters.box_tests) / static_cast<double>(state.iterations());
  state.counters["tri_tests"] =
      static_cast<double>(counters.tri_tests) / static_cast<double>(state.iterations());
  state.counters["pairs"] = static_cast<double>(pairs);
}
BENCHMARK(BM_SphereSpheres)
    ->Args({5, 0})
    ->Args({-10, 0})
    ->Args({-10, 1})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace graspcd

BENCHMARK_MAIN();
