// Contact generation from intersecting triangle pairs, and the reduction to mjMAXCONPAIR.
#include "graspcd/core/contact.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <set>

#include "graspcd/core/tritri.h"
#include "graspcd/support/meshes.h"

namespace graspcd {
namespace {

Triangle tri(Vec3 a, Vec3 b, Vec3 c) { return Triangle{{a, b, c}}; }

// A large floor triangle (normal +z) pierced by a small vertical one dipping 1 cm below it: the
// smaller push is along the floor's normal, 1 cm, and the position is on the segment's midpoint.
TEST(TrianglePairContact, VerticalTrianglePiercingAFloorUsesTheFloorNormal) {
  const Triangle floor = tri({-1, -1, 0}, {1, -1, 0}, {0, 1, 0});
  const Triangle blade = tri({-0.1, 0, 0.05}, {0.1, 0, 0.05}, {0, 0, -0.01});
  const TriContact c = triangle_pair_contact(floor, blade, 1.0, Vec3::UnitX());
  EXPECT_NEAR(c.normal.dot(Vec3::UnitZ()), 1.0, 1e-12);
  EXPECT_NEAR(c.depth, 0.01, 1e-12);
  EXPECT_NEAR(c.pos.z(), 0.0, 1e-12);
  EXPECT_NEAR(c.pos.x(), 0.0, 1e-12);
  // Swapped roles: the floor is geom2 now, its outward normal +z points toward geom1, so the
  // normal from geom1 to geom2 is -z.
  const TriContact s = triangle_pair_contact(blade, floor, 1.0, Vec3::UnitX());
  EXPECT_NEAR(s.normal.dot(-Vec3::UnitZ()), 1.0, 1e-12);
  EXPECT_NEAR(s.depth, 0.01, 1e-12);
}

// Two faces crossing along the edges of two solids (a's +y side and b's -x side of two boxes that
// overlap 1 cm in z): neither face normal is the penetration direction; the edge axis z is.
TEST(TrianglePairContact, CrossingSideFacesUseTheEdgeAxis) {
  const Triangle a = tri({-0.04, 0.04, -0.04}, {-0.04, 0.04, 0.04}, {0.04, 0.04, 0.04});   // +y
  const Triangle b = tri({-0.01, -0.03, 0.03}, {-0.01, 0.05, 0.11}, {-0.01, 0.05, 0.03});  // -x
  // The diagonals (a's edge 2, b's edge 0) are not edges of the boxes.
  const TriContact c = triangle_pair_contact(a, b, 1.0, Vec3::UnitX(), 0b011, 0b110);
  EXPECT_NEAR(c.normal.z(), 1.0, 1e-12);
  EXPECT_NEAR(c.depth, 0.01, 1e-12);
  // Without the face orientation, the axis a's x edge x b's z edge (a's face normal) would
  // separate the triangles with a 1 cm push along -y, into box a; the sign from the faces
  // rules that out, even with every edge taken as sharp.
  const TriContact all = triangle_pair_contact(a, b, 1.0, Vec3::UnitX());
  EXPECT_NEAR(all.normal.z(), 1.0, 1e-12);
  EXPECT_NEAR(all.depth, 0.01, 1e-12);
}

// Seen on the Robotiq pad against the voxel cup (mjcf/real_robotiq_cup.xml), coordinates as the
// served query had them: a horizontal face of the cup (b) crosses the pad's side face (a, normal
// -x) and grazes the pad's front face (y = -0.004) by 0.09 mm. The edge axis of the pad's z edge
// and the cup's x edge is y, tilted 0.23 degrees, so its dot product with n_a - n_b is 0.004: too
// small for the faces to decide its sign (tol::kContactSignCosine). The smaller side, 0.09 mm
// along -y, is the contact. Had the faces decided, that axis would have measured 10 mm and the
// side face's 1.9 mm along -x would have won: the kicks that let the held cup jitter.
TEST(TrianglePairContact, AnEdgeAxisNearlyInBothFacesTakesTheSmallerSide) {
  const Triangle a =
      tri({-0.011, -0.004, -0.009375}, {-0.011, -0.004, 0.009375}, {-0.011, 0.004, 0.009375});
  const Triangle b =
      tri({-0.009087654, -0.006248175, -0.001437782}, {-0.011701105, -0.003914970, -0.001433941},
          {-0.009097126, -0.003904448, -0.001432941});
  ASSERT_TRUE(tri_tri_intersect(a, b));
  const TriContact c = triangle_pair_contact(a, b, 0.01, Vec3::UnitX(), 0b011, 0b010);
  EXPECT_GT(c.normal.dot(-Vec3::UnitY()), 0.999);
  EXPECT_NEAR(c.depth, 0.088e-3, 0.002e-3);
}

TEST(TrianglePairContact, DepthIsClippedToTheCap) {
  const Triangle floor = tri({-1, -1, 0}, {1, -1, 0}, {0, 1, 0});
  const Triangle blade = tri({-0.1, 0, 0.05}, {0.1, 0, 0.05}, {0, 0, -0.2});
  const TriContact c = triangle_pair_contact(floor, blade, 0.003, Vec3::UnitX());
  EXPECT_DOUBLE_EQ(c.depth, 0.003);
}

// Only the part of the blade over the floor triangle counts: a blade whose deep tip lies beyond
// the floor's edge measures the depth inside the floor's prism only.
TEST(TrianglePairContact, DepthIsMeasuredInsideThePrism) {
  const Triangle floor = tri({0, -1, 0}, {1, -1, 0}, {0, 1, 0});  // x >= 0 only
  // Dips to -0.01 at x = 0.05 (inside) and to -0.1 at x = -0.05 (outside the prism).
  const Triangle blade = tri({0.05, 0, -0.01}, {-0.05, 0, -0.1}, {0.0, 0, 0.1});
  const TriContact c = triangle_pair_contact(floor, blade, 1.0, Vec3::UnitX());
  EXPECT_GT(c.depth, 0.0);
  EXPECT_LT(c.depth, 0.06);  // the clipped polygon reaches x = 0 at most: depth <= 0.055
}

// Two crossing segments (zero-area triangles): no face normal, the edge axis is their common
// perpendicular, with no penetration.
TEST(TrianglePairContact, CrossingSegmentsUseTheirCommonPerpendicular) {
  const Triangle a = tri({0, 0, 0}, {1, 0, 0}, {2, 0, 0});
  const Triangle b = tri({0.5, -1, 0}, {0.5, 1, 0}, {0.5, 0, 0});
  const TriContact c = triangle_pair_contact(a, b, 1.0, Vec3::UnitY());
  EXPECT_NEAR(std::abs(c.normal.z()), 1.0, 1e-15);
  EXPECT_EQ(c.depth, 0.0);
}

// Overlapping collinear segments: every edge pair is parallel, so the fallback normal is used.
TEST(TrianglePairContact, CollinearSegmentsUseTheFallbackNormal) {
  const Triangle a = tri({0, 0, 0}, {1, 0, 0}, {2, 0, 0});
  const Triangle b = tri({0.5, 0, 0}, {3, 0, 0}, {1.5, 0, 0});
  const TriContact c = triangle_pair_contact(a, b, 1.0, Vec3::UnitY());
  EXPECT_EQ(c.normal, Vec3::UnitY());
  EXPECT_EQ(c.depth, 0.0);
}

TEST(SelectContacts, KeepsAllWhenFewAndPutsTheDeepestFirst) {
  std::vector<TriContact> cs(5);
  for (int i = 0; i < 5; ++i) {
    cs[static_cast<std::size_t>(i)].pos = Vec3(i, 0, 0);
    cs[static_cast<std::size_t>(i)].depth = i == 3 ? 0.5 : 0.1;
  }
  const auto keep = select_contacts(cs, 50);
  ASSERT_EQ(keep.size(), 5u);
  EXPECT_EQ(keep[0], 3u);
  EXPECT_EQ(std::set<std::size_t>(keep.begin(), keep.end()).size(), 5u);
}

// 200 contacts along a segment: 50 distinct ones, the deepest first, both ends of the segment
// kept (farthest-point sampling reaches the extremes first), and no two chosen closer than half
// the best possible spacing (Gonzalez's 2-approximation of max-min dispersion).
TEST(SelectContacts, CapsAtKWithTheDeepestAndASpread) {
  std::vector<TriContact> cs(200);
  for (std::size_t i = 0; i < cs.size(); ++i) {
    cs[i].pos = Vec3(static_cast<double>(i) * 0.001, 0, 0);
    cs[i].depth = i == 77 ? 0.01 : 0.001;
  }
  const auto keep = select_contacts(cs, 50);
  ASSERT_EQ(keep.size(), 50u);
  EXPECT_EQ(keep[0], 77u);
  const std::set<std::size_t> set(keep.begin(), keep.end());
  EXPECT_EQ(set.size(), 50u);
  EXPECT_TRUE(set.count(0));
  EXPECT_TRUE(set.count(199));
  double min_gap = 1e9;
  for (std::size_t i : keep) {
    for (std::size_t j : keep) {
      if (i != j) min_gap = std::min(min_gap, (cs[i].pos - cs[j].pos).norm());
    }
  }
  // The best 50 of these points are 4 mm apart (floor(199 / 49) grid steps): at least 2 mm.
  EXPECT_GE(min_gap, 0.002 - 1e-12);
}

// Contacts at one position are kept once: fewer than k when the positions run out.
TEST(SelectContacts, DuplicatePositionsAreNotChosenTwice) {
  std::vector<TriContact> cs(120);
  for (std::size_t i = 0; i < cs.size(); ++i) cs[i].pos = Vec3(static_cast<double>(i % 3), 0, 0);
  EXPECT_EQ(select_contacts(cs, 50).size(), 3u);
}

// A box's face diagonals are not feature edges, its 12 edges are; a finely tessellated sphere has
// none.
TEST(SharpEdges, BoxEdgesAreSharpDiagonalsAndSmoothSurfacesAreNot) {
  const TriangleMesh box = testing::make_box_mesh(0.01, 0.02, 0.03);
  std::vector<Triangle> faces;
  for (std::size_t f = 0; f < box.faces.size(); ++f) faces.push_back(box.triangle(f));
  const auto masks = sharp_edge_masks(faces);
  ASSERT_EQ(masks.size(), 12u);
  int sharp = 0;
  for (std::uint8_t m : masks) {
    const int bits = (m & 1) + (m >> 1 & 1) + (m >> 2 & 1);
    EXPECT_EQ(bits, 2);  // two box edges and the diagonal
    sharp += bits;
  }
  EXPECT_EQ(sharp, 24);  // 12 edges, each seen from its two faces
  const TriangleMesh sphere = testing::make_uv_sphere(0.05, 24, 48);
  faces.clear();
  for (std::size_t f = 0; f < sphere.faces.size(); ++f) faces.push_back(sphere.triangle(f));
  for (std::uint8_t m : sharp_edge_masks(faces)) EXPECT_EQ(m, 0);
  // With the welded ids given (as the registry calls it): the same masks; ids of another length
  // are refused.
  faces.clear();
  for (std::size_t f = 0; f < box.faces.size(); ++f) faces.push_back(box.triangle(f));
  EXPECT_EQ(sharp_edge_masks(faces, weld_vertex_ids(faces)), masks);
  EXPECT_THROW(sharp_edge_masks(faces, {}), std::invalid_argument);
  // An open triangle: every edge is a boundary.
  EXPECT_EQ(sharp_edge_masks({tri({0, 0, 0}, {1, 0, 0}, {0, 1, 0})})[0], 7);
}

}  // namespace
}  // namespace graspcd

// ---- The contact manifold
// ------------------------------------------------------------------------

namespace graspcd {
namespace {

// The candidates of two meshes, B placed in A's frame by `pose`: every intersecting triangle pair
// (brute force, in (a, b) order), its contact, and the two faces (B's in its own frame).
struct Candidates {
  std::vector<TriContact> contacts;
  std::vector<Triangle> faces_a, faces_b;
  std::vector<std::size_t> index_a, index_b;  // the faces' indices in their meshes
};

Candidates candidates_of(const TriangleMesh& ma, const TriangleMesh& mb, const Pose& pose) {
  std::vector<Triangle> a, b_local;
  for (std::size_t f = 0; f < ma.faces.size(); ++f) a.push_back(ma.triangle(f));
  for (std::size_t f = 0; f < mb.faces.size(); ++f) b_local.push_back(mb.triangle(f));
  const std::vector<Triangle> b = posed_triangles(mb, pose);
  const std::vector<std::uint8_t> sharp_a = sharp_edge_masks(a),
                                  sharp_b = sharp_edge_masks(b_local);
  Candidates c;
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = 0; j < b.size(); ++j) {
      if (!tri_tri_intersect(a[i], b[j])) continue;
      c.contacts.push_back(
          triangle_pair_contact(a[i], b[j], 1.0, Vec3::UnitZ(), sharp_a[i], sharp_b[j]));
      c.faces_a.push_back(a[i]);
      c.faces_b.push_back(b_local[j]);
      c.index_a.push_back(i);
      c.index_b.push_back(j);
    }
  }
  return c;
}

Pose at(const Vec3& t) {
  Pose p;
  p.R = Mat3::Identity();
  p.t = t;
  return p;
}

// Every kept contact carries its patch's normal, and the pair keeps at most its budget.
void expect_consistent(const ContactManifold& m, std::size_t budget) {
  EXPECT_LE(m.contacts.size(), budget);
  for (const TriContact& c : m.contacts) {
    bool in_a_patch = false;
    for (const ContactPatch& p : m.patches) in_a_patch |= c.normal == p.normal;
    EXPECT_TRUE(in_a_patch);
    EXPECT_GE(c.depth, 0.0);
  }
}

// A U (arms' inner faces at x = +-2 cm) pinching a wall 4.1 cm wide: the wall enters each arm
// 0.5 mm. One patch per side, the normals opposite (from the U into the wall), each 0.5 mm deep.
TEST(ContactManifold, APinchOfAThinWallGivesTwoPatches) {
  const TriangleMesh u = testing::make_u_mesh(0.03, 0.04, 0.01, 0.01);
  const TriangleMesh wall = testing::make_box_mesh(0.0205, 0.01, 0.005);
  const Candidates c = candidates_of(u, wall, at(Vec3(0, 0.025, 0)));
  ASSERT_GT(c.contacts.size(), 8u) << "enough candidates to need a reduction";
  const ContactManifold m = build_contact_manifold(c.contacts, c.faces_a, c.faces_b);
  ASSERT_EQ(m.patches.size(), 2u);
  std::set<int> sides;
  for (const ContactPatch& p : m.patches) {
    EXPECT_GT(std::abs(p.normal.x()), 0.999) << p.normal.transpose();
    sides.insert(p.normal.x() > 0 ? 1 : -1);
    EXPECT_NEAR(p.depth, 0.0005, 1e-9);
    EXPECT_EQ(p.selected.size(), 4u);
  }
  EXPECT_EQ(sides.size(), 2u) << "one patch on each side of the wall";
  ASSERT_EQ(m.contacts.size(), 8u);
  // The first two contacts are the two patches' deepest points.
  EXPECT_LT(m.contacts[0].normal.dot(m.contacts[1].normal), -0.99);
  expect_consistent(m, 8);
}

// A finger segment (a 1 cm cube) pushed into the inner corner of the U, 0.5 mm into the floor
// (normal +y from the U) and into the right arm (normal -x): two patches.
TEST(ContactManifold, ASegmentTouchingTwoWallsOfTheCBlockGivesTwoPatches) {
  const TriangleMesh u = testing::make_u_mesh(0.03, 0.04, 0.01, 0.01);
  const TriangleMesh cube = testing::make_box_mesh(0.005, 0.005, 0.005);
  const Candidates c = candidates_of(u, cube, at(Vec3(0.0155, 0.0145, 0)));
  const ContactManifold m = build_contact_manifold(c.contacts, c.faces_a, c.faces_b);
  ASSERT_EQ(m.patches.size(), 2u);
  bool floor = false, arm = false;
  for (const ContactPatch& p : m.patches) {
    floor |= p.normal.y() > 0.999;
    arm |= p.normal.x() < -0.999;
    EXPECT_NEAR(p.depth, 0.0005, 1e-9);
  }
  EXPECT_TRUE(floor && arm);
  expect_consistent(m, 8);
}

// A small box resting 0.5 mm deep on a large one, face on face: one patch along +z, four points
// spanning most of the small box's 2 x 2 cm footprint.
TEST(ContactManifold, AFlatFaceOnAFlatFaceGivesOnePatch) {
  const TriangleMesh big = testing::make_box_mesh(0.02, 0.02, 0.01);
  const TriangleMesh small = testing::make_box_mesh(0.01, 0.01, 0.01);
  const Candidates c = candidates_of(big, small, at(Vec3(0.003, 0.002, 0.0195)));
  const ContactManifold m = build_contact_manifold(c.contacts, c.faces_a, c.faces_b);
  ASSERT_EQ(m.patches.size(), 1u);
  EXPECT_GT(m.patches[0].normal.z(), 0.999);
  ASSERT_EQ(m.contacts.size(), 4u);
  EXPECT_GT(m.patches[0].area, 0.5 * 0.02 * 0.02);
  for (const TriContact& k : m.contacts) EXPECT_NEAR(k.depth, 0.0005, 1e-9);
  expect_consistent(m, 8);
}

// The budgets: caps per patch and per pair are honoured, and with more patches than the pair's
// cap the deepest patches keep their deepest points.
TEST(ContactManifold, ManyPatchesKeepTheDeepestPatchesFirst) {
  std::vector<TriContact> cs;
  std::vector<Triangle> fa, fb;
  for (int i = 0; i < 10; ++i) {  // ten separate spots, no shared vertices, depths 1..10 mm
    const Vec3 o(0.1 * i, 0, 0);
    cs.push_back(TriContact{o, Vec3::UnitZ(), 0.001 * (i + 1)});
    fa.push_back(tri(o, o + Vec3(0.01, 0, 0), o + Vec3(0, 0.01, 0)));
    fb.push_back(tri(o + Vec3(0, 0, 1), o + Vec3(0.01, 0, 1), o + Vec3(0, 0.01, 1)));
  }
  const ContactManifold m = build_contact_manifold(cs, fa, fb);
  ASSERT_EQ(m.patches.size(), 10u);
  ASSERT_EQ(m.contacts.size(), 8u);
  for (int k = 0; k < 8; ++k) EXPECT_DOUBLE_EQ(m.contacts[k].depth, 0.001 * (10 - k));
  ManifoldOptions two;
  two.max_per_pair = 2;
  EXPECT_EQ(build_contact_manifold(cs, fa, fb, two).contacts.size(), 2u);
}

// Welding: equal ids exactly for equal coordinates, -0.0 and 0.0 alike, the smallest difference
// apart.
TEST(ContactManifold, WeldedIdsAreEqualExactlyForEqualCoordinates) {
  const auto ids = weld_vertex_ids({tri({0, 0, 0}, {1, 0, 0}, {0, 1, 0}),
                                    tri({-0.0, 0, -0.0}, {1, 0, 0}, {0, 0, 1}),
                                    tri({1e-300, 0, 0}, {0, 1, 0}, {0, 0, 1})});
  ASSERT_EQ(ids.size(), 3u);
  EXPECT_EQ(ids[0][0], ids[1][0]);  // -0.0 is 0.0
  EXPECT_EQ(ids[0][1], ids[1][1]);
  EXPECT_EQ(ids[0][2], ids[2][1]);
  EXPECT_EQ(ids[1][2], ids[2][2]);
  EXPECT_NE(ids[0][0], ids[2][0]);  // 1e-300 is not 0
  EXPECT_NE(ids[0][2], ids[1][2]);
  std::set<std::uint32_t> distinct;
  for (const auto& f : ids) distinct.insert(f.begin(), f.end());
  EXPECT_EQ(distinct.size(), 5u);
  EXPECT_EQ(*distinct.rbegin(), 4u) << "ids are 0 .. distinct - 1";
}

// The MuJoCo seam welds each geom's whole mesh once and hands the manifold the candidates' ids;
// that gives the manifold of the candidates' own triangles, bit for bit, on a pinch (two patches)
// and a corner.
TEST(ContactManifold, IdsWeldedPerMeshGiveTheSameManifoldAsTheTriangles) {
  const TriangleMesh u = testing::make_u_mesh(0.03, 0.04, 0.01, 0.01);
  const TriangleMesh wall = testing::make_box_mesh(0.0205, 0.01, 0.005);
  const TriangleMesh cube = testing::make_box_mesh(0.005, 0.005, 0.005);
  const auto faces = [](const TriangleMesh& m) {
    std::vector<Triangle> out;
    for (std::size_t f = 0; f < m.faces.size(); ++f) out.push_back(m.triangle(f));
    return out;
  };
  for (const auto& [mb, t] : {std::pair{&wall, Vec3(0.0001, 0.025, 0.0002)},
                              std::pair{&cube, Vec3(0.0155, 0.0145, 0.0001)}}) {
    const Candidates c = candidates_of(u, *mb, at(t));
    ASSERT_GT(c.contacts.size(), 4u);
    const auto ids_a = weld_vertex_ids(faces(u)), ids_b = weld_vertex_ids(faces(*mb));
    std::vector<FaceVertexIds> va, vb;
    for (std::size_t i = 0; i < c.contacts.size(); ++i) {
      va.push_back(ids_a[c.index_a[i]]);
      vb.push_back(ids_b[c.index_b[i]]);
    }
    const ContactManifold by_ids = build_contact_manifold_by_ids(c.contacts, va, vb);
    const ContactManifold by_faces = build_contact_manifold(c.contacts, c.faces_a, c.faces_b);
    ASSERT_EQ(by_ids.patches.size(), by_faces.patches.size());
    for (std::size_t p = 0; p < by_ids.patches.size(); ++p) {
      EXPECT_EQ(by_ids.patches[p].members, by_faces.patches[p].members);
      EXPECT_EQ(by_ids.patches[p].selected, by_faces.patches[p].selected);
    }
    ASSERT_EQ(by_ids.contacts.size(), by_faces.contacts.size());
    for (std::size_t k = 0; k < by_ids.contacts.size(); ++k) {
      EXPECT_EQ(by_ids.contacts[k].pos, by_faces.contacts[k].pos);
      EXPECT_EQ(by_ids.contacts[k].normal, by_faces.contacts[k].normal);
      EXPECT_EQ(by_ids.contacts[k].depth, by_faces.contacts[k].depth);
    }
  }
}

// The same input gives the same manifold, bit for bit, and the empty input an empty one.
TEST(ContactManifold, IsDeterministic) {
  const TriangleMesh u = testing::make_u_mesh(0.03, 0.04, 0.01, 0.01);
  const TriangleMesh wall = testing::make_box_mesh(0.0205, 0.01, 0.005);
  const Candidates c = candidates_of(u, wall, at(Vec3(0.0001, 0.025, 0.0002)));
  const ContactManifold m1 = build_contact_manifold(c.contacts, c.faces_a, c.faces_b);
  const ContactManifold m2 = build_contact_manifold(c.contacts, c.faces_a, c.faces_b);
  ASSERT_EQ(m1.contacts.size(), m2.contacts.size());
  for (std::size_t i = 0; i < m1.contacts.size(); ++i) {
    EXPECT_EQ(m1.contacts[i].pos, m2.contacts[i].pos);
    EXPECT_EQ(m1.contacts[i].depth, m2.contacts[i].depth);
  }
  EXPECT_TRUE(build_contact_manifold({}, {}, {}).contacts.empty());
}

// ---- Contacts reused across steps (contact.h, ReusedContacts)

Pose turned(double angle, const Vec3& axis, const Vec3& t) {
  Pose p;
  p.R = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  p.t = t;
  return p;
}

// The bound holds for every point within the radius, and is reached by a point at the radius
// square to the axis with no translation.
TEST(ReusedContacts, PoseDriftBoundsHowFarEveryPointWithinTheRadiusMoved) {
  const double radius = 0.05;
  std::uint32_t seed = 7;
  const auto uniform = [&seed] {
    seed = seed * 1664525u + 1013904223u;
    return static_cast<double>(seed >> 8) / 16777216.0 * 2 - 1;
  };
  for (int k = 0; k < 200; ++k) {
    const Pose from = turned(uniform() * 3, Vec3(uniform(), uniform(), 1), Vec3(0.1, 0, 0));
    const Pose to = turned(uniform() * 3, Vec3(1, uniform(), uniform()),
                           Vec3(0.1 + 1e-3 * uniform(), 1e-3 * uniform(), 0));
    const double bound = pose_drift(from, to, radius);
    for (int j = 0; j < 20; ++j) {
      const Vec3 p =
          Vec3(uniform(), uniform(), uniform()).normalized() * radius * std::abs(uniform());
      const double moved = ((to.R * p + to.t) - (from.R * p + from.t)).norm();
      EXPECT_LE(moved, bound * (1 + 1e-12)) << k;
    }
  }
  const Pose a = turned(0, Vec3::UnitZ(), Vec3::Zero());
  const Pose b = turned(0.01, Vec3::UnitZ(), Vec3::Zero());
  const Vec3 rim = Vec3::UnitX() * radius;
  EXPECT_NEAR(pose_drift(a, b, radius), (b.R * rim - rim).norm(), 1e-15);
}

// contact_drift bounds the motion of every point of geom2 within radius_b of its own origin that
// lies within radius_a of geom1's origin, at either pose; for a small geom1 turning about its own
// origin against a large geom2 (a finger on its joint against the object) it is the turn times
// geom1's radius, far below pose_drift's turn times geom2's.
TEST(ReusedContacts, ContactDriftBoundsThePointsOfGeom2NearGeom1) {
  const double radius_a = 0.02, radius_b = 0.1;
  std::uint32_t seed = 11;
  const auto uniform = [&seed] {
    seed = seed * 1664525u + 1013904223u;
    return static_cast<double>(seed >> 8) / 16777216.0 * 2 - 1;
  };
  int checked = 0;
  for (int k = 0; k < 200; ++k) {
    const Pose from = turned(uniform() * 3, Vec3(uniform(), uniform(), 1), Vec3(0.09, 0, 0));
    // `from`, turned by up to 0.01 rad about geom1's origin and moved by up to 1 mm.
    const Mat3 spin =
        Eigen::AngleAxisd(uniform() * 0.01, Vec3(1, uniform(), uniform()).normalized())
            .toRotationMatrix();
    const Pose to{spin * from.R, spin * from.t + 1e-3 * Vec3(uniform(), uniform(), uniform())};
    const double bound = contact_drift(from, to, radius_a, radius_b);
    EXPECT_LE(bound, pose_drift(from, to, radius_b));
    for (int j = 0; j < 40; ++j) {
      // A point of geom1's ball, at `from` (even j) or at `to` (odd j), taken as geom2's point
      // there when it lies within geom2's radius.
      const Vec3 p =
          Vec3(uniform(), uniform(), uniform()).normalized() * radius_a * std::abs(uniform());
      const Pose& at = j % 2 ? to : from;
      const Pose& other = j % 2 ? from : to;
      const Vec3 x = at.R.transpose() * (p - at.t);
      if (x.norm() > radius_b) continue;
      ++checked;
      EXPECT_LE((other.R * x + other.t - p).norm(), bound * (1 + 1e-12)) << k << " " << j;
    }
  }
  EXPECT_GT(checked, 1000);

  // geom2 turned by 0.01 rad about geom1's origin: geom1's rim moved 0.01 * radius_a against it.
  const Pose from = turned(0.4, Vec3(1, 1, 0), Vec3(0.09, 0.01, 0));
  const Pose spin = turned(0.01, Vec3::UnitZ(), Vec3::Zero());
  const Pose to{spin.R * from.R, spin.R * from.t};
  EXPECT_NEAR(contact_drift(from, to, radius_a, radius_b), 2 * std::sin(0.005) * radius_a, 1e-12);
  EXPECT_LT(contact_drift(from, to, radius_a, radius_b), pose_drift(from, to, radius_b) / 5);
  const Pose bad{from.R, Vec3(std::nan(""), 0, 0)};
  EXPECT_TRUE(std::isnan(contact_drift(from, bad, radius_a, radius_b)));
}

// A contact 2 mm deep along +z (geom1 toward geom2): geom2 moving along the normal changes the
// depth by exactly that motion and the position by half of it; moving across it keeps the depth
// and carries the point on geom2 along. Beyond the drift, or once a contact separated, nothing is
// reused; at the very pose of the query, exactly the stored contacts.
TEST(ReusedContacts, RefreshFollowsGeom2AlongTheNormalWithinTheDrift) {
  TriContact c;
  c.pos = Vec3(0.01, 0.02, 0.03);
  c.normal = Vec3::UnitZ();
  c.depth = 0.002;
  TriContact e = c;
  e.pos = Vec3(-0.01, 0, 0.03);
  e.normal = Vec3(0, 0.6, 0.8);
  e.depth = 0.001;
  const Pose at = turned(0.3, Vec3(1, 2, 3), Vec3(0.02, -0.01, 0.05));
  ReusedContacts kept;
  EXPECT_FALSE(kept.valid());
  kept.store(at, {c, e});
  ASSERT_TRUE(kept.valid());
  const double radius = 0.1, drift = 1e-3;
  std::vector<TriContact> out;

  ASSERT_TRUE(kept.refresh(at, radius, radius, drift, out));
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(std::memcmp(&out[0], &c, sizeof c), 0);
  EXPECT_EQ(std::memcmp(&out[1], &e, sizeof e), 0);

  Pose up = at;  // geom2 0.5 mm further along +z in geom1's frame: 0.5 mm less penetration
  up.t += Vec3(0, 0, 5e-4);
  ASSERT_TRUE(kept.refresh(up, radius, radius, drift, out));
  EXPECT_NEAR(out[0].depth, 0.0015, 1e-15);
  EXPECT_NEAR((out[0].pos - (c.pos + Vec3(0, 0, 2.5e-4))).norm(), 0, 1e-15);
  EXPECT_EQ(out[0].normal, c.normal);
  EXPECT_NEAR(out[1].depth, 0.001 - 0.8 * 5e-4, 1e-15);
  EXPECT_EQ(out[1].normal, e.normal);

  Pose across = at;  // 0.3 mm along x: no change of depth, the position half of it
  across.t += Vec3(3e-4, 0, 0);
  ASSERT_TRUE(kept.refresh(across, radius, radius, drift, out));
  EXPECT_NEAR(out[0].depth, 0.002, 1e-15);
  EXPECT_NEAR((out[0].pos - (c.pos + Vec3(1.5e-4, 0, 0))).norm(), 0, 1e-15);

  Pose apart = at;  // e separates (0.001 - 0.8 * 0.0013 < 0) within the drift: query again
  apart.t += Vec3(0, 0, 1.3e-3);
  EXPECT_FALSE(kept.refresh(apart, radius, radius, 2e-3, out));
  Pose far = at;  // beyond the drift
  far.t += Vec3(0, 0, -1.1e-3);
  EXPECT_FALSE(kept.refresh(far, radius, radius, drift, out));
  // A turn whose rim motion exceeds the drift, though the translation is 0.
  const Pose turn{at.R * Eigen::AngleAxisd(0.02, Vec3::UnitX()).toRotationMatrix(), at.t};
  EXPECT_GT(contact_drift(at, turn, radius, radius), drift);
  EXPECT_FALSE(kept.refresh(turn, radius, radius, drift, out));
  Pose bad = at;
  bad.t.x() = std::nan("");
  EXPECT_FALSE(kept.refresh(bad, radius, radius, drift, out));

  // No contacts: nothing kept (a pair apart is always queried); clear() forgets.
  kept.store(at, {});
  EXPECT_FALSE(kept.valid());
  EXPECT_FALSE(kept.refresh(at, radius, radius, drift, out));
  kept.store(at, {c});
  kept.clear();
  EXPECT_FALSE(kept.refresh(at, radius, radius, drift, out));

  // geom2 spun about geom1's origin (the z axis) against a small geom1: the kept points, 36.7 mm
  // from geom1's origin, move 0.0367 turn however small geom1's own radius (the reach widens it);
  // and the turn at the larger geom's rim is held to the drift as well.
  kept.store(at, {c, e});
  const auto spun = [&at](double angle) {
    const Mat3 S = Eigen::AngleAxisd(angle, Vec3::UnitZ()).toRotationMatrix();
    return Pose{S * at.R, S * at.t};
  };
  const double small = 1e-3;
  EXPECT_TRUE(kept.refresh(spun(0.02), small, 0.03, drift, out));   // 0.73 mm, rim 0.6 mm
  EXPECT_NEAR(out[0].depth, c.depth, 1e-15);                        // moved across the normal
  EXPECT_FALSE(kept.refresh(spun(0.03), small, 0.03, drift, out));  // 1.1 mm, rim 0.9 mm
  EXPECT_FALSE(kept.refresh(spun(0.015), small, 0.1, drift, out));  // 0.55 mm, rim 1.5 mm
  EXPECT_TRUE(kept.refresh(spun(0.015), small, 0.06, drift, out));  // 0.55 mm, rim 0.9 mm
}

}  // namespace
}  // namespace graspcd
