// Contacts reused across physics steps.
//
// A pair's contacts from one exact query, kept and refreshed while the pair moves little, after
// Bullet's persistent manifold (btPersistentManifold::refreshContactPoints, Coumans): each contact
// is stored as its point on geom1's surface (geom1 frame) and its point on geom2's surface (geom2
// frame); at a later relative pose the point on geom2 is moved with geom2, and the depth is the
// penetration of the two points along the stored normal. What is not refreshed: the normal (it
// stays the patch normal of the exact query, though the pair may have turned by up to about the
// drift over the larger geom's radius since), and the set of points: a region that begins or ends
// to touch within the drift is seen only at the next exact query. A refreshed depth and the exact
// one at the same pose each moved at most the drift from the query's, so they differ by at most
// twice the drift (nonconvex_contacts_test checks it against exact queries), and a missed region is
// at most the drift deep.
#pragma once

#include <vector>

#include "graspcd/core/geometry.h"
#include "graspcd/core/triangle_contact.h"

namespace graspcd {

// A bound on how far any point of geom2 within `radius` of geom2's origin moved relative to geom1
// between the relative poses `from` and `to`: |t - t0| + ||R - R0||_2 radius, with the spectral
// norm of R - R0 = R0 (R0^T R - I) taken as its Frobenius norm over sqrt(2) (a rotation's
// difference from the identity has singular values 2 sin(theta / 2) twice and 0).
double pose_drift(const Pose& from, const Pose& to, double radius);

// A bound on how far any point of geom2 within `radius_b` of geom2's origin and within `radius_a`
// of geom1's origin (at `from` or at `to`) moved relative to geom1: the smaller of pose_drift(from,
// to, radius_b), which bounds every point of geom2 within `radius_b` of its own origin, and the
// same bound seen from geom2, |R^T t - R0^T t0| + ||R - R0||_2 radius_a (pose_drift of the inverse
// poses: geom1's points within `radius_a` of its origin moved by that relative to geom2, and a
// point of geom2 at such a point by as much the other way). With radius_a and radius_b the geoms'
// radii it bounds the motion of every point of geom2 that can touch geom1 (one inside geom1 lies
// within its radius); the second bound is the smaller one when geom1 is the smaller geom, e.g. a
// finger segment on the object.
double contact_drift(const Pose& from, const Pose& to, double radius_a, double radius_b);

class ReusedContacts {
 public:
  // Keeps `contacts` (geom1 frame, as the manifold gave them) computed at the relative pose
  // `pose` (geom2 in geom1), with each contact's gain (ContactManifold::contact_gain: how much its
  // reported depth changes per unit of penetration; empty: 1 each). No contacts: nothing is kept
  // (a pair apart is always queried).
  void store(const Pose& pose, const std::vector<TriContact>& contacts,
             const std::vector<double>& gains = {});
  // The kept contacts' gains (1 each unless store was given others), in the order of `out`.
  const std::vector<double>& gains() const { return gains_; }
  void clear() { valid_ = false; }
  bool valid() const { return valid_; }

  // The kept contacts at `pose`, into `out`, when some are kept, every point of geom2 that can
  // touch geom1 moved at most `max_drift` (metres, > 0) since they were computed, the pair turned
  // by at most `max_drift` at the larger geom's rim, and none of them separated (refreshed depth
  // < 0; a contact's depth changes by its gain times the penetration change of its two points):
  // then true. The motion is contact_drift with geom1's radius `radius_a` (widened to reach
  // the kept points on geom2) and geom2's radius `radius_b`, each about its geom's origin; the
  // turn is held too because the normal is not refreshed (docs/performance.md, "Contact reuse:
  // where it fails"). At the very pose they were computed at, exactly the stored contacts.
  // Otherwise false and `out` unspecified: the caller queries exactly (and stores again).
  bool refresh(const Pose& pose, double radius_a, double radius_b, double max_drift,
               std::vector<TriContact>& out) const;

 private:
  bool valid_ = false;
  double reach_ = 0;  // the farthest kept point on geom2 from geom1's origin, at the query's pose
  Pose pose_;
  std::vector<TriContact> contacts_;
  std::vector<double> gains_;
  std::vector<Vec3> on_b_;  // each contact's point on geom2's surface, in geom2's frame
};

}  // namespace graspcd
