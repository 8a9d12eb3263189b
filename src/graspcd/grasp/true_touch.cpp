#include "graspcd/grasp/true_touch.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "graspcd/core/obb_tree.h"
#include "graspcd/core/proximity.h"
#include "graspcd/grasp/true_surfaces.h"
#include "graspcd/mujoco/collision_pose.h"

namespace graspcd::grasp {

namespace {

// How far a pair's distance is searched beyond the tolerance, m: a pair found farther than this
// is queried again only after moving about this much.
constexpr double kTouchDistanceCap = 5e-3;

}  // namespace

struct TrueTouch::Pair {
  int object = -1, hand = -1;
  // The last query: the hand geom in the object geom's frame then, and the answer.
  bool queried = false;
  Pose last;
  double value = 0;
};

TrueTouch::~TrueTouch() = default;

TrueTouch::TrueTouch(const mjModel* truth, int object_body, int support_root, double tolerance,
                     SurfaceCache* surfaces)
    : m_(truth),
      tolerance_(tolerance),
      own_surfaces_(surfaces ? nullptr : std::make_unique<SurfaceCache>(truth)),
      surfaces_(surfaces ? surfaces : own_surfaces_.get()),
      reach_(static_cast<std::size_t>(truth->ngeom), -1.0) {
  const mjModel* m = truth;
  const int root = m->body_rootid[object_body];
  const auto in_object = [&](int g) { return m->body_rootid[m->geom_bodyid[g]] == root; };
  const auto has_surface = [&](int g) {
    const int type = m->geom_type[g];
    return type != mjGEOM_PLANE && type != mjGEOM_HFIELD &&
           (type != mjGEOM_MESH || m->geom_dataid[g] >= 0);
  };
  for (int o = 0; o < m->ngeom; ++o) {
    if (!in_object(o) || !has_surface(o)) continue;
    if (m->geom_contype[o] == 0 && m->geom_conaffinity[o] == 0) continue;
    for (int h = 0; h < m->ngeom; ++h) {
      const int body = m->geom_bodyid[h];
      if (in_object(h) || body == 0 || m->body_rootid[body] == support_root) continue;
      if (!has_surface(h) || !may_collide(m, o, h)) continue;
      Pair pair;
      pair.object = o;
      pair.hand = h;
      pairs_.push_back(pair);
    }
  }
}

const GeomSurface* TrueTouch::surface(int geom) {
  const GeomSurface* s = surfaces_->surface(geom);
  if (s != nullptr) reach_[static_cast<std::size_t>(geom)] = s->radius();
  return s;
}

double TrueTouch::query(const mjData* d, const Pair& pair, const Pose& now) {
  const double gap =
      (mujoco::geom_position(d, pair.object) - mujoco::geom_position(d, pair.hand)).norm() -
      m_->geom_rbound[pair.object] - m_->geom_rbound[pair.hand];
  if (gap > kTouchDistanceCap) return gap;
  const GeomSurface* object = surface(pair.object);
  const GeomSurface* hand = surface(pair.hand);
  if (object == nullptr || hand == nullptr) return kTouchDistanceCap;
  return tree_distance(object->tree(), hand->tree(), now, kTouchDistanceCap, tolerance_);
}

bool TrueTouch::touching(const mjData* d) {
  for (Pair& pair : pairs_) {
    const Pose now = mujoco::relative_pose(d, pair.object, pair.hand);
    if (pair.queried) {
      const double turn = (now.R - pair.last.R).norm();  // Frobenius: at least the spectral norm
      const double known = reach_[static_cast<std::size_t>(pair.hand)];
      const double reach = known >= 0 ? known : m_->geom_rbound[pair.hand];
      const double moved = turn * reach + (now.t - pair.last.t).norm();
      if (pair.value <= tolerance_ && pair.value + moved <= tolerance_) return true;
      if (pair.value > tolerance_ && pair.value - moved > tolerance_) continue;
    }
    pair.value = query(d, pair, now);
    pair.last = now;
    pair.queried = true;
    if (pair.value <= tolerance_) return true;
  }
  return false;
}

bool TrueTouch::touching_now(const mjData* d) {
  for (const Pair& pair : pairs_) {
    if (query(d, pair, mujoco::relative_pose(d, pair.object, pair.hand)) <= tolerance_) {
      return true;
    }
  }
  return false;
}

GripTouch TrueTouch::grip(const mjData* d) {
  GripTouch out;
  std::vector<std::pair<int, Vec3>> pushes;  // hand geom, summed push into the object (world)
  Vec3 sum = Vec3::Zero();
  long points = 0;
  std::vector<NearTriangles> near;
  for (const Pair& pair : pairs_) {
    const double gap =
        (mujoco::geom_position(d, pair.object) - mujoco::geom_position(d, pair.hand)).norm() -
        m_->geom_rbound[pair.object] - m_->geom_rbound[pair.hand];
    if (gap > tolerance_) continue;
    const GeomSurface* object = surface(pair.object);
    const GeomSurface* hand = surface(pair.hand);
    if (object == nullptr || hand == nullptr) continue;
    const Pose now = mujoco::relative_pose(d, pair.object, pair.hand);
    near.clear();
    triangles_within(object->tree(), hand->tree(), now, tolerance_, near);
    if (near.empty()) continue;
    const Mat3 rotation = mujoco::from_row_major(d->geom_xmat + 9 * pair.object);
    const Vec3 origin = mujoco::geom_position(d, pair.object);
    Vec3 push = Vec3::Zero();
    for (const NearTriangles& n : near) {
      const Triangle& t = object->tree().triangles()[static_cast<std::size_t>(n.a)];
      const Triangle h = apply_pose(now, hand->tree().triangles()[static_cast<std::size_t>(n.b)]);
      Vec3 normal = (t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]);
      const double length = normal.norm();
      if (length > 0) {
        normal /= length;
        const Vec3 centroid = (h.v[0] + h.v[1] + h.v[2]) / 3.0;
        if (normal.dot(centroid - t.v[0]) < 0) normal = -normal;
        push -= normal;
      }
      sum += rotation * n.point + origin;
      ++points;
    }
    push = rotation * push;
    auto at = std::find_if(pushes.begin(), pushes.end(),
                           [&pair](const auto& p) { return p.first == pair.hand; });
    if (at == pushes.end()) {
      pushes.emplace_back(pair.hand, push);
    } else {
      at->second += push;
    }
  }
  out.touching = static_cast<int>(pushes.size());
  for (std::size_t a = 0; a < pushes.size() && !out.opposing; ++a) {
    for (std::size_t b = a + 1; b < pushes.size(); ++b) {
      if (pushes[a].second.dot(pushes[b].second) < 0) {
        out.opposing = true;
        break;
      }
    }
  }
  if (points > 0) out.point = sum / static_cast<double>(points);
  return out;
}

}  // namespace graspcd::grasp
