// FCL, the study's peer (src/graspcd/peer/fcl_peer.h), against our tree query (graspcd::collide
// with SatSeparator, all contacts, the exact triangle test at the leaves), on real and shipped
// meshes at a few thousand poses around contact.
//
// FCL: Pan, Chitta, Manocha, "FCL: A General Purpose Library for Collision and Proximity Queries",
// ICRA 2012. OBB trees: Gottschalk, Lin, Manocha, "OBBTree", SIGGRAPH 1996.
//
// What is asserted, and why. FCL's triangle test (Intersect::intersect_Triangle, 17 projection
// axes) runs in plain double arithmetic; ours is exact. So at poses where two triangles touch to
// within rounding, the two may disagree, and that is not an error of either. The test asserts that
// FCL's disagreements are only of that kind:
//  1. Every triangle pair in one answer and not the other is within kDepthTol x (scene size) of
//     changing its answer: a pair only FCL reports (exactly disjoint) is at a Euclidean distance
//     below the tolerance; a pair only we report (exactly intersecting) can be separated by a
//     translation below the tolerance (the smallest one along FCL's 17 axes, an upper bound on the
//     penetration depth). kDepthTol = 1e-12 is 1e-13 m for a 10 cm scene: some 7,000 ulps of the
//     coordinates, 10^4 times the largest disagreement seen (1.4e-17 m on the cup and mug), and
//     far below anything a wrong pose convention, a wrongly culled box or a lost pair would give
//     (the poses other than the touching ones are 1e-4 of the size, tens of micrometres, away).
//     The distance and the depth bound are computed in floating point: a diagnostic, accurate to
//     a few ulps, which is all the tolerance needs.
//  2. At the poses that are not touching by construction (near miss by 1e-4 of the size, shallow
//     overlap by 1e-3, deep overlap by 0.25) FCL's collision answer equals ours.
//  3. Disagreeing pairs are at most kMaxDisagreeShare (1 %) of the pairs we find.
//  4. FCL's first-contact answer matches its own all-contacts answer (pair_count 0 or 1, and the
//     one pair among all-contacts' pairs), and no pair is reported twice.
// Counts are printed: poses, intersecting poses, pairs found by each, pairs missed and extra, the
// largest distance and depth among them, for FCL's OBB and RSS trees.
#include "graspcd/peer/fcl_peer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "graspcd/core/obb_tree.h"
#include "graspcd/core/tree_query.h"
#include "graspcd/io/mesh_io.h"
#include "graspcd/support/meshes.h"
#include "graspcd/support/random_geometry.h"
#include "helpers/contact_rays.h"
#include "helpers/real_models.h"
#include "helpers/test_scale.h"

namespace graspcd {
namespace {

using peer::FclBv;
using peer::FclMesh;
using testing::scaled;

constexpr double kDepthTol = 1e-12;         // relative to the scene size, see the header
constexpr double kMaxDisagreeShare = 0.01;  // of the pairs we find

// ---- Poses around contact ---------------------------------------------------------------------

enum class Kind { kTouchingIn, kTouchingOut, kNearMiss, kShallow, kDeep };

struct PoseCase {
  Pose pose;
  Kind kind;
};

bool touching(Kind k) { return k == Kind::kTouchingIn || k == Kind::kTouchingOut; }

// Our answer at one pose, all contacts, pairs sorted.
std::vector<TrianglePair> our_pairs(const ObbTree& ta, const ObbTree& tb, const Pose& pose) {
  SatSeparator sat;
  QueryCounters counters;
  std::vector<TrianglePair> pairs;
  const QueryResult r = collide(ta, tb, pose, QueryMode::kAllContacts, sat, counters, &pairs);
  EXPECT_EQ(r.pair_count, pairs.size());
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

// As tests/helpers/tree_agreement.h cases_around, without the CGAL truth: on each contact ray
// (bracketed by our query), poses at both sides of the transition (touching to within rounding),
// just outside (1e-4 of the size), just inside (1e-3) and deep inside (0.25).
std::vector<PoseCase> poses_around(const ObbTree& ta, const ObbTree& tb, double size,
                                   int directions, std::uint64_t seed) {
  testing::Rng rng(seed);
  const auto hits = [&](const Pose& p) {
    SatSeparator sat;
    QueryCounters counters;
    return collide(ta, tb, p, QueryMode::kFirstContact, sat, counters).intersect;
  };
  std::vector<PoseCase> cases;
  for (const testing::ContactRay& r : testing::contact_rays(ta, tb, size, directions, rng, hits)) {
    cases.push_back({r.at(r.lo), Kind::kTouchingIn});
    cases.push_back({r.at(r.hi), Kind::kTouchingOut});
    cases.push_back({r.at(r.hi + 1e-4 * size), Kind::kNearMiss});
    cases.push_back({r.at(r.lo - 1e-3 * size), Kind::kShallow});
    cases.push_back({r.at(r.lo - 0.25 * size), Kind::kDeep});
  }
  return cases;
}

// ---- How close a disagreeing pair is to the other answer (floating point, diagnostic) ---------

// Distance between segments [p1, q1] and [p2, q2], either possibly a point (Ericson, Real-Time
// Collision Detection, 5.1.9).
double segment_distance(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2) {
  const Vec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  const auto clamp01 = [](double x) { return std::min(1.0, std::max(0.0, x)); };
  double s = 0, t = 0;
  if (a <= 0 && e <= 0) return r.norm();
  if (a <= 0) {
    t = clamp01(f / e);
  } else {
    const double c = d1.dot(r);
    if (e <= 0) {
      s = clamp01(-c / a);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      s = denom > 0 ? clamp01((b * f - c * e) / denom) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = clamp01(-c / a);
      } else if (t > 1) {
        t = 1;
        s = clamp01((b - c) / a);
      }
    }
  }
  return ((p1 + s * d1) - (p2 + t * d2)).norm();
}

// Distance from a point to a triangle (possibly of zero area).
double point_triangle_distance(const Vec3& p, const Triangle& t) {
  const Vec3 n = (t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]);
  const double nn = n.squaredNorm();
  if (nn > 0) {
    bool inside = true;
    for (int i = 0; i < 3; ++i) {
      const Vec3& a = t.v[i];
      const Vec3& b = t.v[(i + 1) % 3];
      if ((b - a).cross(p - a).dot(n) < 0) inside = false;
    }
    if (inside) return std::abs((p - t.v[0]).dot(n)) / std::sqrt(nn);
  }
  double d = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) d = std::min(d, segment_distance(p, p, t.v[i], t.v[(i + 1) % 3]));
  return d;
}

// Distance between two disjoint triangles: the least of the 6 vertex-triangle and 9 edge-edge
// distances (exact in real arithmetic for disjoint triangles, which is the case where it is used).
double triangle_distance(const Triangle& p, const Triangle& q) {
  double d = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    d = std::min(d, point_triangle_distance(p.v[i], q));
    d = std::min(d, point_triangle_distance(q.v[i], p));
    for (int j = 0; j < 3; ++j) {
      d = std::min(d, segment_distance(p.v[i], p.v[(i + 1) % 3], q.v[j], q.v[(j + 1) % 3]));
    }
  }
  return d;
}

// An upper bound on the penetration depth of two intersecting triangles: the shortest translation
// along one of FCL's 17 axes (the normals, the 9 edge-edge crosses, the 6 in-plane edge normals)
// that separates their projections. Axes of zero length (degenerate triangles) are skipped;
// infinity when none is left.
double depth_bound(const Triangle& p, const Triangle& q) {
  const Vec3 e[3] = {p.v[1] - p.v[0], p.v[2] - p.v[1], p.v[0] - p.v[2]};
  const Vec3 f[3] = {q.v[1] - q.v[0], q.v[2] - q.v[1], q.v[0] - q.v[2]};
  const Vec3 n = e[0].cross(e[1]), m = f[0].cross(f[1]);
  std::vector<Vec3> axes = {n, m};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) axes.push_back(e[i].cross(f[j]));
    axes.push_back(e[i].cross(n));
    axes.push_back(f[i].cross(m));
  }
  double best = std::numeric_limits<double>::infinity();
  for (const Vec3& axis : axes) {
    const double len = axis.norm();
    if (!(len > 0) || !std::isfinite(len)) continue;
    const Vec3 u = axis / len;
    double p_lo = std::numeric_limits<double>::infinity(), p_hi = -p_lo, q_lo = p_lo, q_hi = -p_lo;
    for (int k = 0; k < 3; ++k) {
      p_lo = std::min(p_lo, u.dot(p.v[k]));
      p_hi = std::max(p_hi, u.dot(p.v[k]));
      q_lo = std::min(q_lo, u.dot(q.v[k]));
      q_hi = std::max(q_hi, u.dot(q.v[k]));
    }
    best = std::min(best, std::max(0.0, std::min(p_hi - q_lo, q_hi - p_lo)));
  }
  return best;
}

// ---- The comparison ---------------------------------------------------------------------------

struct Tally {
  int poses = 0, intersecting = 0;
  int answer_disagreements = 0;           // poses where intersect differs
  int touching_answer_disagreements = 0;  // ... of which at the touching poses
  std::uint64_t our_pairs = 0, fcl_pairs = 0;
  std::uint64_t missed = 0, extra = 0;  // pairs only we report / only FCL reports
  double max_missed_depth = 0, max_extra_distance = 0;
};

Tally compare_with_fcl(const TriangleMesh& a, const TriangleMesh& b, const ObbTree& ta,
                       const ObbTree& tb, double size, const std::vector<PoseCase>& cases,
                       FclBv bv) {
  const FclMesh fa(a, bv), fb(b, bv);
  EXPECT_EQ(fa.triangle_count(), a.faces.size());
  EXPECT_EQ(fb.triangle_count(), b.faces.size());
  Tally tally;
  const double tol = kDepthTol * size;
  for (const PoseCase& c : cases) {
    const std::vector<TrianglePair> ours = our_pairs(ta, tb, c.pose);
    std::vector<TrianglePair> theirs;
    const peer::FclQueryResult all = peer::fcl_collide(fa, fb, c.pose, false, &theirs);
    EXPECT_EQ(all.pair_count, theirs.size());
    EXPECT_EQ(all.intersect, !theirs.empty());
    std::sort(theirs.begin(), theirs.end());
    EXPECT_TRUE(std::adjacent_find(theirs.begin(), theirs.end()) == theirs.end())
        << "FCL reported a pair twice";
    // First contact: FCL's own all-contacts answer, one pair of it.
    std::vector<TrianglePair> first_pair;
    const peer::FclQueryResult first = peer::fcl_collide(fa, fb, c.pose, true, &first_pair);
    EXPECT_EQ(first.intersect, all.intersect);
    EXPECT_EQ(first.pair_count, all.intersect ? 1u : 0u);
    if (!first_pair.empty()) {
      EXPECT_TRUE(std::binary_search(theirs.begin(), theirs.end(), first_pair.front()));
    }

    const bool our_hit = !ours.empty();
    ++tally.poses;
    tally.intersecting += our_hit;
    tally.our_pairs += ours.size();
    tally.fcl_pairs += theirs.size();
    if (our_hit != all.intersect) {
      ++tally.answer_disagreements;
      tally.touching_answer_disagreements += touching(c.kind);
      EXPECT_TRUE(touching(c.kind)) << "FCL's answer differs at a pose that is not touching: ours "
                                    << our_hit << ", kind " << static_cast<int>(c.kind);
    }
    std::vector<TrianglePair> only_ours, only_theirs;
    std::set_difference(ours.begin(), ours.end(), theirs.begin(), theirs.end(),
                        std::back_inserter(only_ours));
    std::set_difference(theirs.begin(), theirs.end(), ours.begin(), ours.end(),
                        std::back_inserter(only_theirs));
    for (const TrianglePair& p : only_ours) {
      const double depth =
          depth_bound(a.triangle(static_cast<std::size_t>(p.a)),
                      apply_pose(c.pose, b.triangle(static_cast<std::size_t>(p.b))));
      ++tally.missed;
      tally.max_missed_depth = std::max(tally.max_missed_depth, depth);
      EXPECT_LE(depth, tol) << "FCL missed faces " << p.a << ", " << p.b << ", depth " << depth;
    }
    for (const TrianglePair& p : only_theirs) {
      const double distance =
          triangle_distance(a.triangle(static_cast<std::size_t>(p.a)),
                            apply_pose(c.pose, b.triangle(static_cast<std::size_t>(p.b))));
      ++tally.extra;
      tally.max_extra_distance = std::max(tally.max_extra_distance, distance);
      EXPECT_LE(distance, tol) << "FCL reported faces " << p.a << ", " << p.b << " at distance "
                               << distance;
    }
  }
  return tally;
}

void check_and_print(const char* name, const TriangleMesh& a, const TriangleMesh& b, int directions,
                     std::uint64_t seed) {
  const ObbTree ta = ObbTree::build(a), tb = ObbTree::build(b);
  const double size = ta.root().box.half.norm() + tb.root().box.half.norm();
  const std::vector<PoseCase> cases = poses_around(ta, tb, size, directions, seed);
  ASSERT_GE(cases.size(), 5u * static_cast<std::size_t>(directions));
  for (const FclBv bv : {FclBv::kObb, FclBv::kRss}) {
    const Tally t = compare_with_fcl(a, b, ta, tb, size, cases, bv);
    std::printf(
        "%s, %s: %d poses, %d intersecting (ours); answers differ at %d poses (%d touching); "
        "pairs: ours %llu, FCL %llu, only ours %llu (max depth %.3g m), only FCL %llu "
        "(max distance %.3g m); tolerance %.3g m\n",
        name, peer::fcl_bv_name(bv), t.poses, t.intersecting, t.answer_disagreements,
        t.touching_answer_disagreements, static_cast<unsigned long long>(t.our_pairs),
        static_cast<unsigned long long>(t.fcl_pairs), static_cast<unsigned long long>(t.missed),
        t.max_missed_depth, static_cast<unsigned long long>(t.extra), t.max_extra_distance,
        kDepthTol * size);
    // The poses mix contact and no contact, with many pairs: the comparison is not vacuous.
    EXPECT_GT(t.intersecting, t.poses / 4);
    EXPECT_LT(t.intersecting, t.poses * 3 / 4 + 1);
    EXPECT_GT(t.our_pairs, static_cast<std::uint64_t>(t.poses));
    EXPECT_LE(static_cast<double>(t.missed + t.extra),
              kMaxDisagreeShare * static_cast<double>(t.our_pairs));
  }
}

// ---- Construction and the adapter's contract --------------------------------------------------

TriangleMesh unit_tetrahedron() {
  TriangleMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  m.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

TEST(FclPeer, BuildsBothVolumesAndRejectsBadInput) {
  const TriangleMesh tet = unit_tetrahedron();
  for (const FclBv bv : {FclBv::kObb, FclBv::kRss}) {
    const FclMesh m(tet, bv);
    EXPECT_EQ(m.bv(), bv);
    EXPECT_EQ(m.triangle_count(), 4u);
    EXPECT_EQ(m.bv_count(), 7);  // one triangle a leaf: 2n - 1 nodes
  }
  EXPECT_THROW(FclMesh(TriangleMesh{}), std::invalid_argument);
  TriangleMesh bad = tet;
  bad.faces.push_back({0, 1, 4});
  EXPECT_THROW(FclMesh(bad, FclBv::kRss), std::invalid_argument);
  const FclMesh obb(tet, FclBv::kObb), rss(tet, FclBv::kRss);
  EXPECT_THROW(peer::fcl_collide(obb, rss, Pose{}, false, nullptr), std::invalid_argument);
}

// The pose convention x_A = R x_B + t and the face indices: a tetrahedron against itself at random
// poses (generic: no pair touches to within rounding), where FCL's pairs must equal ours exactly.
// A transposed R, an inverted pose or renumbered faces would fail here.
TEST(FclPeer, PoseConventionAndFaceIndicesMatchOurs) {
  const TriangleMesh tet = unit_tetrahedron();
  const ObbTree tree = ObbTree::build(tet);
  testing::Rng rng(7);
  int hits = 0, misses = 0;
  for (const FclBv bv : {FclBv::kObb, FclBv::kRss}) {
    const FclMesh m(tet, bv);
    for (int i = 0; i < 400; ++i) {
      Pose pose;
      pose.R = testing::random_rotation(rng);
      pose.t = testing::random_in_cube(rng, Vec3(0.3, 0.3, 0.3), 1.0);
      const std::vector<TrianglePair> ours = our_pairs(tree, tree, pose);
      std::vector<TrianglePair> theirs;
      const peer::FclQueryResult r = peer::fcl_collide(m, m, pose, false, &theirs);
      std::sort(theirs.begin(), theirs.end());
      ASSERT_EQ(theirs, ours) << "pose " << i;
      ASSERT_EQ(r.intersect, !ours.empty());
      (ours.empty() ? misses : hits) += 1;
    }
  }
  // Random poses of this spread both hit and miss often.
  EXPECT_GT(hits, 100);
  EXPECT_GT(misses, 100);
}

// FCL's front list (temporal coherence) and its box-test statistic: along a coherent path of a
// sphere sweeping through another, the front list must give the answers of the query from the
// roots at every step, and the statistic must count box tests (at least one, the roots). FCL 0.7
// reports some pairs twice when it starts from a front (a leaf pair on the front and again below a
// front node that overlaps now), so the pairs are compared as sets.
TEST(FclPeer, FrontListKeepsTheAnswersAndBoxTestsAreCounted) {
  const TriangleMesh sphere = testing::make_uv_sphere(0.05, 10, 20);
  const FclMesh m(sphere, FclBv::kObb);
  peer::FclFront front;
  int hits = 0;
  const int n = 120;
  for (int i = 0; i < n; ++i) {
    Pose pose;
    pose.R = testing::rotation_about(Vec3(0, 0.6, 0.8), 0.003 * i);
    pose.t = Vec3(0.12 - 0.001 * i, 0.01, 0);
    std::vector<TrianglePair> direct, coherent;
    const peer::FclQueryResult r = peer::fcl_collide(m, m, pose, false, &direct);
    const peer::FclQueryResult f = peer::fcl_collide(m, m, pose, false, &coherent, &front);
    std::sort(direct.begin(), direct.end());
    std::sort(coherent.begin(), coherent.end());
    coherent.erase(std::unique(coherent.begin(), coherent.end()), coherent.end());
    ASSERT_EQ(direct, coherent) << "step " << i;
    ASSERT_EQ(r.intersect, f.intersect);
    EXPECT_GE(r.bv_tests, 1u);
    EXPECT_GE(front.size(), 1u);
    hits += r.intersect;
  }
  // The path starts clear (centres 12 cm apart, radius 5 cm) and ends in deep overlap.
  EXPECT_GT(hits, n / 4);
  EXPECT_LT(hits, n - n / 10);
  front.clear();
  EXPECT_EQ(front.size(), 0u);
}

// ---- Real and shipped meshes ------------------------------------------------------------------

TEST(FclPeer, RealCupAgainstMugAgreesUpToRounding) {
  std::string why_not;
  const std::optional<testing::CupAndMug> real = testing::load_cup_and_mug(why_not);
  if (!real) GTEST_SKIP() << why_not;
  check_and_print("cube_cup_hi/mug", real->cup, real->mug, scaled(400), 11);
}

TEST(FclPeer, FingerAgainstCupAgreesUpToRounding) {
  const std::filesystem::path dir(GRASPCD_MESHES_DIR);
  const TriangleMesh finger = io::load_mesh((dir / "finger_C.obj").string());
  const TriangleMesh cup = io::load_mesh((dir / "cup.obj").string());
  check_and_print("cup/finger_C", cup, finger, scaled(400), 12);
}

}  // namespace
}  // namespace graspcd
