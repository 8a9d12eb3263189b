// The reduction of a pair's triangle-pair contacts: farthest-point selection, and the contact
// manifold (patches, their points, the pair's budget) with its vertex adjacency.
#include "graspcd/core/contact_manifold.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "graspcd/core/adjacency_index.h"
#include "graspcd/core/mesh_features.h"
#include "graspcd/core/triangle_contact.h"
#include "graspcd/core/tritri.h"
#include "graspcd/support/meshes.h"

namespace graspcd {
namespace {

Triangle tri(Vec3 a, Vec3 b, Vec3 c) { return Triangle{{a, b, c}}; }

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

// Candidates are adjacent through a vertex id on one geom: the same id on the other geom is
// another vertex. Each vertex's list holds every candidate on it, the last added first, and a
// second build forgets the first. Ids below AdjacencyIndex::kDirectIds get one slot per distinct
// vertex; the same ids shifted beyond it the same lists, in a hash table (a power of two, at least
// 6 n slots).
TEST(AdjacencyIndex, ListsTheCandidatesOnEachVertexPerGeom) {
  for (const std::uint32_t shift : {std::uint32_t{0}, AdjacencyIndex::kDirectIds}) {
    SCOPED_TRACE(shift);
    const auto shifted = [shift](std::vector<FaceVertexIds> ids) {
      for (FaceVertexIds& f : ids) {
        for (std::uint32_t& id : f) id += shift;
      }
      return ids;
    };
    const std::vector<FaceVertexIds> a = shifted({{0, 1, 2}, {2, 3, 4}, {5, 6, 7}});
    const std::vector<FaceVertexIds> b = shifted({{0, 1, 2}, {3, 4, 5}, {6, 7, 2}});
    AdjacencyIndex index;
    index.build(a, b);
    if (shift == 0) {
      EXPECT_EQ(index.slot_count(), 16u) << "one slot per distinct vertex";
    } else {
      EXPECT_GE(index.slot_count(), 18u);
      EXPECT_EQ(index.slot_count() & (index.slot_count() - 1), 0u) << "a power of two";
    }
    const auto on = [&index](std::uint32_t slot) {
      std::vector<std::size_t> out;
      index.for_each_candidate(slot, [&out](std::size_t i) { out.push_back(i); });
      return out;
    };
    // Geom1's vertex 2: corner 2 of candidate 0, corner 0 of candidate 1.
    EXPECT_EQ(index.slot(0, 2), index.slot(1, 0));
    EXPECT_EQ(on(index.slot(0, 2)), (std::vector<std::size_t>{1, 0}));
    // Geom2's vertex 2: corner 2 of candidates 0 and 2 (k = 3 + corner); not geom1's vertex 2.
    EXPECT_EQ(index.slot(0, 5), index.slot(2, 5));
    EXPECT_EQ(on(index.slot(0, 5)), (std::vector<std::size_t>{2, 0}));
    EXPECT_NE(index.slot(0, 2), index.slot(0, 5));
    // Geom1's vertex 5 is candidate 2's alone; geom2's vertex 5 is candidate 1's alone.
    EXPECT_EQ(on(index.slot(2, 0)), (std::vector<std::size_t>{2}));
    EXPECT_EQ(on(index.slot(1, 5)), (std::vector<std::size_t>{1}));
    // 8 distinct vertices on each geom: 16 slots in use, each below the slot count.
    std::set<std::uint32_t> used;
    for (std::size_t i = 0; i < 3; ++i) {
      for (std::size_t k = 0; k < 6; ++k) used.insert(index.slot(i, k));
    }
    EXPECT_EQ(used.size(), 16u);
    EXPECT_LT(*used.rbegin(), index.slot_count());
    index.build(shifted({{9, 9, 9}}), shifted({{0, 1, 2}}));
    EXPECT_EQ(on(index.slot(0, 0)), (std::vector<std::size_t>{0, 0, 0}));
    EXPECT_EQ(on(index.slot(0, 3)), (std::vector<std::size_t>{0}));
    if (shift == 0) {
      EXPECT_EQ(index.slot_count(), 4u) << "the first build's slots forgotten";
    }
  }
}

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

// The MuJoCo layer welds each geom's whole mesh once and hands the manifold the candidates' ids;
// that gives the manifold of the candidates' own triangles, bit for bit, on a pinch (two patches)
// and a corner. So do the same ids shifted beyond AdjacencyIndex::kDirectIds, which the index finds
// in its hash table instead of its direct one, and build_contact_manifold_into with one manifold
// reused for both cases twice over (its buffers, and patches, from the other case).
TEST(ContactManifold, IdsWeldedPerMeshGiveTheSameManifoldAsTheTriangles) {
  const TriangleMesh u = testing::make_u_mesh(0.03, 0.04, 0.01, 0.01);
  const TriangleMesh wall = testing::make_box_mesh(0.0205, 0.01, 0.005);
  const TriangleMesh cube = testing::make_box_mesh(0.005, 0.005, 0.005);
  const auto faces = [](const TriangleMesh& m) {
    std::vector<Triangle> out;
    for (std::size_t f = 0; f < m.faces.size(); ++f) out.push_back(m.triangle(f));
    return out;
  };
  const auto expect_same = [](const ContactManifold& x, const ContactManifold& y) {
    ASSERT_EQ(x.patches.size(), y.patches.size());
    for (std::size_t p = 0; p < x.patches.size(); ++p) {
      EXPECT_EQ(x.patches[p].members, y.patches[p].members);
      EXPECT_EQ(x.patches[p].selected, y.patches[p].selected);
      EXPECT_EQ(x.patches[p].normal, y.patches[p].normal);
      EXPECT_EQ(x.patches[p].depth, y.patches[p].depth);
      EXPECT_EQ(x.patches[p].area, y.patches[p].area);
    }
    EXPECT_EQ(x.contact_patch, y.contact_patch);
    EXPECT_EQ(x.contact_gain, y.contact_gain);
    ASSERT_EQ(x.contacts.size(), y.contacts.size());
    for (std::size_t k = 0; k < x.contacts.size(); ++k) {
      EXPECT_EQ(x.contacts[k].pos, y.contacts[k].pos);
      EXPECT_EQ(x.contacts[k].normal, y.contacts[k].normal);
      EXPECT_EQ(x.contacts[k].depth, y.contacts[k].depth);
    }
  };
  ContactManifold reused;
  for (int round = 0; round < 2; ++round) {
    for (const auto& [mb, t] : {std::pair{&wall, Vec3(0.0001, 0.025, 0.0002)},
                                std::pair{&cube, Vec3(0.0155, 0.0145, 0.0001)}}) {
      const Candidates c = candidates_of(u, *mb, at(t));
      ASSERT_GT(c.contacts.size(), 4u);
      const auto ids_a = weld_vertex_ids(faces(u)), ids_b = weld_vertex_ids(faces(*mb));
      std::vector<FaceVertexIds> va, vb, va_far, vb_far;
      for (std::size_t i = 0; i < c.contacts.size(); ++i) {
        va.push_back(ids_a[c.index_a[i]]);
        vb.push_back(ids_b[c.index_b[i]]);
        va_far.push_back(va.back());
        vb_far.push_back(vb.back());
        for (std::uint32_t& id : va_far.back()) id += AdjacencyIndex::kDirectIds;
        for (std::uint32_t& id : vb_far.back()) id += AdjacencyIndex::kDirectIds;
      }
      const ContactManifold by_faces = build_contact_manifold(c.contacts, c.faces_a, c.faces_b);
      expect_same(build_contact_manifold_by_ids(c.contacts, va, vb), by_faces);
      expect_same(build_contact_manifold_by_ids(c.contacts, va_far, vb_far), by_faces);
      // One side far, the other near: the hash table too.
      expect_same(build_contact_manifold_by_ids(c.contacts, va, vb_far), by_faces);
      build_contact_manifold_into(c.contacts, va, vb, {}, reused);
      expect_same(reused, by_faces);
    }
  }
  build_contact_manifold_into({}, {}, {}, {}, reused);
  EXPECT_TRUE(reused.patches.empty());
  EXPECT_TRUE(reused.contacts.empty());
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

// Candidates and triangles (or vertex ids) that differ in number are refused with a message that
// names the counts, not answered with an empty manifold; no candidates and no triangles is the
// empty manifold.
TEST(ContactManifold, InputsOfDifferentLengthsAreRefused) {
  const std::vector<TriContact> cs(2);
  const Triangle t = tri({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  const std::vector<Triangle> one = {t}, two = {t, t};
  const std::vector<FaceVertexIds> ids_one = {{0, 1, 2}}, ids_two = {{0, 1, 2}, {0, 1, 2}};
  const auto refusal = [](const auto& call) -> std::string {
    try {
      call();
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "not refused";
  };
  EXPECT_EQ(refusal([&] { build_contact_manifold(cs, one, two); }),
            "build_contact_manifold: 1 faces_a and 2 faces_b for 2 candidates");
  EXPECT_EQ(refusal([&] { build_contact_manifold(cs, two, one); }),
            "build_contact_manifold: 2 faces_a and 1 faces_b for 2 candidates");
  EXPECT_EQ(refusal([&] { build_contact_manifold({}, one, one); }),
            "build_contact_manifold: 1 faces_a and 1 faces_b for 0 candidates");
  EXPECT_EQ(refusal([&] { build_contact_manifold_by_ids(cs, ids_two, ids_one); }),
            "build_contact_manifold_by_ids: 2 vertices_a and 1 vertices_b for 2 candidates");
  EXPECT_EQ(refusal([&] { build_contact_manifold_by_ids(cs, {}, {}); }),
            "build_contact_manifold_by_ids: 0 vertices_a and 0 vertices_b for 2 candidates");
  // Matching lengths: two candidates at one spot sharing their triangles give one patch, one point.
  const ContactManifold m = build_contact_manifold_by_ids(cs, ids_two, ids_two);
  EXPECT_EQ(m.patches.size(), 1u);
  EXPECT_EQ(m.contacts.size(), 1u);
  EXPECT_EQ(build_contact_manifold(cs, two, two).contacts.size(), 1u);
  EXPECT_TRUE(build_contact_manifold_by_ids({}, {}, {}).patches.empty());
}

}  // namespace
}  // namespace graspcd
