// The tree query against CGAL's brute force (src/graspcd/exact): same collision answers and the
// same intersecting triangle pairs, in first-contact and all-contacts modes, on generated and real
// non-convex meshes, at poses in deep overlap, shallow contact, touching and near miss.
#include "graspcd/core/tree_query.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <random>
#include <string>

#include "graspcd/core/tritri.h"
#include "graspcd/support/seeded.h"
#include "helpers/real_models.h"
#include "helpers/tree_agreement.h"
#include "helpers/triangle_distance.h"

namespace graspcd {
namespace {

using testing::Agreement;
using testing::scaled;

TEST(TreeQuery, GeneratedTorusAgainstSphereMatchesBruteForce) {
  const TriangleMesh torus = testing::make_torus(0.04, 0.012, 40, 20);
  const TriangleMesh sphere = testing::make_uv_sphere(0.015, 16, 24);
  Agreement agreement;
  Detector sat(Method::kSat);
  testing::check_cases(sat, ObbTree::build(torus), ObbTree::build(sphere),
                       testing::cases_around(torus, sphere, scaled(150), 1), agreement);
  // The poses really mix contact and no contact.
  EXPECT_GT(agreement.intersecting, agreement.poses / 4);
  EXPECT_LT(agreement.intersecting, agreement.poses * 3 / 4 + 1);
  std::printf("torus/sphere: %d poses, %d intersecting, %llu pairs, all agree\n", agreement.poses,
              agreement.intersecting, static_cast<unsigned long long>(agreement.pairs));
}

// A mesh against itself in place: every face touches itself (coplanar) and its neighbours
// (shared edges and vertices): the hardest case for the leaves and the boxes alike.
TEST(TreeQuery, MeshAgainstItselfFindsEverySharedEdgeAndVertex) {
  for (const TriangleMesh& m :
       {testing::make_torus(0.04, 0.012, 24, 12), testing::make_uv_sphere(0.02, 12, 16)}) {
    const ObbTree tree = ObbTree::build(m);
    Agreement agreement;
    Detector sat(Method::kSat);
    testing::check_case(sat, tree, tree, testing::make_case(m, m, Pose{}), agreement);
    // Each face touches itself and at least its three edge neighbours.
    EXPECT_GE(agreement.pairs, 4 * m.faces.size());
  }
}

TEST(TreeQuery, LeafSizeAndHullFitDoNotChangeAnswers) {
  const TriangleMesh torus = testing::make_torus(0.04, 0.012, 30, 16);
  const TriangleMesh sphere = testing::make_uv_sphere(0.015, 12, 16);
  const ObbTree ref_a = ObbTree::build(torus), ref_b = ObbTree::build(sphere);
  testing::Rng rng(9);
  for (const ObbTreeOptions& options :
       {ObbTreeOptions{4, ObbFit::kCovariance}, ObbTreeOptions{8, ObbFit::kHullArea}}) {
    const ObbTree ta = ObbTree::build(torus, options), tb = ObbTree::build(sphere, options);
    for (int i = 0; i < scaled(200); ++i) {
      Pose pose;
      pose.R = testing::random_rotation(rng);
      pose.t = testing::uniform_in_box(rng, Vec3(-0.06, -0.06, -0.018), Vec3(0.06, 0.06, 0.018));
      SatSeparator sat;
      QueryCounters c;
      std::vector<TrianglePair> p1, p2;
      const QueryResult r1 = collide(ref_a, ref_b, pose, QueryMode::kAllContacts, sat, c, &p1);
      const QueryResult r2 = collide(ta, tb, pose, QueryMode::kAllContacts, sat, c, &p2);
      std::sort(p1.begin(), p1.end());
      std::sort(p2.begin(), p2.end());
      ASSERT_EQ(r1.pair_count, r2.pair_count);
      ASSERT_EQ(p1, p2);
    }
  }
}

// The SAT separators take the RAPID-style descent with frames carried down the trees
// (detail::collide_carried); a separator without hint() takes the generic one, which places B's
// box and forms A^T B at every node pair. Both must visit the same node pairs and find the same
// triangle pairs, also far from the origin (meshes moved 1 km away), where the carried rounding
// is largest against the features' size, and with the cached separator along a coherent path.
struct GenericSat {  // sat_separating_axis per pair, no hint(): the generic descent
  bool disjoint(const Obb& a, const Obb& b, std::int32_t, std::int32_t, QueryCounters&) {
    return sat_separating_axis(a, b) != kSatNoAxis;
  }
};

TEST(TreeQuery, CarriedFramesVisitTheSameNodePairsAsTheGenericDescent) {
  for (const double offset : {0.0, 1000.0}) {
    TriangleMesh torus = testing::make_torus(0.04, 0.012, 30, 16);
    TriangleMesh sphere = testing::make_uv_sphere(0.015, 12, 16);
    for (Vec3& v : torus.vertices) v += Vec3(offset, -offset, offset);
    for (Vec3& v : sphere.vertices) v += Vec3(offset, -offset, offset);
    const ObbTree ta = ObbTree::build(torus), tb = ObbTree::build(sphere);
    testing::Rng rng(21);
    Detector cached(Method::kSatCached);
    int hits = 0;
    const int n = scaled(300);
    for (int i = 0; i < n; ++i) {
      // A coherent path for the cached detector: a slow turn and a sweep across the torus.
      Pose pose;
      pose.R = testing::rotation_about(Vec3(0.3, 0.5, 0.8).normalized(), 0.01 * i);
      const Vec3 c(offset, -offset, offset);
      const double dy = 0.3 * testing::uniform(rng, -0.06, 0.06);
      const double dz = 0.2 * testing::uniform(rng, -0.06, 0.06);
      pose.t = c - pose.R * c + Vec3(0.12 * i / n - 0.06, dy, dz);
      for (const QueryMode mode : {QueryMode::kAllContacts, QueryMode::kFirstContact}) {
        GenericSat generic;
        SatSeparator carried;
        QueryCounters cg, cc, ck;
        std::vector<TrianglePair> pg, pc, pk;
        const QueryResult rg = collide(ta, tb, pose, mode, generic, cg, &pg);
        const QueryResult rc = collide(ta, tb, pose, mode, carried, cc, &pc);
        const QueryResult rk = cached.collide(ta, tb, pose, mode, ck, &pk);
        ASSERT_EQ(rg.intersect, rc.intersect) << "offset " << offset << " pose " << i;
        ASSERT_EQ(pg, pc) << "offset " << offset << " pose " << i;
        ASSERT_EQ(cg.box_tests, cc.box_tests) << "offset " << offset << " pose " << i;
        ASSERT_EQ(cg.tri_tests, cc.tri_tests);
        // The cached hint changes which axis is found first, not the answer or the pairs.
        ASSERT_EQ(rg.intersect, rk.intersect);
        ASSERT_EQ(cg.box_tests, ck.box_tests);
        if (mode == QueryMode::kAllContacts) {
          std::sort(pg.begin(), pg.end());
          std::sort(pk.begin(), pk.end());
          ASSERT_EQ(pg, pk);
          hits += rg.intersect;
        }
      }
    }
    // The path both touches and misses.
    EXPECT_GT(hits, n / 10) << "offset " << offset;
    EXPECT_LT(hits, n - n / 10) << "offset " << offset;
  }
}

// Temporal coherence (collide_coherent): along a path that moves a little each step, with large
// jumps away and back (a state restore), the query restarted from the last front finds exactly
// the triangle pairs of a descent from the roots, for the carried SAT descent and the generic one
// (the perceptron); every 100th pose of SAT also against CGAL. Small motions restart from the front
// and save box tests; the jumps descend from the roots.
TEST(TreeQuery, FrontListFindsTheSameTrianglePairsAsADescentFromTheRoots) {
  const TriangleMesh torus = testing::make_torus(0.04, 0.012, 30, 16);
  const TriangleMesh sphere = testing::make_uv_sphere(0.015, 12, 16);
  const ObbTree ta = ObbTree::build(torus), tb = ObbTree::build(sphere);
  // Not scaled by GRASPCD_TEST_SCALE: the path's small steps, its contacts and its jumps are the
  // test, and a tenth of it would hold no jump and hardly a contact.
  const int n = 200;
  for (const Method method : {Method::kSat, Method::kPerceptron}) {
    testing::Rng rng(33);
    // A short perceptron cap: its "may overlap" at the cap only sends the descent further down.
    const DetectorOptions options{10, 10, 1u << 12};
    Detector fresh(method, options), coherent(method, options);
    QueryFront front;
    QueryCounters cf, cc;
    int restarts = 0, hits = 0, checked = 0;
    for (int i = 0; i < n; ++i) {
      // Along the torus's outer rim (ring radius 0.04, tube 0.012; the sphere touches at a
      // centre 0.067 from the axis), in and out of contact, turning slowly.
      Pose pose;
      pose.R = testing::rotation_about(Vec3(0.3, 0.5, 0.8).normalized(), 0.004 * i);
      const double r = 0.066 + 0.004 * std::sin(0.05 * i), angle = 0.004 * i;
      pose.t = Vec3(r * std::cos(angle), r * std::sin(angle), 0.002);
      if (i % 100 == 60) {
        // A jump far away for one step (a state restore), then back on the path.
        pose.R = testing::rotation_about(Vec3(1, 0, 0), 2.0);
        pose.t = Vec3(0.3, -0.2, 0.1);
      } else if (i % 100 == 80) {
        pose.t += testing::uniform_vec3(rng, -0.02, 0.02);  // a jump within reach
      }
      restarts += front_applies(front, tb, pose);
      std::vector<TrianglePair> pf, pc;
      const QueryResult rf = fresh.collide(ta, tb, pose, QueryMode::kAllContacts, cf, &pf);
      const QueryResult rc = coherent.collide_coherent(ta, tb, pose, cc, &pc, front);
      std::sort(pf.begin(), pf.end());
      std::sort(pc.begin(), pc.end());
      ASSERT_EQ(rf.intersect, rc.intersect) << method_name(method) << " pose " << i;
      ASSERT_EQ(rf.pair_count, rc.pair_count) << method_name(method) << " pose " << i;
      ASSERT_EQ(pf, pc) << method_name(method) << " pose " << i;
      hits += rf.intersect;
      if (method == Method::kSat && i % 100 == 0) {
        const testing::PoseCase truth = testing::make_case(torus, sphere, pose);
        ASSERT_EQ(pc, truth.truth) << method_name(method) << " pose " << i;
        ++checked;
      }
    }
    // The path touches and misses, follows the front most of the time, and the front saves work.
    EXPECT_GT(hits, n / 4) << method_name(method);
    EXPECT_LT(hits, n - n / 10) << method_name(method);
    EXPECT_GT(restarts, n * 3 / 4) << method_name(method);
    EXPECT_LT(restarts, n - n / 100) << method_name(method);  // the jumps start from the roots
    EXPECT_LT(cc.box_tests, cf.box_tests) << method_name(method);
    if (method == Method::kSat) {
      EXPECT_GE(checked, n / 100);
      // SAT's gaps let restarted descents keep disjoint front pairs untested.
      EXPECT_GT(cc.front_skips, 0u);
    } else {
      EXPECT_EQ(cc.front_skips, 0u);  // the perceptron measures no gap
    }
    std::printf(
        "%s front list: %d of %d queries restarted, box tests %llu vs %llu from the roots, %llu "
        "front pairs kept untested\n",
        method_name(method), restarts, n, static_cast<unsigned long long>(cc.box_tests),
        static_cast<unsigned long long>(cf.box_tests),
        static_cast<unsigned long long>(cc.front_skips));
  }
}

// Any front covers every leaf pair: one recorded at one pose and followed at a pose far away (as
// happens after an mjData is reused) still gives the descent from the roots' pairs.
TEST(TreeQuery, AStaleFrontStillGivesTheSameAnswer) {
  const TriangleMesh torus = testing::make_torus(0.04, 0.012, 24, 12);
  const TriangleMesh sphere = testing::make_uv_sphere(0.015, 12, 16);
  const ObbTree ta = ObbTree::build(torus), tb = ObbTree::build(sphere);
  testing::Rng rng(5);
  Detector sat(Method::kSat);
  for (int i = 0; i < scaled(100); ++i) {
    QueryFront front;
    QueryCounters c;
    Pose first;
    first.R = testing::random_rotation(rng);
    first.t = testing::uniform_vec3(rng, -0.05, 0.05);
    std::vector<TrianglePair> ignored;
    sat.collide_coherent(ta, tb, first, c, &ignored, front);
    Pose second;
    second.R = testing::random_rotation(rng);
    second.t = testing::uniform_vec3(rng, -0.05, 0.05);
    // Pretend it was recorded here, so that it is followed; its gaps were measured at `first`, so
    // they go (QueryFront: they hold at the front's pose only).
    front.pose = second;
    for (NodePair& p : front.pairs) p.gap = 0;
    ASSERT_TRUE(front_applies(front, tb, second));
    std::vector<TrianglePair> pf, pc;
    sat.collide(ta, tb, second, QueryMode::kAllContacts, c, &pf);
    sat.collide_coherent(ta, tb, second, c, &pc, front);
    std::sort(pf.begin(), pf.end());
    std::sort(pc.begin(), pc.end());
    ASSERT_EQ(pf, pc) << "pose " << i;
  }
}

// The path of the two gap tests below: a SAT detector's coherent queries of a sphere along the
// torus's outer rim, turning slowly, with a small jump every 50 steps; visit(i, pose, trees, front,
// front pairs kept untested by this query) after each.
template <class Visit>
void follow_gap_path(Visit visit) {
  const TriangleMesh torus = testing::make_torus(0.04, 0.012, 30, 16);
  const TriangleMesh sphere = testing::make_uv_sphere(0.015, 12, 16);
  const ObbTree ta = ObbTree::build(torus), tb = ObbTree::build(sphere);
  testing::Rng rng(34);
  Detector sat(Method::kSat);
  QueryFront front;
  QueryCounters c;
  for (int i = 0; i < 200; ++i) {
    Pose pose;
    pose.R = testing::rotation_about(Vec3(0.3, 0.5, 0.8).normalized(), 0.004 * i);
    const double r = 0.066 + 0.004 * std::sin(0.05 * i), angle = 0.004 * i;
    pose.t = Vec3(r * std::cos(angle), r * std::sin(angle), 0.002);
    if (i % 50 == 30) pose.t += testing::uniform_vec3(rng, -0.003, 0.003);
    const std::uint64_t skips_before = c.front_skips;
    std::vector<TrianglePair> pairs;
    sat.collide_coherent(ta, tb, pose, c, &pairs, front);
    visit(i, pose, ta, tb, front, c.front_skips - skips_before);
  }
}

// The gaps a front keeps are lower bounds on the distance between their boxes at the front's pose,
// measured or carried over untested from an earlier pose less B's motion (front_motion): B's box
// grown by gap / sqrt(3) on every half-extent lies within the gap's distance of the box, so grown
// by 0.9 of that it must still be disjoint from A's box. Along the path of the test above, small
// steps and jumps.
TEST(TreeQuery, FrontGapsAreLowerBoundsOnTheBoxDistance) {
  std::uint64_t carried = 0, checked = 0;
  follow_gap_path([&](int i, const Pose& pose, const ObbTree& ta, const ObbTree& tb,
                      const QueryFront& front, std::uint64_t skips) {
    carried += skips;
    for (const NodePair& p : front.pairs) {
      if (!p.disjoint) continue;
      ASSERT_GE(p.gap, 0.0) << "pose " << i;
      Obb grown = tb.nodes()[static_cast<std::size_t>(p.b)].box;
      // 0.9: room for SAT's slack where the gap is tight.
      grown.half.array() += 0.9 * p.gap / std::sqrt(3.0);
      ASSERT_NE(sat_separating_axis(ta.nodes()[static_cast<std::size_t>(p.a)].box,
                                    transform(pose, grown)),
                kSatNoAxis)
          << "pose " << i << " pair " << p.a << ", " << p.b << " gap " << p.gap;
      ++checked;
    }
  });
  // Pairs were carried over untested, and many gaps were checked.
  EXPECT_GT(carried, 1000u);
  EXPECT_GT(checked, 10000u);
  std::printf("%llu front gaps checked, %llu front pairs kept untested\n",
              static_cast<unsigned long long>(checked), static_cast<unsigned long long>(carried));
}

// A leaf pair on the front keeps the least gap of its triangle pairs when the plane test rejected
// them all (tree_query.h, tritri.h): every such gap is a lower bound on the distance between every
// triangle pair of the two leaves at the front's pose (computed independently: no pair intersects,
// and the distance in long double, up to 1e-9 of it for its rounding), whether measured there or
// carried over untested from an earlier pose less B's motion. Along the path of the gap test
// above.
TEST(TreeQuery, LeafGapsAreLowerBoundsOnTheTriangleDistance) {
  std::uint64_t checked = 0, exact_checks = 0;
  long double tightest = 0;  // the largest gap / distance ratio seen
  follow_gap_path([&](int i, const Pose& pose, const ObbTree& ta, const ObbTree& tb,
                      const QueryFront& front, std::uint64_t /*skips*/) {
    for (const NodePair& p : front.pairs) {
      if (p.disjoint || p.gap <= 0) continue;
      const ObbNode& x = ta.nodes()[static_cast<std::size_t>(p.a)];
      const ObbNode& y = tb.nodes()[static_cast<std::size_t>(p.b)];
      ASSERT_TRUE(x.is_leaf() && y.is_leaf());
      for (std::int32_t j = y.first; j < y.first + y.count; ++j) {
        const Triangle u = apply_pose(pose, tb.triangles()[static_cast<std::size_t>(j)]);
        for (std::int32_t k = x.first; k < x.first + x.count; ++k) {
          const Triangle& t = ta.triangles()[static_cast<std::size_t>(k)];
          ASSERT_FALSE(tri_tri_intersect_predicates(t, u))
              << "pose " << i << ": a leaf gap on triangles that meet";
          // Exactly when a plane keeps the triangles the gap apart (a gap measured here, or carried
          // while the plane still does); else against their distance in long double.
          const bool by_plane =
              exact::plane_keeps_apart(t, u, p.gap) || exact::plane_keeps_apart(u, t, p.gap);
          exact_checks += by_plane;
          const long double bound = testing::triangle_distance(t, u) * (1 + 1e-9L);
          ASSERT_TRUE(by_plane || static_cast<long double>(p.gap) <= bound)
              << "pose " << i << " pair " << p.a << ", " << p.b << " gap " << p.gap;
          tightest = std::max(tightest, static_cast<long double>(p.gap) / bound);
          ++checked;
        }
      }
    }
  });
  EXPECT_GT(checked, 1000u);
  EXPECT_GT(exact_checks, checked / 2);
  EXPECT_GT(tightest, 0.5L) << "some gaps are close to the distance they bound";
  std::printf(
      "%llu leaf gaps checked (%llu exactly by a plane), the tightest at %.6Lf of its "
      "distance\n",
      static_cast<unsigned long long>(checked), static_cast<unsigned long long>(exact_checks),
      tightest);
}

// The descent's stack comes from a per-thread pool (tree_query.h, DescentStack): a query run from
// inside another one, here by a triangle test that queries the same trees at another pose at
// every triangle pair, takes its own stack and leaves the outer descent's untouched, so both
// answers are those of queries run one after the other.
struct NestingTriTest {
  const ObbTree* ta;
  const ObbTree* tb;
  Pose pose;
  std::vector<TrianglePair> expected;  // the inner query's pairs, run on its own
  int nested = 0, wrong = 0;
  bool operator()(const Triangle& a, const Triangle& b) {
    SatSeparator sat;
    QueryCounters c;
    std::vector<TrianglePair> found;
    collide(*ta, *tb, pose, QueryMode::kAllContacts, sat, c, &found);
    std::sort(found.begin(), found.end());
    ++nested;
    wrong += found != expected;
    return tri_tri_intersect(a, b);
  }
};

TEST(TreeQuery, AQueryInsideAnotherKeepsItsOwnStack) {
  const TriangleMesh torus = testing::make_torus(0.04, 0.012, 30, 16);
  const TriangleMesh sphere = testing::make_uv_sphere(0.015, 12, 16);
  const ObbTree ta = ObbTree::build(torus), tb = ObbTree::build(sphere);
  Pose outer, inner;
  outer.t = Vec3(0.064, 0.001, 0.002);  // the sphere 3 mm into the torus's rim
  inner.R = testing::rotation_about(Vec3(0, 0, 1), 0.7);
  inner.t = Vec3(-0.03, 0.05, 0.005);  // elsewhere on the rim, deep in the tube
  SatSeparator sat;
  QueryCounters c;
  std::vector<TrianglePair> plain_outer;
  NestingTriTest nesting{&ta, &tb, inner, {}};
  collide(ta, tb, inner, QueryMode::kAllContacts, sat, c, &nesting.expected);
  std::sort(nesting.expected.begin(), nesting.expected.end());
  collide(ta, tb, outer, QueryMode::kAllContacts, sat, c, &plain_outer);
  std::sort(plain_outer.begin(), plain_outer.end());
  ASSERT_FALSE(nesting.expected.empty());
  ASSERT_FALSE(plain_outer.empty());
  ASSERT_NE(nesting.expected, plain_outer);
  std::vector<TrianglePair> nested_outer;
  collide(ta, tb, outer, QueryMode::kAllContacts, sat, c, &nested_outer, std::ref(nesting));
  std::sort(nested_outer.begin(), nested_outer.end());
  EXPECT_EQ(nested_outer, plain_outer);
  EXPECT_GT(nesting.nested, 10);
  EXPECT_EQ(nesting.wrong, 0);
}

// pull_up_front on its own (the coherent query calls it only every tol::kFrontPullUpPeriod
// restarts): a front recorded in contact and followed while B backs away goes deeper than it needs;
// pulled up at the pose it was followed to, it has fewer pairs, still covers every leaf pair of
// the two trees exactly once, each pulled-up pair is disjoint with a gap no larger than its boxes'
// SAT gap allows (B's box grown by 0.9 gap / sqrt(3) stays disjoint), and a restart from it finds
// the descent from the roots' triangle pairs, as B comes back into contact.
TEST(TreeQuery, APulledUpFrontCoversEveryLeafPairOnceAndGivesTheSameAnswer) {
  const TriangleMesh torus = testing::make_torus(0.04, 0.012, 30, 16);
  const TriangleMesh sphere = testing::make_uv_sphere(0.015, 12, 16);
  const ObbTree ta = ObbTree::build(torus), tb = ObbTree::build(sphere);
  // The leaves below each node, by the layout's left child (i + 1) and `right`.
  const auto leaves_below = [](const ObbTree& t) {
    const auto& nodes = t.nodes();
    std::vector<std::vector<std::int32_t>> below(nodes.size());
    for (std::size_t i = nodes.size(); i-- > 0;) {
      const ObbNode& n = nodes[i];
      if (n.is_leaf()) {
        below[i] = {static_cast<std::int32_t>(i)};
        continue;
      }
      below[i] = below[i + 1];
      const auto& r = below[static_cast<std::size_t>(n.right)];
      below[i].insert(below[i].end(), r.begin(), r.end());
    }
    return below;
  };
  const auto below_a = leaves_below(ta), below_b = leaves_below(tb);
  const std::size_t nb = tb.nodes().size();
  const auto pose_at = [](double r) {
    Pose pose;
    pose.R = testing::rotation_about(Vec3(0.3, 0.5, 0.8).normalized(), 0.1);
    pose.t = Vec3(r, 0.001, 0.002);
    return pose;
  };
  Detector sat(Method::kSat);
  QueryFront front;
  QueryCounters c;
  std::vector<TrianglePair> pairs;
  // In contact (the sphere's centre 0.064 from the torus's axis: 3 mm deep), then backing away
  // 0.5 mm a step while the front is followed (no pull-up yet at these few restarts).
  sat.collide_coherent(ta, tb, pose_at(0.064), c, &pairs, front);
  ASSERT_FALSE(pairs.empty());
  for (int i = 1; i <= 10; ++i) {
    pairs.clear();
    sat.collide_coherent(ta, tb, pose_at(0.064 + 0.0005 * i), c, &pairs, front);
    ASSERT_TRUE(front.restarted) << "step " << i;
  }
  ASSERT_TRUE(pairs.empty());  // 2 mm apart
  const Pose apart = pose_at(0.069);
  const std::size_t before = front.pairs.size();
  const std::uint64_t box_tests = c.box_tests;
  pull_up_front(ta, tb, apart, front, c);
  const std::size_t after = front.pairs.size();
  EXPECT_LT(after, before / 2) << "the front apart is pulled well up";
  EXPECT_GT(c.box_tests, box_tests);
  std::vector<int> cover(ta.nodes().size() * nb, 0);
  int pulled = 0;
  for (const NodePair& p : front.pairs) {
    for (std::int32_t la : below_a[static_cast<std::size_t>(p.a)]) {
      for (std::int32_t lb : below_b[static_cast<std::size_t>(p.b)]) {
        ++cover[static_cast<std::size_t>(la) * nb + static_cast<std::size_t>(lb)];
      }
    }
    const ObbNode& x = ta.nodes()[static_cast<std::size_t>(p.a)];
    const ObbNode& y = tb.nodes()[static_cast<std::size_t>(p.b)];
    if (x.is_leaf() && y.is_leaf()) continue;
    ++pulled;
    ASSERT_TRUE(p.disjoint) << "an inner pair on the front is a disjoint one";
    ASSERT_GE(p.gap, 0);
    Obb grown = y.box;
    grown.half.array() += 0.9 * p.gap / std::sqrt(3.0);
    EXPECT_NE(sat_separating_axis(x.box, transform(apart, grown)), kSatNoAxis)
        << "pair " << p.a << ", " << p.b << " gap " << p.gap;
  }
  EXPECT_GT(pulled, 0);
  for (std::size_t la = 0; la < ta.nodes().size(); ++la) {
    if (!ta.nodes()[la].is_leaf()) continue;
    for (std::size_t lb = 0; lb < nb; ++lb) {
      if (!tb.nodes()[lb].is_leaf()) continue;
      ASSERT_EQ(cover[la * nb + lb], 1) << "leaf pair " << la << ", " << lb;
    }
  }
  // Back into contact from the pulled-up front: the pairs of a descent from the roots.
  for (int i = 9; i >= 0; --i) {
    const Pose pose = pose_at(0.064 + 0.0005 * i);
    std::vector<TrianglePair> pf, pc;
    sat.collide(ta, tb, pose, QueryMode::kAllContacts, c, &pf);
    sat.collide_coherent(ta, tb, pose, c, &pc, front);
    ASSERT_TRUE(front.restarted) << "step " << i;
    std::sort(pf.begin(), pf.end());
    std::sort(pc.begin(), pc.end());
    ASSERT_EQ(pf, pc) << "step " << i;
  }
  std::printf("front pulled up from %zu to %zu pairs (%d inner)\n", before, after, pulled);
}

// A non-finite pose intersects nothing and costs no descent, and a front the coherent query kept
// is not left empty by it: the next finite query still finds the descent from the roots' pairs.
TEST(TreeQuery, ANonFinitePoseIntersectsNothingAndLeavesNoFrontBehind) {
  const TriangleMesh torus = testing::make_torus(0.04, 0.012, 24, 12);
  const TriangleMesh sphere = testing::make_uv_sphere(0.015, 12, 16);
  const ObbTree ta = ObbTree::build(torus), tb = ObbTree::build(sphere);
  Pose touching;
  touching.t = Vec3(0.066, 0, 0);  // the sphere across the torus's outer rim
  Detector sat(Method::kSat);
  QueryFront front;
  QueryCounters c;
  std::vector<TrianglePair> expected, found;
  sat.collide(ta, tb, touching, QueryMode::kAllContacts, c, &expected);
  ASSERT_FALSE(expected.empty());
  sat.collide_coherent(ta, tb, touching, c, &found, front);
  ASSERT_TRUE(front.valid);
  for (const double bad : {std::nan(""), std::numeric_limits<double>::infinity()}) {
    Pose pose = touching;
    pose.t[1] = bad;
    const QueryCounters before = c;
    found.clear();
    EXPECT_FALSE(sat.collide(ta, tb, pose, QueryMode::kAllContacts, c, &found).intersect);
    EXPECT_FALSE(sat.collide_coherent(ta, tb, pose, c, &found, front).intersect);
    EXPECT_TRUE(found.empty());
    EXPECT_EQ(c.box_tests, before.box_tests);  // no descent
    EXPECT_FALSE(front.valid);
    found.clear();
    sat.collide_coherent(ta, tb, touching, c, &found, front);
    std::sort(found.begin(), found.end());
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(found, expected);
  }
}

// Real non-convex meshes from ../shared/models (support/real_models.h): cube_cup_hi against the
// mug.
TEST(TreeQuery, RealCupAgainstMugMatchesBruteForce) {
  std::string why_not;
  const std::optional<testing::CupAndMug> real = testing::load_cup_and_mug(why_not);
  if (!real) GTEST_SKIP() << why_not;
  const TriangleMesh& cup = real->cup;
  const TriangleMesh& mug = real->mug;
  Agreement agreement;
  Detector sat(Method::kSat);
  testing::check_cases(sat, ObbTree::build(cup), ObbTree::build(mug),
                       testing::cases_around(cup, mug, scaled(400), 2), agreement);
  EXPECT_GE(agreement.poses, scaled(2000));
  EXPECT_GT(agreement.intersecting, agreement.poses / 4);
  std::printf("cube_cup_hi/mug: %d poses, %d intersecting, %llu pairs, all agree\n",
              agreement.poses, agreement.intersecting,
              static_cast<unsigned long long>(agreement.pairs));
}

}  // namespace
}  // namespace graspcd
