// Contacts MuJoCo's solver can use, made from the intersecting triangle pairs of the tree query.
// Pure geometry (no MuJoCo; the MuJoCo seam writes them into mjContact, graspcd/mujoco): everything
// is in geom1's frame, geom2's triangles already posed.
//
// Orientation: mesh faces are assumed counter-clockwise seen from outside (outward normals), as
// in a closed, consistently oriented mesh; the normal's sign comes from that orientation.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "graspcd/core/geometry.h"
#include "graspcd/core/mesh_features.h"
#include "graspcd/core/tolerances.h"
#include "graspcd/core/triangle_contact.h"

namespace graspcd {

// Chooses at most `k` of `contacts` (indices, the deepest first): the deepest contact, then
// farthest-point sampling on positions (Gonzalez 1985: each next contact maximises its distance
// to the chosen ones; ties go to the deeper one), which keeps a spread over the contact region.
// Returns all indices, deepest first, when there are at most k.
std::vector<std::size_t> select_contacts(const std::vector<TriContact>& contacts, std::size_t k);

// ---- The contact manifold of a geom pair
// ---------------------------------------------------------
//
// MuJoCo's solver wants few, well-spread contacts per pair with consistent normals and depths, not
// one contact per intersecting triangle pair (a fingertip in a cup wall gives dozens). The
// manifold groups a pair's triangle-pair contacts into patches and keeps a few points of each.

struct ManifoldOptions {
  int max_per_patch = tol::kManifoldPatchContacts;  // points kept per patch (>= 1)
  int max_per_pair = tol::kManifoldPairContacts;    // points kept per geom pair (>= 1)
  double patch_cosine = tol::kPatchNormalCosine;    // see tolerances.h
};

struct ContactPatch {
  Vec3 normal = Vec3::UnitZ();        // the seed's (the deepest candidate's) normal, unit
  double depth = 0;                   // the deepest member's depth along `normal`
  double area = 0;                    // area of the kept points' convex hull across `normal`
  std::vector<std::size_t> members;   // indices into the candidates, deepest first
  std::vector<std::size_t> selected;  // the patch's chosen points (indices), in choice order
};

struct ContactManifold {
  std::vector<ContactPatch> patches;  // the deepest patch first
  // What the solver gets: at most max_per_pair points, each with its patch's normal and its depth
  // along it; the deepest point of every patch first (deepest patch first), then the patches'
  // further points, the patch of largest area first.
  std::vector<TriContact> contacts;
};

// Builds the manifold of one geom pair from its candidates: candidate i is the contact of the
// intersecting triangles faces_a[i] (geom1) and faces_b[i] (geom2, in any one frame: only equal
// coordinates matter). Deterministic: the result depends on the candidates' order only through
// ties, so callers pass them in the sorted order of their triangle pairs.
//
// 1. Patches: the deepest unassigned candidate seeds a patch, which grows breadth-first through
//    candidates whose triangles share a vertex (exactly equal coordinates) with a member's on
//    either geom -- consecutive triangle pairs along one intersection curve share a triangle --
//    and whose normal lies within acos(patch_cosine) of the seed's. A finger pinching a wall from
//    both sides, or touching two walls of a corner, gives one patch per side; a flat face on a
//    flat face gives one.
// 2. Points of a patch (at most max_per_patch), in the patch plane (positions projected across
//    the patch normal): the deepest member; then the member farthest from it; then each next the
//    member that most enlarges the convex hull of those chosen (the support polygon), after the
//    largest-area reduction of Jolt Physics (PruneContactPoints in ManifoldBetweenTwoFaces.cpp,
//    which keeps 4); when no member enlarges it (collinear points), the one farthest from the
//    chosen. Ties go to the deeper, then the earlier candidate.
// 3. The pair's budget as described at ContactManifold::contacts.
// Each kept point keeps its position; its normal is the patch's and its depth the candidate's
// depth times the cosine between its normal and the patch's (its penetration along the patch
// normal), so the points of a patch push along one direction. What is lost: the other candidates
// (the full triangle-pair list stays with the caller: validate, meshpair and the study use it),
// and patches beyond max_per_pair (the shallowest).
ContactManifold build_contact_manifold(const std::vector<TriContact>& candidates,
                                       const std::vector<Triangle>& faces_a,
                                       const std::vector<Triangle>& faces_b,
                                       const ManifoldOptions& options = {});

// The same manifold from the candidates' triangles given as welded vertex ids (ids of one geom
// from one weld_vertex_ids call, e.g. kept with the geom's tree): what the MuJoCo seam calls, with
// no coordinates to compare per candidate. Ids must be below 2^31. (A name of its own: an
// overload would make build_contact_manifold(c, {}, {}) ambiguous.)
ContactManifold build_contact_manifold_by_ids(const std::vector<TriContact>& candidates,
                                              const std::vector<FaceVertexIds>& vertices_a,
                                              const std::vector<FaceVertexIds>& vertices_b,
                                              const ManifoldOptions& options = {});

// ---- Contacts reused across physics steps (opt-in)
// ---------------------------------------------------------
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
  // `pose` (geom2 in geom1). No contacts: nothing is kept (a pair apart is always queried).
  void store(const Pose& pose, const std::vector<TriContact>& contacts);
  void clear() { valid_ = false; }
  bool valid() const { return valid_; }

  // The kept contacts at `pose`, into `out`, when some are kept, every point of geom2 that can
  // touch geom1 moved at most `max_drift` (metres, > 0) since they were computed, the pair turned
  // by at most `max_drift` at the larger geom's rim, and none of them separated (refreshed depth
  // < 0): then true. The motion is contact_drift with geom1's radius `radius_a` (widened to reach
  // the kept points on geom2) and geom2's radius `radius_b`, each about its geom's origin; the
  // turn is held too because the normal is not refreshed (without it, the PD-driven hand of
  // hard_scenes_test on example 3 keeps the object moving at 11-14 mm/s at 20-30 um, against
  // 0.7-1.3 mm/s with it). At the very pose they were computed at, exactly the stored contacts.
  // Otherwise false and `out` unspecified: the caller queries exactly (and stores again).
  bool refresh(const Pose& pose, double radius_a, double radius_b, double max_drift,
               std::vector<TriContact>& out) const;

 private:
  bool valid_ = false;
  double reach_ = 0;  // the farthest kept point on geom2 from geom1's origin, at the query's pose
  Pose pose_;
  std::vector<TriContact> contacts_;
  std::vector<Vec3> on_b_;  // each contact's point on geom2's surface, in geom2's frame
};

}  // namespace graspcd
