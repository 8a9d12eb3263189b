// Core micro-benchmarks: ns per SAT box test and per triangle-triangle test, each variant timed
// on the same seeded inputs in the same run (compare as ratios). Every benchmark also reports a
// hash of its answers ("answers") so a timing run shows that the variants agreed.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "core/obb.h"
#include "core/sat.h"
#include "core/tree_query.h"
#include "core/tritri.h"
#include "support/meshes.h"
#include "support/random_geometry.h"

namespace graspcd {
namespace {

constexpr int kInputs = 1 << 16;

// Random box pairs of size ~1 with the centre distance drawn so that `overlap_share` of them
// roughly overlap.
std::vector<std::pair<Obb, Obb>> make_box_pairs(double spread, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.1, 1.0), c(-spread, spread);
  std::vector<std::pair<Obb, Obb>> pairs(kInputs);
  for (auto& [a, b] : pairs) {
    a.axes = testing::random_rotation(rng);
    b.axes = testing::random_rotation(rng);
    a.half = Vec3(u(rng), u(rng), u(rng));
    b.half = Vec3(u(rng), u(rng), u(rng));
    b.center = Vec3(c(rng), c(rng), c(rng));
  }
  return pairs;
}

// Triangle pairs of size ~1 cm whose centres are within `spread` (hit rate ~40 % at 0.01).
std::vector<std::pair<Triangle, Triangle>> make_triangle_pairs(double spread, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-0.01, 0.01), c(-spread, spread);
  std::vector<std::pair<Triangle, Triangle>> pairs(kInputs);
  for (auto& [a, b] : pairs) {
    const Vec3 offset(c(rng), c(rng), c(rng));
    for (Vec3& v : a.v) v = Vec3(u(rng), u(rng), u(rng));
    for (Vec3& v : b.v) v = offset + Vec3(u(rng), u(rng), u(rng));
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
BENCHMARK_TEMPLATE(BM_TriTri, tri_tri_intersect_exact)
    ->Name("BM_TriTri/predicates_only")
    ->Arg(10)
    ->Arg(30);

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
