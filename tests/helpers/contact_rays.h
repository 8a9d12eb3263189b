// Poses around contact for the agreement tests: rays along which one mesh leaves another, the
// transition bracketed by bisection with the caller's own intersection test. Shared by the tree
// agreement checks (tree_agreement.h, CGAL as the truth) and the FCL peer test (ours as the
// reference).
#pragma once

#include <gtest/gtest.h>

#include <vector>

#include "graspcd/core/obb_tree.h"
#include "graspcd/support/random_geometry.h"

namespace graspcd::testing {

// A ray of poses of b around a: a random rotation, and offsets s along a random direction from
// the placement that puts b's root box centre on a's; [lo, hi] brackets the transition from
// "intersect" (lo) to "not" (hi) to within 60 bisections (1e-18 of the size).
struct ContactRay {
  Pose pose;  // the rotation, and the translation at s = 0
  Vec3 dir = Vec3::UnitX();
  double lo = 0, hi = 0;
  Pose at(double s) const {
    Pose p = pose;
    p.t = pose.t + s * dir;
    return p;
  }
};

// `directions` rays whose transition `hits` (a pose -> bool, true when the meshes intersect)
// finds within [0, 2 size]; a ray that starts outside or never leaves is drawn again (at most
// 4 directions attempts, and a test failure if too few rays were found).
template <class Hits>
std::vector<ContactRay> contact_rays(const ObbTree& ta, const ObbTree& tb, double size,
                                     int directions, Rng& rng, Hits hits) {
  std::vector<ContactRay> rays;
  for (int attempt = 0; static_cast<int>(rays.size()) < directions && attempt < 4 * directions;
       ++attempt) {
    ContactRay ray;
    ray.pose.R = random_rotation(rng);
    ray.dir = random_unit(rng);
    ray.pose.t = ta.root().box.center - ray.pose.R * tb.root().box.center;
    double lo = -1, hi = 2 * size;
    for (int i = 0; i < 16 && lo < 0; ++i) {
      if (hits(ray.at(size * i / 16.0))) lo = size * i / 16.0;
    }
    if (lo < 0 || hits(ray.at(hi))) continue;
    for (int i = 0; i < 60; ++i) {
      const double mid = 0.5 * (lo + hi);
      (hits(ray.at(mid)) ? lo : hi) = mid;
    }
    ray.lo = lo;
    ray.hi = hi;
    rays.push_back(ray);
  }
  EXPECT_EQ(static_cast<int>(rays.size()), directions);
  return rays;
}

}  // namespace graspcd::testing
