// The force reduction of the contact manifold (build_contact_manifold, "Force reduction"): each
// patch's kept points reproduce the summed depth and the depth-weighted centre (so the moment about
// it) of the points the support reduction keeps at the reference budget, the bound stated at
// build_contact_manifold, on constructed patches (a flat face on a face, a pinch from both sides, a
// curved edge line, a patch of zero depth) and random multi-patch pairs with capped depths; the
// reference budget reached gives the support reduction's points unchanged.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "graspcd/core/contact_manifold.h"
#include "graspcd/core/geometry.h"
#include "graspcd/core/mesh_features.h"
#include "graspcd/core/reused_contacts.h"
#include "graspcd/core/triangle_contact.h"
#include "helpers/manifold_patches.h"

namespace graspcd {
namespace {

struct Patches : testing::PatchCandidates {
  ContactManifold build(int per_pair, ManifoldReduction reduction = ManifoldReduction::kForce,
                        int reference = tol::kManifoldReferencePairContacts) const {
    ManifoldOptions options;
    options.max_per_pair = per_pair;
    options.reduction = reduction;
    options.reference_per_pair = reference;
    return build_with(options);
  }
};

// The contacts of patch p, in order.
// A flat 5 x 5 grid face on a face (2 mm apart), its depth rising along x from 0.5 mm.
Patches tilted_grid() {
  Patches s;
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 5; ++j) {
      s.add(0, Vec3(0.002 * i, 0.002 * j, 0), Vec3::UnitZ(), 0.0005 + 0.0001 * i);
    }
  }
  return s;
}

std::vector<TriContact> of_patch(const ContactManifold& m, std::size_t p) {
  std::vector<TriContact> out;
  EXPECT_EQ(m.contact_patch.size(), m.contacts.size());
  for (std::size_t i = 0; i < m.contacts.size(); ++i) {
    if (m.contact_patch[i] == p) out.push_back(m.contacts[i]);
  }
  return out;
}

struct Checked {
  double force = 0;     // D, the reference's summed depth
  double diameter = 0;  // the largest distance between two reference points
};

// The bound of build_contact_manifold ("Force reduction") for one patch with normal `nrm`: `kept`
// against its reference set `reference` (the support reduction's points at the reference budget).
Checked expect_force_bound(const std::vector<TriContact>& reference,
                           const std::vector<TriContact>& kept, const Vec3& nrm) {
  Checked out;
  EXPECT_FALSE(kept.empty());
  EXPECT_LE(kept.size(), reference.size());
  if (kept.empty() || kept.size() > reference.size()) return out;
  Vec3 weighted = Vec3::Zero();
  for (const TriContact& c : reference) {
    out.force += c.depth;
    weighted += c.depth * c.pos;
    for (const TriContact& d : reference) {
      out.diameter = std::max(out.diameter, (c.pos - d.pos).norm());
    }
  }
  const double eps = 1e-12 * (out.diameter + 1e-3);
  if (kept.size() == reference.size()) {  // S itself
    for (std::size_t k = 0; k < kept.size(); ++k) {
      EXPECT_EQ(kept[k].pos, reference[k].pos);
      EXPECT_EQ(kept[k].depth, reference[k].depth);
    }
  }
  if (!(out.force > 0)) {
    for (const TriContact& c : kept) EXPECT_EQ(c.depth, 0.0);
    return out;
  }
  const Vec3 centre = weighted / out.force;
  double sum = 0;
  Vec3 moment = Vec3::Zero();
  const Vec3 shift = reference[0].pos - kept[0].pos;
  for (std::size_t k = 0; k < kept.size(); ++k) {
    const TriContact& c = kept[k];
    EXPECT_EQ(c.normal, nrm);
    EXPECT_GE(c.depth, 0.0);
    EXPECT_LE(c.depth, out.force * (1 + 1e-12));  // (4)
    sum += c.depth;
    moment += c.depth * (c.pos - centre).cross(nrm);
    // (3): one shift for all, across N, at most the reference's diameter.
    EXPECT_LE((reference[k].pos - c.pos - shift).norm(), eps);
  }
  EXPECT_LE(std::abs(shift.dot(nrm)), eps);
  EXPECT_LE(shift.norm(), out.diameter + eps);
  EXPECT_NEAR(sum, out.force, 1e-12 * out.force);  // (1)
  // (2), to rounding on coordinates as large as the points' distance from the origin.
  double extent = out.diameter;
  for (const TriContact& c : reference) extent = std::max(extent, c.pos.norm());
  EXPECT_LE(moment.norm(), 1e-12 * out.force * extent);
  return out;
}

// The bound for every patch of a pair: the support reduction at `reference` per pair against the
// force reduction at `per_pair` (the same patches, the same normals); a reference below per_pair
// counts as per_pair.
void expect_pair_bound(const Patches& s, int per_pair, int reference = 8) {
  const ContactManifold ref = s.build(std::max(reference, per_pair), ManifoldReduction::kSupport);
  const ContactManifold red = s.build(per_pair, ManifoldReduction::kForce, reference);
  ASSERT_EQ(ref.patches.size(), red.patches.size());
  EXPECT_LE(red.contacts.size(), static_cast<std::size_t>(per_pair));
  std::size_t counted = 0;
  for (std::size_t p = 0; p < red.patches.size(); ++p) {
    const std::vector<TriContact> kept = of_patch(red, p);
    counted += kept.size();
    if (kept.empty()) continue;  // beyond the budget (the shallowest patches)
    SCOPED_TRACE(p);
    expect_force_bound(of_patch(ref, p), kept, red.patches[p].normal);
  }
  EXPECT_EQ(counted, red.contacts.size());
  // Every patch with a point first, the deepest patch first (step 3's order).
  const std::size_t firsts = std::min(red.patches.size(), static_cast<std::size_t>(per_pair));
  ASSERT_GE(red.contact_patch.size(), firsts);
  for (std::size_t i = 0; i < firsts; ++i) EXPECT_EQ(red.contact_patch[i], i);
}

using testing::same_bits;

// A flat 5 x 5 grid face on a face, tilted in depth along x: at 1, 2 and 3 points the summed depth
// and the centre of pressure of the support reduction's 4 corners; at 4 the corners themselves.
TEST(ForceReduction, AFlatFaceOnAFaceKeepsItsForceAndCentreOfPressure) {
  const Patches s = tilted_grid();
  for (int per_pair = 1; per_pair <= 4; ++per_pair) {
    SCOPED_TRACE(per_pair);
    const ContactManifold m = s.build(per_pair);
    ASSERT_EQ(m.patches.size(), 1u);
    ASSERT_EQ(m.contacts.size(), static_cast<std::size_t>(per_pair));
    expect_pair_bound(s, per_pair);
  }
  // One point: at the centre of pressure, with the summed depth.
  const std::vector<TriContact> ref = s.build(8, ManifoldReduction::kSupport).contacts;
  ASSERT_EQ(ref.size(), 4u);
  double sum = 0;
  Vec3 centre = Vec3::Zero();
  for (const TriContact& c : ref) {
    sum += c.depth;
    centre += c.depth * c.pos;
  }
  const ContactManifold one = s.build(1);
  EXPECT_NEAR(one.contacts[0].depth, sum, 1e-15);
  EXPECT_LE((one.contacts[0].pos - centre / sum).norm(), 1e-15);
  EXPECT_TRUE(same_bits(s.build(4).contacts, ref)) << "the reference budget reached: S itself";
}

// A pinch from both sides of a 2 mm wall: two patches of 4 reference points each; at 4 per pair
// step 3 gives each its deepest point and the rest to the first of equal area (3 and 1), every
// patch with its own force and centre.
TEST(ForceReduction, APinchFromBothSidesKeepsBothForces) {
  Patches s;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const double x = 0.003 * i, y = 0.003 * j;
      s.add(0, Vec3(x, y, 0), Vec3::UnitZ(), 0.0005 + 0.0002 * i);
      s.add(1, Vec3(x, y, 0.002), -Vec3::UnitZ(), 0.0004 + 0.0001 * j);
    }
  }
  const ContactManifold m = s.build(4);
  ASSERT_EQ(m.patches.size(), 2u);
  ASSERT_EQ(m.contacts.size(), 4u);
  EXPECT_EQ(of_patch(m, 0).size(), 3u);
  EXPECT_EQ(of_patch(m, 1).size(), 1u);
  for (int per_pair = 1; per_pair <= 8; ++per_pair) {
    SCOPED_TRACE(per_pair);
    expect_pair_bound(s, per_pair);
  }
}

// A curved edge line (a cylinder touching a plane; its candidates' normals turn by 30 degrees, the
// patch's is the seed's): collinear points, so 2 or 3 kept points carry the centre by their depths
// or by the shift along the line.
TEST(ForceReduction, ACurvedEdgeLineKeepsItsCentre) {
  Patches s;
  for (int i = 0; i <= 20; ++i) {
    const double t = -0.26 + 0.026 * i;
    s.add(0, Vec3(0.02 * std::sin(t), 0, 0), Vec3(std::sin(t), 0, std::cos(t)),
          0.0002 + 0.00005 * i);
  }
  for (int per_pair = 1; per_pair <= 4; ++per_pair) {
    SCOPED_TRACE(per_pair);
    expect_pair_bound(s, per_pair);
  }
}

// A patch that only touches (every depth 0): its kept points at depth 0, no force invented.
TEST(ForceReduction, APatchOfZeroDepthStaysAtZero) {
  Patches s;
  for (int i = 0; i < 6; ++i) s.add(0, Vec3(0.001 * i, 0.0005 * (i % 2), 0), Vec3::UnitZ(), 0.0);
  const ContactManifold m = s.build(2);
  ASSERT_EQ(m.contacts.size(), 2u);
  for (const TriContact& c : m.contacts) EXPECT_EQ(c.depth, 0.0);
  expect_pair_bound(s, 2);
}

// Random pairs of 1 to 4 patches (random axes, normals within 12 degrees of each, depths capped at
// a max_depth of 2 mm as the MuJoCo layer caps them, a few zero), 1 to 8 points per pair,
// references of 4 to 12: the bound on every kept patch, each depth at most the patch's reference
// count times the cap, and the same bits from a second build.
TEST(ForceReduction, RandomPairsKeepTheBoundAndAreDeterministic) {
  std::mt19937 rng(20261126);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_real_distribution<double> depth(0.0, 0.005);
  const double max_depth = 0.002;
  for (int trial = 0; trial < 300; ++trial) {
    SCOPED_TRACE(trial);
    Patches s;
    const int groups = 1 + trial % 4;
    for (int g = 0; g < groups; ++g) {
      const Vec3 axis = Vec3(unit(rng), unit(rng), unit(rng) + 1e-3).normalized();
      const Vec3 origin = 0.05 * Vec3(unit(rng), unit(rng), unit(rng));
      const int count = 1 + static_cast<int>((trial * 7 + g * 13) % 30);
      for (int i = 0; i < count; ++i) {
        const Vec3 tilt = 0.12 * Vec3(unit(rng), unit(rng), unit(rng));
        const Vec3 n = (axis + tilt - tilt.dot(axis) * axis).normalized();
        const Vec3 pos = origin + Vec3(0.01 * unit(rng), 0.01 * unit(rng), 0.001 * unit(rng));
        s.add(g, pos, n, i % 7 == 3 ? 0.0 : std::min(depth(rng), max_depth));
      }
    }
    const int per_pair = 1 + trial % 8;
    const int reference = 4 + trial % 9;
    expect_pair_bound(s, per_pair, reference);
    const ContactManifold m = s.build(per_pair, ManifoldReduction::kForce, reference);
    const ContactManifold ref = s.build(std::max(reference, per_pair), ManifoldReduction::kSupport);
    for (std::size_t i = 0; i < m.contacts.size(); ++i) {
      const double share = static_cast<double>(of_patch(ref, m.contact_patch[i]).size());
      EXPECT_LE(m.contacts[i].depth, share * max_depth * (1 + 1e-12));
    }
    EXPECT_TRUE(
        same_bits(m.contacts, s.build(per_pair, ManifoldReduction::kForce, reference).contacts));
  }
}

// Each reduced point's gain is its patch's |S| / m (1 where S is kept whole), and a reused
// contact's depth follows it: geom2 pushed deeper by h along the normal deepens the m points by
// |S| / m h each, the patch's sum by |S| h, as the reference's |S| points would deepen.
TEST(ForceReduction, GainsKeepTheSummedDepthOfReusedContacts) {
  const Patches s = tilted_grid();
  for (int per_pair = 1; per_pair <= 4; ++per_pair) {
    SCOPED_TRACE(per_pair);
    const ContactManifold m = s.build(per_pair);
    ASSERT_EQ(m.contact_gain.size(), m.contacts.size());
    const std::size_t set = of_patch(s.build(8, ManifoldReduction::kSupport), 0).size();
    for (double g : m.contact_gain) {
      EXPECT_EQ(g, static_cast<double>(set) / static_cast<double>(m.contacts.size()));
    }
    ReusedContacts kept;
    kept.store(Pose{}, m.contacts, m.contact_gain);
    Pose deeper;
    const double h = 1e-5;
    deeper.t = Vec3(0, 0, -h);  // geom2 (above, pushing down along -z) moves further in
    std::vector<TriContact> out;
    ASSERT_TRUE(kept.refresh(deeper, 0.02, 0.02, 1e-4, out));
    double before = 0, after = 0;
    for (std::size_t k = 0; k < out.size(); ++k) {
      before += m.contacts[k].depth;
      after += out[k].depth;
    }
    EXPECT_NEAR(after - before, static_cast<double>(set) * h, 1e-15);
  }
}

// The option leaves the default alone: the default options are the support reduction, and the
// force reduction at the reference budget gives its points bit for bit.
TEST(ForceReduction, AtTheReferenceBudgetItIsTheSupportReduction) {
  EXPECT_EQ(ManifoldOptions{}.reduction, ManifoldReduction::kSupport);
  EXPECT_EQ(ManifoldOptions{}.reference_per_pair, tol::kManifoldReferencePairContacts);
  Patches s;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      s.add(0, Vec3(0.003 * i, 0.003 * j, 0), Vec3::UnitZ(), 0.0005 + 0.0002 * i);
      s.add(1, Vec3(0.003 * i, 0.003 * j, 0.002), -Vec3::UnitZ(), 0.0004);
    }
  }
  const ContactManifold support = build_contact_manifold_by_ids(s.candidates, s.a, s.b);
  EXPECT_EQ(support.contacts.size(), 8u);
  EXPECT_TRUE(same_bits(support.contacts, s.build(8).contacts));
  EXPECT_EQ(support.contact_patch, s.build(8).contact_patch);
}

}  // namespace
}  // namespace graspcd
