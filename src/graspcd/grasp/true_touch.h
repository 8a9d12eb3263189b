// Whether the hand touches the object, decided on the true meshes (docs/design.md, "Semantics";
// docs/run-record.md): a hand geom touches the object when their true surfaces come within a
// tolerance, kTouchDistance plus, for a simulator that collides an inflated surface, its
// inflation. Never from a simulator's contacts, so that a phantom contact cannot make a grip and
// graspcd's own run agrees with its judged record.
//
// The hand geoms: every geom outside the object's body tree, the world body and the support's
// body tree that the contype/conaffinity filter lets collide with an object geom and that has a
// surface (a mesh or a primitive; planes and height fields have none here). Surfaces are the
// geoms' triangles in their own frames (true_surfaces.h), each built into an OBB tree the first
// time it is needed, in a SurfaceCache (surface_cache.h) the caller may share with the start
// check and the true penetration.
#pragma once

#include <mujoco/mujoco.h>

#include <memory>
#include <optional>
#include <vector>

#include "graspcd/core/geometry.h"
#include "graspcd/grasp/surface_cache.h"

namespace graspcd::grasp {

// How close two true surfaces must come to touch, m: the judge's phantom distance
// (study/contact_judge.h, kPhantomDistance), so that a contact the judge does not call phantom
// is a touch here.
inline constexpr double kTouchDistance = 1e-3;

// The hand's touch of the object at one state: how many hand geoms touch it, whether two of them
// push from opposing sides, and the mean of the touching places (world), none without a touch.
// A hand geom pushes along the sum, over its triangle pairs within the tolerance, of the object
// triangle's unit normal turned to point from the hand triangle's centroid into the object; two
// hand geoms oppose when their sums have a negative dot product.
struct GripTouch {
  int touching = 0;
  bool opposing = false;
  std::optional<Vec3> point;
};

class TrueTouch {
 public:
  // `truth`: the model whose geoms are the true surfaces (the run's, or a decomposed scene's
  // true_object_model); `object_body` its object's body; `support_root` the root of the
  // support's body tree (-1: none, the world only); `tolerance`, m; `surfaces` the geoms'
  // surfaces, kept by the caller (null: built here).
  TrueTouch(const mjModel* truth, int object_body, int support_root, double tolerance,
            SurfaceCache* surfaces = nullptr);
  ~TrueTouch();
  TrueTouch(const TrueTouch&) = delete;
  TrueTouch& operator=(const TrueTouch&) = delete;

  double tolerance() const { return tolerance_; }

  // Whether a hand geom touches the object at the state `d` (its geom placements). For a
  // sequence of states: each pair keeps its distance at its last query and the pose then, and
  // is queried again only when its motion since could have changed the answer (a distance moves
  // no more than the hand geom's points do in the object's frame, |R1 - R0|_F r + |t1 - t0|), so
  // that following a held object costs little; the answers are those of querying every time.
  bool touching(const mjData* d);
  // The same answer without the pairs' history (the end of a direction of the six-direction
  // test, which restarts from the hold's state).
  bool touching_now(const mjData* d);
  // Every touching triangle pair of every hand geom at the state `d` (the start of the lift).
  GripTouch grip(const mjData* d);

 private:
  struct Pair;
  // The geom's surface (null: none), its reach noted.
  const GeomSurface* surface(int geom);
  // The pair's distance at `d` when at most the tolerance, else a lower bound of it (up to
  // kTouchDistanceCap; the gap of the geoms' bounding spheres beyond that).
  double query(const mjData* d, const Pair& pair, const Pose& now);

  const mjModel* m_;
  double tolerance_;
  std::unique_ptr<SurfaceCache> own_surfaces_;
  SurfaceCache* surfaces_;
  // By geom id: the farthest vertex from the geom's origin once its surface was fetched, else
  // -1 (MuJoCo's bounding radius, at least as far, stands in).
  std::vector<double> reach_;
  std::vector<Pair> pairs_;  // (object geom, hand geom), in id order
};

}  // namespace graspcd::grasp
