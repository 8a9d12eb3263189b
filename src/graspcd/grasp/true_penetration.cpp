#include "graspcd/grasp/true_penetration.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "graspcd/core/containment.h"
#include "graspcd/core/geometry.h"
#include "graspcd/core/obb_tree.h"
#include "graspcd/core/penetration.h"
#include "graspcd/core/sat.h"
#include "graspcd/grasp/true_surfaces.h"
#include "graspcd/mujoco/collision_pose.h"
#include "graspcd/mujoco/primitives.h"

namespace graspcd::grasp {

// An object geom and a geom it may collide with: which ways are tested.
struct TruePenetrationWatch::Pair {
  int object = -1, other = -1;
  bool plane = false;            // the other is a plane: the object's probes below it
  bool object_in_other = false;  // the object's probes inside the other's solid
  bool other_in_object = false;  // the other's probes inside the object's solid
  bool support = false;
  std::string name;  // the other geom's, for the result
  // The last measure of the pair: the other geom in the object's frame then, and its depth.
  bool measured = false;
  Pose last;
  double last_depth = 0;
};

namespace {

// Whether geom g has a true surface (surface_cache.h): a mesh with faces, or a primitive.
bool has_surface(const mjModel* m, int g) {
  const int type = m->geom_type[g];
  if (type == mjGEOM_MESH) return m->geom_dataid[g] >= 0 && m->mesh_facenum[m->geom_dataid[g]] > 0;
  return mujoco::is_primitive(type);
}

}  // namespace

TruePenetrationWatch::~TruePenetrationWatch() = default;

TruePenetrationWatch::TruePenetrationWatch(const mjModel* truth, int object_body, int support_root,
                                           SurfaceCache* surfaces)
    : own_surfaces_(surfaces ? nullptr : std::make_unique<SurfaceCache>(truth)),
      surfaces_(surfaces ? surfaces : own_surfaces_.get()),
      truth_(truth) {
  const mjModel* m = truth;
  const int root = m->body_rootid[object_body];
  const auto in_object = [&](int g) { return m->body_rootid[m->geom_bodyid[g]] == root; };
  std::vector<char> partial(static_cast<std::size_t>(m->ngeom), 0);
  for (int o = 0; o < m->ngeom; ++o) {
    if (!in_object(o) || (m->geom_contype[o] == 0 && m->geom_conaffinity[o] == 0)) continue;
    for (int g = 0; g < m->ngeom; ++g) {
      if (in_object(g) || !may_collide(m, o, g)) continue;
      Pair pair;
      pair.object = o;
      pair.other = g;
      pair.name = geom_label(m, g);
      const int body = m->geom_bodyid[g];
      pair.support = body == 0 || m->body_rootid[body] == support_root;
      const int type = m->geom_type[g];
      if (!has_surface(m, o)) break;  // a plane or height field as the object: nothing to probe
      if (type == mjGEOM_PLANE) {
        pair.plane = true;
      } else {
        if (!has_surface(m, g)) {
          result_.unmeasured.push_back(pair.name + " (a " + mujoco::geom_type_name(type) +
                                       ") is not measured against the object");
          continue;
        }
        const bool object_closed = surfaces_->closed(o);
        const bool other_closed = surfaces_->closed(g);
        pair.object_in_other = other_closed;
        pair.other_in_object = object_closed;
        if (!other_closed && !object_closed) {
          result_.unmeasured.push_back(pair.name + " and the object's " + geom_label(m, o) +
                                       " are both open meshes: not measured");
          continue;
        }
        for (const auto& [open, closed] :
             {std::pair{o, object_closed}, std::pair{g, other_closed}}) {
          if (closed || partial[static_cast<std::size_t>(open)]) continue;
          partial[static_cast<std::size_t>(open)] = 1;
          result_.partial.push_back(
              geom_label(m, open) + (open == o ? " (the object)" : "") +
              " is not closed: nothing is tested inside it, only its probes inside the closed "
              "geoms it meets");
        }
      }
      pairs_.push_back(std::move(pair));
    }
  }
  result_.pairs = static_cast<int>(pairs_.size());
}

void TruePenetrationWatch::measure(const mjData* d, long step, double time,
                                   const std::string& phase) {
  const mjModel* m = truth_;
  ++result_.measures;
  std::vector<Vec3> placed;
  for (Pair& pair : pairs_) {
    const int o = pair.object;
    const int g = pair.other;
    double& side = pair.support ? result_.support_max : result_.hand_max;
    double depth = 0;
    if (pair.plane) {
      // The plane's solid is the half-space below it (its z axis points out).
      const Vec3 normal = mujoco::from_row_major(d->geom_xmat + 9 * g).col(2);
      const Vec3 at = mujoco::geom_position(d, g);
      const Pose pose{mujoco::from_row_major(d->geom_xmat + 9 * o), mujoco::geom_position(d, o)};
      const GeomSurface& object = *surfaces_->surface(o);
      // The vertices lie in their box along the geom's axes: none lies deeper than its deepest
      // corner, and one no deeper than the side's deepest so far changes nothing.
      const Vec3 n = pose.R.transpose() * normal;
      const double corner = -normal.dot(apply_pose(pose, object.aligned_center()) - at) +
                            n.cwiseAbs().dot(object.aligned_half());
      if (corner <= side) continue;
      // A triangle's depth below a plane is deepest at a vertex.
      for (const Vec3& p : object.vertices()) {
        depth = std::max(depth, -normal.dot(apply_pose(pose, p) - at));
      }
    } else {
      const double gap = (mujoco::geom_position(d, o) - mujoco::geom_position(d, g)).norm() -
                         m->geom_rbound[o] - m->geom_rbound[g];
      if (gap > 0) continue;
      const GeomSurface& object = *surfaces_->surface(o);
      const GeomSurface& other = *surfaces_->surface(g);
      // A pair that moved too little since its last measure to pass the deepest of its side is
      // not measured again: a probe's depth (its distance to the surface inside, 0 outside) moves
      // no more than the probe, and the probes of the other geom in the object's frame, and of
      // the object in the other's, moved at most |R1 - R0|_F r + |dt| (r the surfaces' radius, a
      // probe lying between vertices), so the pair's depth is at most its last bound plus that
      // (exact: the maxima are those of measuring every time).
      const Pose now = mujoco::relative_pose(d, o, g);
      if (pair.measured) {
        const Pose& was = pair.last;
        const double turn = (now.R - was.R).norm();  // Frobenius, at least the spectral norm
        const double moved =
            std::max(turn * other.radius() + (now.t - was.t).norm(),
                     turn * object.radius() +
                         (now.R.transpose() * now.t - was.R.transpose() * was.t).norm());
        if (pair.last_depth + moved + 1e-9 < side) continue;
      }
      // Only the probes that could lie deeper than the side's deepest so far are tested
      // (deepest_probe_inside); the pair's bound keeps what the others could reach.
      double bound = 0;
      const auto deepest = [&](const GeomSurface& solid, const GeomSurface& probed, const Pose& p) {
        const ProbeDepth found =
            deepest_probe_inside(solid, probed, p, kTrueProbeSpacing, side, placed);
        bound = std::max(bound, found.bound);
        return found.depth;
      };
      // relative_pose(d, a, b) places b in a's frame.
      if (pair.object_in_other) {
        depth = std::max(depth, deepest(other, object, mujoco::relative_pose(d, g, o)));
      }
      if (pair.other_in_object) depth = std::max(depth, deepest(object, other, now));
      pair.measured = true;
      pair.last = now;
      pair.last_depth = bound;
    }
    side = std::max(side, depth);
    if (depth > result_.max) {
      result_.max = depth;
      result_.step = step;
      result_.time = time;
      result_.phase = phase;
      result_.geom = pair.name;
      result_.side = pair.support ? "support" : "hand";
    }
  }
}

}  // namespace graspcd::grasp
