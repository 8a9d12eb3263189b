// The moment reduction of the contact manifold (build_contact_manifold, "Moment reduction"): the
// kept points of each patch push along the proxy's net normal direction, and their moment about
// the centre of pressure per unit force is the proxy's but for its torsion, the bound stated at
// build_contact_manifold, on constructed patches (a flat face on a face, a pinch from both sides, a
// curved edge line, a single point) and random ones; the output is deterministic and the default
// reduction is unchanged by the option.
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
#include "graspcd/core/triangle_contact.h"
#include "helpers/manifold_patches.h"

namespace graspcd::contact_manifold_moment_test {
namespace {

struct Patches : testing::PatchCandidates {
  ContactManifold build(int per_pair, int per_patch = tol::kManifoldPatchContacts,
                        ManifoldReduction reduction = ManifoldReduction::kMoment) const {
    ManifoldOptions options;
    options.max_per_pair = per_pair;
    options.max_per_patch = per_patch;
    options.reduction = reduction;
    return build_with(options);
  }
};

// The proxy of a patch's normal force, computed here from its members as build_contact_manifold
// defines it: weights w_i the depths along the patch's (seed's) normal.
struct Proxy {
  Vec3 direction = Vec3::Zero();  // N
  double force = 0;               // |F|
  Vec3 centre = Vec3::Zero();     // c
  Vec3 moment = Vec3::Zero();     // M about c
  double torsion_bound = 0;       // sum w_i |p_i - c| sin(n_i, N)
  double radius = 0;              // max |p_i - c|
};

Proxy proxy_of(const std::vector<TriContact>& cs, const ContactPatch& patch) {
  std::vector<double> w;
  for (std::size_t i : patch.members) {
    w.push_back(cs[i].depth * std::clamp(cs[i].normal.dot(patch.normal), 0.0, 1.0));
  }
  double sum = 0;
  for (double x : w) sum += x;
  Proxy p;
  Vec3 f = Vec3::Zero();
  for (std::size_t k = 0; k < w.size(); ++k) {
    f += w[k] * cs[patch.members[k]].normal;
    p.centre += w[k] / sum * cs[patch.members[k]].pos;
  }
  p.force = f.norm();
  p.direction = f / p.force;
  for (std::size_t k = 0; k < w.size(); ++k) {
    const TriContact& c = cs[patch.members[k]];
    p.moment += w[k] * (c.pos - p.centre).cross(c.normal);
    p.torsion_bound += w[k] * (c.pos - p.centre).norm() * c.normal.cross(p.direction).norm();
    p.radius = std::max(p.radius, (c.pos - p.centre).norm());
  }
  return p;
}

// Checks the bound of build_contact_manifold on the kept points `kept` of one patch: every normal
// the proxy's direction; the kept force along it; the kept moment about c per unit force the
// proxy's but for the torsion |N . M| / |F|, which is at most the stated bound.
void expect_bound(const Proxy& p, const std::vector<TriContact>& kept) {
  ASSERT_FALSE(kept.empty());
  double depth_sum = 0;
  Vec3 force = Vec3::Zero();
  Vec3 moment = Vec3::Zero();
  for (const TriContact& c : kept) {
    EXPECT_LE((c.normal - p.direction).norm(), 1e-12);
    EXPECT_GE(c.depth, 0.0);
    depth_sum += c.depth;
    force += c.depth * c.normal;
    moment += c.depth * (c.pos - p.centre).cross(c.normal);
  }
  ASSERT_GT(depth_sum, 0.0);
  EXPECT_LE(force.normalized().cross(p.direction).norm(), 1e-12);
  const double torsion = std::abs(p.direction.dot(p.moment)) / p.force;
  const double error = (moment / depth_sum - p.moment / p.force).norm();
  EXPECT_NEAR(error, torsion, 1e-9 * p.radius + 1e-15);
  EXPECT_LE(torsion, p.torsion_bound / p.force + 1e-12 * p.radius);
}

// The kept points of one patch: those whose normal is the patch's proxy direction.
std::vector<TriContact> kept_of(const ContactManifold& m, const Proxy& p) {
  std::vector<TriContact> out;
  for (const TriContact& c : m.contacts) {
    if (c.normal.dot(p.direction) > 0.999) out.push_back(c);
  }
  return out;
}

using testing::same_bits;

// A flat 5 x 5 grid face on a face, 1 mm deep everywhere: the anchor at the grid's centre with the
// depth 1 mm, three extremes, the kept points' depth-weighted centre the centre of pressure.
TEST(MomentReduction, AFlatFaceOnAFaceKeepsItsCentreOfPressure) {
  Patches s;
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 5; ++j) s.add(0, Vec3(0.002 * i, 0.002 * j, 0), Vec3::UnitZ(), 0.001);
  }
  const ContactManifold m = s.build(4);
  ASSERT_EQ(m.patches.size(), 1u);
  ASSERT_EQ(m.contacts.size(), 4u);
  const Proxy p = proxy_of(s.candidates, m.patches[0]);
  EXPECT_LE(p.moment.norm(), 1e-18);
  EXPECT_LE((m.contacts[0].pos - Vec3(0.004, 0.004, 0)).norm(), 1e-15) << "the anchor";
  EXPECT_NEAR(m.contacts[0].depth, 0.001, 1e-15);
  expect_bound(p, m.contacts);
  Vec3 centre = Vec3::Zero();
  double sum = 0;
  for (const TriContact& c : m.contacts) {
    centre += c.depth * c.pos;
    sum += c.depth;
  }
  EXPECT_LE((centre / sum - p.centre).norm(), 1e-15);
}

// A pinch from both sides of a 2 mm wall, the lower face deeper on one side: two patches, both
// anchors kept before any extreme, each patch within the bound, at most 4 in all.
TEST(MomentReduction, APinchFromBothSidesKeepsBothPatches) {
  Patches s;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const double x = 0.003 * i, y = 0.003 * j;
      s.add(0, Vec3(x, y, 0), Vec3::UnitZ(), 0.0005 + 0.0002 * i);
      s.add(1, Vec3(x, y, 0.002), -Vec3::UnitZ(), 0.0004);
    }
  }
  const ContactManifold m = s.build(4);
  ASSERT_EQ(m.patches.size(), 2u);
  ASSERT_EQ(m.contacts.size(), 4u);
  EXPECT_GT(m.contacts[0].normal.dot(Vec3::UnitZ()), 0.999) << "the deeper patch's anchor";
  EXPECT_LT(m.contacts[1].normal.dot(Vec3::UnitZ()), -0.999) << "the other patch's anchor";
  for (const ContactPatch& patch : m.patches) {
    const Proxy p = proxy_of(s.candidates, patch);
    expect_bound(p, kept_of(m, p));
  }
}

// A curved edge line (a cylinder of 2 cm radius along y touching a plane along x), its normals
// turning by 30 degrees over the line and its depths largest at one end: a non-zero moment
// across the normal, no torsion, so the kept moment is the proxy's (to rounding) and the anchor
// leaves the centre of pressure along the line.
TEST(MomentReduction, ACurvedEdgeLineKeepsItsMoment) {
  Patches s;
  for (int i = 0; i <= 20; ++i) {
    const double t = -0.26 + 0.026 * i;  // radians
    s.add(0, Vec3(0.02 * std::sin(t), 0, 0), Vec3(std::sin(t), 0, std::cos(t)),
          0.0002 + 0.00005 * i);
  }
  for (int per_pair : {1, 2, 4}) {
    const ContactManifold m = s.build(per_pair);
    ASSERT_EQ(m.patches.size(), 1u);
    ASSERT_EQ(m.contacts.size(), static_cast<std::size_t>(per_pair));
    const Proxy p = proxy_of(s.candidates, m.patches[0]);
    EXPECT_GT(p.moment.norm() / p.force, 1e-5) << "a moment to keep";
    EXPECT_LE(std::abs(p.moment.dot(p.direction)), 1e-15) << "and no torsion";
    expect_bound(p, m.contacts);
    EXPECT_GT((m.contacts[0].pos - p.centre).norm(), 1e-5) << "per_pair " << per_pair;
  }
}

// Random patches (normals within 12 degrees of one axis, so one patch; depths up to 5 mm, a few
// zero), with 1 to 6 points per pair: the bound on every one, and the same bits from a second
// build.
TEST(MomentReduction, RandomPatchesKeepTheBoundAndAreDeterministic) {
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_real_distribution<double> depth(0.0, 0.005);
  for (int trial = 0; trial < 200; ++trial) {
    Patches s;
    const int count = 1 + trial % 40;
    const Vec3 axis = Vec3(unit(rng), unit(rng), 2.0 + unit(rng)).normalized();
    for (int i = 0; i < count; ++i) {
      const Vec3 tilt = 0.12 * Vec3(unit(rng), unit(rng), unit(rng));
      const Vec3 n = (axis + tilt - tilt.dot(axis) * axis).normalized();
      const Vec3 pos(0.01 * unit(rng), 0.01 * unit(rng), 0.001 * unit(rng));
      s.add(0, pos, n, i % 7 == 3 ? 0.0 : depth(rng));
    }
    const int per_pair = 1 + trial % 6;
    const ContactManifold m = s.build(per_pair);
    ASSERT_EQ(m.patches.size(), 1u) << trial;
    ASSERT_LE(m.contacts.size(), static_cast<std::size_t>(per_pair));
    const Proxy p = proxy_of(s.candidates, m.patches[0]);
    if (!(p.force > 0)) continue;  // every depth 0 (a lone zero-depth candidate)
    SCOPED_TRACE(trial);
    expect_bound(p, m.contacts);
    // The anchor stays within the patch: on these patches its shift from the centre of pressure
    // (the central-axis offset and what the clamp leaves) is at most a third of the radius.
    EXPECT_LE((m.contacts[0].pos - p.centre).norm(), p.radius + 1e-15);
    EXPECT_TRUE(same_bits(m.contacts, s.build(per_pair).contacts));
  }
}

// The option leaves the default alone: the default options are the support reduction, whose
// points are the selected candidates with the seed's normal; the moment reduction's differ.
TEST(MomentReduction, TheDefaultIsTheSupportReductionUnchanged) {
  EXPECT_EQ(ManifoldOptions{}.reduction, ManifoldReduction::kSupport);
  Patches s;
  for (int i = 0; i <= 20; ++i) {
    const double t = -0.26 + 0.026 * i;
    s.add(0, Vec3(0.02 * std::sin(t), 0, 0), Vec3(std::sin(t), 0, std::cos(t)),
          0.0002 + 0.00005 * i);
  }
  const ContactManifold support = build_contact_manifold_by_ids(s.candidates, s.a, s.b);
  EXPECT_TRUE(same_bits(
      support.contacts,
      s.build(tol::kManifoldPairContacts, tol::kManifoldPatchContacts, ManifoldReduction::kSupport)
          .contacts));
  ASSERT_EQ(support.contacts.size(), support.patches[0].selected.size());
  for (std::size_t k = 0; k < support.contacts.size(); ++k) {
    const TriContact& c = s.candidates[support.patches[0].selected[k]];
    EXPECT_EQ(support.contacts[k].pos, c.pos);
    EXPECT_EQ(support.contacts[k].normal, s.candidates[support.patches[0].members[0]].normal);
  }
  EXPECT_FALSE(same_bits(support.contacts, s.build(tol::kManifoldPairContacts).contacts));
}

}  // namespace
}  // namespace graspcd::contact_manifold_moment_test
