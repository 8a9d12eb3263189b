// Our tree query against FCL on the same coherent pose sequences: ns per mesh-mesh query for
// graspcd (sat, sat-cached; all contacts and first contact) and FCL 0.7 (OBB and RSS trees, the
// same two modes), and the time to build each tree. Compare within one run, as ratios.
// Bullet's GImpact is the second peer: btGImpactMeshShape against btGImpactMeshShape,
// double precision, margins 0 (src/graspcd/peer/gimpact_peer.h), on the same meshes and poses;
// "cgal_disagree" counts its answers (and everyone's) that differ from CGAL's exact one.
//
// GImpact: F. Leon, GIMPACT (2006), Bullet's concave mesh collision (btGImpactCollisionAlgorithm).
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
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "graspcd/core/obb_tree.h"
#include "graspcd/core/separators.h"
#include "graspcd/core/tolerances.h"
#include "graspcd/core/tree_query.h"
#include "graspcd/exact/exact.h"
#include "graspcd/io/mesh_io.h"
#include "graspcd/peer/fcl_peer.h"
#include "graspcd/peer/gimpact_peer.h"
#include "graspcd/support/meshes.h"
#include "graspcd/support/random_geometry.h"

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
  std::unique_ptr<peer::GimpactMesh> ga, gb;
  // CGAL's answer (the surfaces intersect) at every pose of a distance class, made on first use.
  std::map<double, std::vector<bool>> truth;
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
        fb_rss(std::make_unique<peer::FclMesh>(b, peer::FclBv::kRss)),
        ga(std::make_unique<peer::GimpactMesh>(a)),
        gb(std::make_unique<peer::GimpactMesh>(b)) {}

  // CGAL's exact brute force (first contact) at each pose of the distance class `gap`.
  const std::vector<bool>& cgal_truth(double gap) {
    auto& t = truth[gap];
    if (!t.empty()) return t;
    std::vector<Triangle> ta_tris;
    for (std::size_t f = 0; f < a.faces.size(); ++f) ta_tris.push_back(a.triangle(f));
    for (const Pose& p : poses(gap)) {
      t.push_back(!exact::mesh_mesh_pairs(ta_tris, posed_triangles(b, p), true).empty());
    }
    return t;
  }

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
    const Vec3 axis = testing::random_unit(rng);
    dir = testing::random_unit(rng);
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

enum class Who { kOursSat, kOursSatCached, kFclObb, kFclObbFront, kFclRss, kGimpact };

const char* who_name(Who w) {
  switch (w) {
    case Who::kOursSat:
      return "ours-sat";
    case Who::kOursSatCached:
      return "ours-sat-cached";
    case Who::kFclObb:
      return "fcl-obb";
    case Who::kFclObbFront:
      return "fcl-obb-front";
    case Who::kFclRss:
      return "fcl-rss";
    case Who::kGimpact:
      return "gimpact";
  }
  return "?";
}

// ns per query along one trajectory, replayed cyclically (one jump back to the start every
// kSteps queries; the cached detector and FCL's front list keep their state throughout). Counters,
// from one extra untimed pass over the whole trajectory after the timed loop, so they are the same
// for every method up to FCL's rounding at touching poses: share of poses intersecting and pairs
// per pose (GImpact: contact points per pose); for ours also box and triangle tests per pose; and
// the poses whose answer differs from CGAL's (cgal_disagree).
void BM_Query(benchmark::State& state, Scene* scene, Who who, bool first_contact, double gap) {
  const std::vector<Pose> poses = scene->poses(gap);
  Detector detector(who == Who::kOursSatCached ? Method::kSatCached : Method::kSat);
  const QueryMode mode = first_contact ? QueryMode::kFirstContact : QueryMode::kAllContacts;
  const bool ours = who == Who::kOursSat || who == Who::kOursSatCached;
  const peer::FclMesh& fa = who == Who::kFclRss ? *scene->fa_rss : *scene->fa_obb;
  const peer::FclMesh& fb = who == Who::kFclRss ? *scene->fb_rss : *scene->fb_obb;
  peer::FclFront front;
  peer::FclFront* front_list = who == Who::kFclObbFront ? &front : nullptr;
  peer::GimpactQuery gimpact;
  QueryCounters counters;
  std::uint64_t fcl_bv_tests = 0;
  // One query: (intersect, pairs).
  const auto query = [&](const Pose& pose) -> std::pair<bool, std::uint64_t> {
    if (ours) {
      const QueryResult r = detector.collide(scene->ta, scene->tb, pose, mode, counters);
      return {r.intersect, r.pair_count};
    }
    if (who == Who::kGimpact) {
      const peer::GimpactQueryResult r = gimpact.collide(*scene->ga, *scene->gb, pose);
      return {r.intersect, r.contacts};
    }
    const peer::FclQueryResult r =
        peer::fcl_collide(fa, fb, pose, first_contact, nullptr, front_list);
    fcl_bv_tests += r.bv_tests;
    return {r.intersect, r.pair_count};
  };
  std::size_t i = 0;
  for (auto _ : state) {
    const auto r = query(poses[i++ % poses.size()]);
    benchmark::DoNotOptimize(r);
  }
  counters = QueryCounters{};
  fcl_bv_tests = 0;
  std::uint64_t hits = 0, pairs = 0, cgal_disagree = 0;
  const std::vector<bool>& truth = scene->cgal_truth(gap);
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const auto [hit, count] = query(poses[k]);
    hits += hit;
    pairs += count;
    cgal_disagree += hit != truth[k];
  }
  const double n = static_cast<double>(poses.size());
  state.counters["hit_share"] = static_cast<double>(hits) / n;
  state.counters["cgal_disagree"] = static_cast<double>(cgal_disagree);
  state.counters["pairs"] = static_cast<double>(pairs) / n;
  if (who != Who::kGimpact) {
    state.counters["box_tests"] = static_cast<double>(ours ? counters.box_tests : fcl_bv_tests) / n;
  }
  if (ours) state.counters["tri_tests"] = static_cast<double>(counters.tri_tests) / n;
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
// overlap-heavy: [0, 0.6]). Each iteration tests the next pair (cycling). Both are given what
// FCL's test takes, B's axes and centre in A's frame and the half-extents: "ours" is
// sat_separating_axis_in_a with its slack computed per pair (as sat_separating_axis computes it
// for A at the identity); "ours-boxes" is sat_separating_axis on the two boxes, which also forms
// A^T B and A^T (cB - cA). "disjoint" counts the answers, which must agree between the three (the
// pairs are random: no touching ones, where the slack or rounding could differ).
struct BoxPairSet {
  std::vector<Obb> a, b;
  double disjoint_ours = 0, disjoint_fcl = 0;
};

enum class ObbTester { kOurs, kOursBoxes, kFcl };

bool obb_disjoint(ObbTester who, const Obb& a, const Obb& b) {
  switch (who) {
    case ObbTester::kOurs: {
      const double slack =
          tol::kSatRelativeSlack * (a.half.sum() + b.half.sum() + b.center.lpNorm<1>()) +
          tol::kSatRoundoffFactor * b.center.lpNorm<1>();
      return sat_separating_axis_in_a(b.axes, b.center, a.half, b.half, slack) != kSatNoAxis;
    }
    case ObbTester::kOursBoxes:
      return sat_separating_axis(a, b) != kSatNoAxis;
    case ObbTester::kFcl:
      return peer::fcl_obb_disjoint(b.axes, b.center, a.half, b.half);
  }
  return false;
}

BoxPairSet make_box_pairs(double lo, double hi, std::uint64_t seed) {
  testing::Rng rng(seed);
  BoxPairSet set;
  for (int i = 0; i < 65536; ++i) {
    Obb a = testing::random_box(rng, Vec3::Zero(), 0.2, 1.0);
    a.axes = Mat3::Identity();
    Obb b = testing::random_box(rng, Vec3::Zero(), 0.2, 1.0);
    const double reach = a.half.norm() + b.half.norm();
    const Vec3 dir = testing::random_unit(rng);
    b.center = dir * reach * testing::uniform(rng, lo, hi);
    const bool ours = obb_disjoint(ObbTester::kOurs, a, b);
    if (ours != obb_disjoint(ObbTester::kOursBoxes, a, b)) {
      std::fprintf(stderr, "BM_ObbTest: our two forms disagree on pair %d\n", i);
      std::exit(1);
    }
    set.disjoint_ours += ours;
    set.disjoint_fcl += obb_disjoint(ObbTester::kFcl, a, b);
    set.a.push_back(a);
    set.b.push_back(b);
  }
  return set;
}

void BM_ObbTest(benchmark::State& state, const BoxPairSet* set, ObbTester who) {
  std::size_t i = 0;
  const std::size_t n = set->a.size();
  for (auto _ : state) {
    const bool disjoint = obb_disjoint(who, set->a[i], set->b[i]);
    benchmark::DoNotOptimize(disjoint);
    i = i + 1 == n ? 0 : i + 1;
  }
  state.counters["disjoint_share"] =
      (who == ObbTester::kFcl ? set->disjoint_fcl : set->disjoint_ours) / static_cast<double>(n);
  state.counters["answers_differ"] = std::fabs(set->disjoint_fcl - set->disjoint_ours);
}

// Mesh against mesh: two UV spheres of radius 5 cm, A at the origin, B turned by a fixed random
// rotation and placed along a fixed random direction d. The gaps are measured from the meshes'
// own first contact along d (the largest centre distance s0 at which they intersect, to 50
// bisections): a near miss at s0 + 0.5 mm, overlaps at s0 - 1 mm and s0 - 10 mm, at every
// resolution. Every method of ours, the previous SAT descent ("ours-sat-transform": B's box
// placed and A^T B formed at every node pair, as before the RAPID-style descent), and FCL's
// BVHModel<OBBd>. Counters from one untimed query after the timed loop: box tests (FCL:
// num_bv_tests), pairs found, and "agrees": 1 when the answer is FCL's (all contacts: the same
// sorted pair list; first contact: the same yes/no).
struct SpherePair {
  TriangleMesh mesh;
  ObbTree tree;
  std::unique_ptr<peer::FclMesh> fcl;
  Mat3 rotation;
  Vec3 dir;
  double contact = 0;  // s0
  explicit SpherePair(int rings)
      : mesh(testing::make_uv_sphere(0.05, rings, 2 * rings)),
        tree(ObbTree::build(mesh)),
        fcl(std::make_unique<peer::FclMesh>(mesh, peer::FclBv::kObb)) {
    testing::Rng rng(17);
    rotation = testing::random_rotation(rng);
    dir = testing::random_unit(rng);
    // Convex solids: they overlap on an interval of s around 0; at 5 cm the surfaces cross, at
    // 10.01 cm (the circumscribed spheres apart) they do not.
    double lo = 0.05, hi = 0.1001;
    for (int k = 0; k < 50; ++k) {
      const double mid = 0.5 * (lo + hi);
      SatSeparator sat;
      QueryCounters counters;
      const bool hit =
          collide(tree, tree, pose(mid), QueryMode::kFirstContact, sat, counters).intersect;
      (hit ? lo : hi) = mid;
    }
    contact = lo;
  }
  Pose pose(double s) const {
    Pose p;
    p.R = rotation;
    p.t = s * dir;
    return p;
  }
};

// The sphere pair of `rings` rings, built on first use (outside any timed loop) and kept.
const SpherePair& sphere_pair(int rings) {
  static std::map<int, std::unique_ptr<SpherePair>> pairs;
  auto& p = pairs[rings];
  if (!p) p = std::make_unique<SpherePair>(rings);
  return *p;
}

struct PlainSatSeparator {  // the previous descent: no hint(), so collide() takes the generic one
  bool disjoint(const Obb& a, const Obb& b, std::int32_t, std::int32_t, QueryCounters&) {
    return sat_separating_axis(a, b) != kSatNoAxis;
  }
};

// who: a Method index, kTransform (the previous SAT descent), kFcl or kGimpact.
constexpr int kTransform = -1, kFcl = -2, kGimpact = -3;

// Mesh queries whose answer differed from FCL's: main() exits 1 when there were any.
int& disagreements() {
  static int n = 0;
  return n;
}

struct MeshRun {
  bool intersect = false;
  std::uint64_t box_tests = 0;
  std::uint64_t tri_tests = 0;  // ours only
};

// GImpact on the sphere pair: ns per query, contact points, and whether its answer is CGAL's
// (cgal_disagree 0 or 1). Not compared with FCL's pairs: GImpact reports contact points, not
// triangle pairs.
void BM_SpheresGimpact(benchmark::State& state, int rings, double gap) {
  const SpherePair* s = &sphere_pair(rings);
  const Pose pose = s->pose(s->contact + gap);
  const peer::GimpactMesh mesh(s->mesh);
  peer::GimpactQuery query;
  for (auto _ : state) {
    const peer::GimpactQueryResult r = query.collide(mesh, mesh, pose);
    benchmark::DoNotOptimize(r.intersect);
  }
  const peer::GimpactQueryResult r = query.collide(mesh, mesh, pose);
  std::vector<Triangle> tris;
  for (std::size_t f = 0; f < s->mesh.faces.size(); ++f) tris.push_back(s->mesh.triangle(f));
  const bool truth = !exact::mesh_mesh_pairs(tris, posed_triangles(s->mesh, pose), true).empty();
  state.counters["contacts"] = static_cast<double>(r.contacts);
  state.counters["cgal_disagree"] = r.intersect != truth ? 1 : 0;
  state.counters["faces"] = static_cast<double>(s->mesh.faces.size());
}

void BM_Spheres(benchmark::State& state, int rings, int who, double gap, bool first) {
  const SpherePair* s = &sphere_pair(rings);
  const Pose pose = s->pose(s->contact + gap);
  const QueryMode mode = first ? QueryMode::kFirstContact : QueryMode::kAllContacts;
  std::optional<Detector> detector;
  if (who >= 0) detector.emplace(all_methods()[static_cast<std::size_t>(who)]);
  PlainSatSeparator plain;
  const auto run = [&](std::vector<TrianglePair>* pairs) {
    MeshRun r;
    if (who == kFcl) {
      const peer::FclQueryResult f = peer::fcl_collide(*s->fcl, *s->fcl, pose, first, pairs);
      r.intersect = f.intersect;
      r.box_tests = f.bv_tests;
      return r;
    }
    QueryCounters c;
    r.intersect = who == kTransform
                      ? collide(s->tree, s->tree, pose, mode, plain, c, pairs).intersect
                      : detector->collide(s->tree, s->tree, pose, mode, c, pairs).intersect;
    r.box_tests = c.box_tests;
    r.tri_tests = c.tri_tests;
    return r;
  };
  for (auto _ : state) {
    const MeshRun r = run(nullptr);
    benchmark::DoNotOptimize(r.intersect);
  }
  std::vector<TrianglePair> my_pairs, fcl_pairs;
  const MeshRun mine = run(&my_pairs);
  const peer::FclQueryResult f = peer::fcl_collide(*s->fcl, *s->fcl, pose, first, &fcl_pairs);
  std::sort(my_pairs.begin(), my_pairs.end());
  std::sort(fcl_pairs.begin(), fcl_pairs.end());
  const bool agrees = first ? mine.intersect == f.intersect : my_pairs == fcl_pairs;
  if (!agrees) {
    disagreements() += 1;
    state.SkipWithError("the answer differs from FCL's");
  }
  state.counters["box_tests"] = static_cast<double>(mine.box_tests);
  state.counters["pairs"] = static_cast<double>(my_pairs.size());
  if (who != kFcl) state.counters["tri_tests"] = static_cast<double>(mine.tri_tests);
  state.counters["agrees"] = agrees ? 1 : 0;
  state.counters["faces"] = static_cast<double>(s->mesh.faces.size());
}

std::string mesh_who_name(int who) {
  if (who == kFcl) return "fcl-obb";
  if (who == kTransform) return "ours-sat-transform";
  return std::string("ours-") + method_name(all_methods()[static_cast<std::size_t>(who)]);
}

// Tree build on UV spheres of about n triangles (the meshes of the scaling series): ours
// (covariance fit, one triangle a leaf) and FCL's OBB build.
void BM_BuildScale(benchmark::State& state, int rings, bool fcl) {
  const TriangleMesh* mesh = &sphere_pair(rings).mesh;
  for (auto _ : state) {
    if (fcl) {
      const peer::FclMesh m(*mesh, peer::FclBv::kObb);
      benchmark::DoNotOptimize(&m);
    } else {
      const ObbTree tree = ObbTree::build(*mesh);
      benchmark::DoNotOptimize(tree.nodes().data());
    }
  }
  state.counters["faces"] = static_cast<double>(mesh->faces.size());
}

// Rings of a UV sphere with about n triangles (4 rings (rings - 1) of them).
int rings_for(double n) { return std::max(4, static_cast<int>(std::lround(std::sqrt(n) / 2))); }

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
  benchmark::AddCustomContext("graspcd_build", GRASPCD_BUILD_DESCRIPTION);
  const BoxPairSet disjoint_heavy = make_box_pairs(0.6, 1.2, 11);
  const BoxPairSet overlap_heavy = make_box_pairs(0.0, 0.6, 12);
  for (const auto& [label, set] :
       {std::pair<const char*, const BoxPairSet*>{"disjoint-heavy", &disjoint_heavy},
        {"overlap-heavy", &overlap_heavy}}) {
    for (const auto& [who_label, who] :
         {std::pair<const char*, ObbTester>{"ours", ObbTester::kOurs},
          {"ours-boxes", ObbTester::kOursBoxes},
          {"fcl", ObbTester::kFcl}}) {
      const std::string name = std::string("BM_ObbTest/") + label + "/" + who_label;
      add_min_max(benchmark::RegisterBenchmark(name.c_str(), BM_ObbTest, set, who));
    }
  }
  // Two 3,968-triangle spheres (32 rings), and the scaling series 1e2 to 1e6 triangles, built on
  // first use (the largest take seconds), so only the sizes a filter selects pay for theirs.
  const std::pair<const char*, double> sphere_gaps[] = {
      {"near_miss_0.5mm", 5e-4}, {"overlap_1mm", -1e-3}, {"overlap_10mm", -1e-2}};
  std::vector<int> whos;
  for (std::size_t m = 0; m < all_methods().size(); ++m) whos.push_back(static_cast<int>(m));
  whos.push_back(kTransform);
  whos.push_back(kFcl);
  for (const auto& [gap_name, gap] : sphere_gaps) {
    for (const bool first : {true, false}) {
      for (const int who : whos) {
        const std::string name = std::string("BM_Spheres/3968/") + gap_name +
                                 (first ? "/first/" : "/all/") + mesh_who_name(who);
        add_min_max(benchmark::RegisterBenchmark(name.c_str(), BM_Spheres, 32, who, gap, first)
                        ->Unit(benchmark::kMicrosecond));
      }
    }
    const std::string name = std::string("BM_Spheres/3968/") + gap_name + "/all/gimpact";
    add_min_max(benchmark::RegisterBenchmark(name.c_str(), BM_SpheresGimpact, 32, gap)
                    ->Unit(benchmark::kMicrosecond));
  }
  for (const double n : {1e3, 1e4, 1e5, 1e6}) {
    for (const bool fcl : {false, true}) {
      const std::string name =
          "BM_BuildScale/" + std::to_string(static_cast<long>(n)) + (fcl ? "/fcl-obb" : "/ours");
      auto* b = benchmark::RegisterBenchmark(name.c_str(), BM_BuildScale, rings_for(n), fcl)
                    ->Unit(benchmark::kMillisecond);
      if (n >= 1e6) b->Iterations(1);
      add_min_max(b);
    }
  }
  for (const double n : {1e2, 1e3, 1e4, 1e5, 1e6}) {
    for (const auto& [gap_name, gap] :
         {std::pair<const char*, double>{"near_miss_0.5mm", 5e-4}, {"overlap_1mm", -1e-3}}) {
      for (const int who : {static_cast<int>(Method::kSat), kFcl}) {
        const std::string name = "BM_QueryScale/" + std::to_string(static_cast<long>(n)) + "/" +
                                 gap_name + "/all/" + mesh_who_name(who);
        add_min_max(
            benchmark::RegisterBenchmark(name.c_str(), BM_Spheres, rings_for(n), who, gap, false)
                ->Unit(benchmark::kMicrosecond));
      }
    }
  }
  const std::vector<std::unique_ptr<Scene>> scenes = load_scenes();
  // Distance classes as a fraction of A's size, as BM_BoxPair in core_bench.cpp.
  const std::pair<const char*, double> gaps[] = {
      {"far", 1.0}, {"near", 0.1}, {"very_near", 0.01}, {"touching", 0.0}, {"overlap", -0.2}};
  for (const auto& scene : scenes) {
    for (const auto& [gap_name, gap] : gaps) {
      for (const bool first : {false, true}) {
        for (const Who who : {Who::kOursSat, Who::kOursSatCached, Who::kFclObb, Who::kFclObbFront,
                              Who::kFclRss, Who::kGimpact}) {
          if (who == Who::kGimpact && first) continue;  // GImpact has no first-contact mode
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
  if (disagreements() > 0) {
    std::fprintf(stderr, "error: %d mesh queries answered differently from FCL\n", disagreements());
    return 1;
  }
  return 0;
}
