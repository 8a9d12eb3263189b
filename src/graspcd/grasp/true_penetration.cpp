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

// A geom's true surface in its own frame: its tree, whether it bounds a solid, its vertices (each
// once) and its probes (vertices and edge points at most kTrueProbeSpacing apart, each once),
// grouped by the tree's triangles: the probes of triangle k (in the tree's leaf order) are
// probes[probe_start[k], probe_start[k + 1]), so that a query takes only those of the leaves
// whose boxes meet the other solid's box.
struct TruePenetrationWatch::Surface {
  ObbTree tree;
  bool closed = false;
  std::vector<Vec3> vertices;
  std::vector<Vec3> probes;
  std::vector<std::size_t> probe_start;
  double radius = 0;  // the farthest probe from the geom's origin, m
};

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

TruePenetrationWatch::~TruePenetrationWatch() = default;

TruePenetrationWatch::TruePenetrationWatch(const mjModel* truth, int object_body, int support_root)
    : surfaces_(static_cast<std::size_t>(truth->ngeom)), truth_(truth) {
  const mjModel* m = truth;
  const int root = m->body_rootid[object_body];
  const auto in_object = [&](int g) { return m->body_rootid[m->geom_bodyid[g]] == root; };
  const auto surface = [&](int g) -> Surface* {
    std::unique_ptr<Surface>& s = surfaces_[static_cast<std::size_t>(g)];
    if (s) return s.get();
    std::vector<Triangle> local = geom_triangles(m, g);
    if (local.empty()) return nullptr;
    s = std::make_unique<Surface>();
    s->tree = ObbTree::build(std::move(local));
    s->closed = closedness(s->tree).closed();
    // Each probe once, kept with the first triangle (in leaf order) that has it.
    std::vector<std::pair<Vec3, std::size_t>> probes;
    const std::vector<Triangle>& triangles = s->tree.triangles();
    for (std::size_t f = 0; f < triangles.size(); ++f) {
      const Triangle& t = triangles[f];
      for (int k = 0; k < 3; ++k) {
        const Vec3& a = t.v[static_cast<std::size_t>(k)];
        const Vec3& b = t.v[static_cast<std::size_t>((k + 1) % 3)];
        probes.emplace_back(a, f);
        s->vertices.push_back(a);
        const int n = static_cast<int>(std::ceil((b - a).norm() / kTrueProbeSpacing));
        for (int i = 1; i < n; ++i) {
          probes.emplace_back(a + (b - a) * (static_cast<double>(i) / n), f);
        }
      }
    }
    const auto less = [](const Vec3& a, const Vec3& b) {
      return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
    };
    std::sort(s->vertices.begin(), s->vertices.end(), less);
    s->vertices.erase(std::unique(s->vertices.begin(), s->vertices.end()), s->vertices.end());
    std::sort(probes.begin(), probes.end(), [&less](const auto& a, const auto& b) {
      return less(a.first, b.first) || (a.first == b.first && a.second < b.second);
    });
    probes.erase(std::unique(probes.begin(), probes.end(),
                             [](const auto& a, const auto& b) { return a.first == b.first; }),
                 probes.end());
    std::stable_sort(probes.begin(), probes.end(),
                     [](const auto& a, const auto& b) { return a.second < b.second; });
    s->probe_start.assign(triangles.size() + 1, 0);
    for (const auto& [p, f] : probes) {
      s->probes.push_back(p);
      ++s->probe_start[f + 1];
    }
    for (std::size_t f = 0; f < triangles.size(); ++f) s->probe_start[f + 1] += s->probe_start[f];
    for (const Vec3& p : s->probes) s->radius = std::max(s->radius, p.norm());
    return s.get();
  };
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
      const Surface* object = surface(o);
      const int type = m->geom_type[g];
      if (object == nullptr) break;  // a plane or height field as the object: nothing to probe
      if (type == mjGEOM_PLANE) {
        pair.plane = true;
      } else {
        const Surface* other = surface(g);
        if (other == nullptr) {
          result_.unmeasured.push_back(pair.name + " (a " + mujoco::geom_type_name(type) +
                                       ") is not measured against the object");
          continue;
        }
        pair.object_in_other = other->closed;
        pair.other_in_object = object->closed;
        if (!other->closed && !object->closed) {
          result_.unmeasured.push_back(pair.name + " and the object's " + geom_label(m, o) +
                                       " are both open meshes: not measured");
          continue;
        }
        for (const int open : {o, g}) {
          const Surface* s = surfaces_[static_cast<std::size_t>(open)].get();
          if (s->closed || partial[static_cast<std::size_t>(open)]) continue;
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
  std::vector<std::int32_t> stack;
  for (Pair& pair : pairs_) {
    const int o = pair.object;
    const int g = pair.other;
    const Surface& object = *surfaces_[static_cast<std::size_t>(o)];
    double depth = 0;
    if (pair.plane) {
      // The plane's solid is the half-space below it (its z axis points out).
      const Vec3 normal = mujoco::from_row_major(d->geom_xmat + 9 * g).col(2);
      const Vec3 at = mujoco::geom_position(d, g);
      const Pose pose{mujoco::from_row_major(d->geom_xmat + 9 * o), mujoco::geom_position(d, o)};
      // A triangle's depth below a plane is deepest at a vertex.
      for (const Vec3& p : object.vertices) {
        depth = std::max(depth, -normal.dot(apply_pose(pose, p) - at));
      }
    } else {
      const double gap = (mujoco::geom_position(d, o) - mujoco::geom_position(d, g)).norm() -
                         m->geom_rbound[o] - m->geom_rbound[g];
      if (gap > 0) continue;
      const Surface& other = *surfaces_[static_cast<std::size_t>(g)];
      // A pair that moved too little since its last measure to pass the deepest of its side is
      // not measured again: a probe's depth (its distance to the surface inside, 0 outside) moves
      // no more than the probe, and the probes of the other geom in the object's frame, and of
      // the object in the other's, moved at most |R1 - R0|_F r + |dt| (r the probes' radius), so
      // the pair's depth is at most its last plus that (exact: the maxima are those of measuring
      // every time).
      const Pose now = mujoco::relative_pose(d, o, g);
      if (pair.measured) {
        const Pose& was = pair.last;
        const double turn = (now.R - was.R).norm();  // Frobenius, at least the spectral norm
        const double moved = std::max(
            turn * other.radius + (now.t - was.t).norm(),
            turn * object.radius + (now.R.transpose() * now.t - was.R.transpose() * was.t).norm());
        const double side = pair.support ? result_.support_max : result_.hand_max;
        if (pair.last_depth + moved + 1e-9 < side) continue;
      }
      // The deepest of `probed`'s probes inside `solid`, `p` placing probed in solid's frame: only
      // the probes of the probed tree's leaves whose boxes meet the solid's root box.
      const auto deepest = [&placed, &stack](const Surface& solid, const Surface& probed,
                                             const Pose& p) {
        const Pose inverse{p.R.transpose(), -(p.R.transpose() * p.t)};
        const Obb solid_box = transform(inverse, solid.tree.root().box);
        const std::vector<ObbNode>& nodes = probed.tree.nodes();
        placed.clear();
        stack.assign(1, 0);
        while (!stack.empty()) {
          const std::int32_t index = stack.back();
          stack.pop_back();
          const ObbNode& node = nodes[static_cast<std::size_t>(index)];
          if (sat_disjoint(node.box, solid_box)) continue;
          if (!node.is_leaf()) {
            stack.push_back(node.right);
            stack.push_back(index + 1);
            continue;
          }
          const auto first = static_cast<std::size_t>(node.first);
          const auto last = first + static_cast<std::size_t>(node.count);
          for (std::size_t i = probed.probe_start[first]; i < probed.probe_start[last]; ++i) {
            placed.push_back(apply_pose(p, probed.probes[i]));
          }
        }
        return placed.empty() ? 0.0 : deepest_point_inside(solid.tree, placed).depth;
      };
      // relative_pose(d, a, b) places b in a's frame.
      if (pair.object_in_other) {
        depth = std::max(depth, deepest(other, object, mujoco::relative_pose(d, g, o)));
      }
      if (pair.other_in_object) depth = std::max(depth, deepest(object, other, now));
      pair.measured = true;
      pair.last = now;
      pair.last_depth = depth;
    }
    double& side = pair.support ? result_.support_max : result_.hand_max;
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
