// Contacts reused across steps: the drift bounds and the refresh of kept contacts.
#include "graspcd/core/reused_contacts.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

namespace graspcd {
namespace {

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
