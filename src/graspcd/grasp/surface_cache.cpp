#include "graspcd/grasp/surface_cache.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include "graspcd/core/containment.h"
#include "graspcd/core/penetration.h"
#include "graspcd/core/sat.h"
#include "graspcd/grasp/true_surfaces.h"
#include "graspcd/mujoco/geom_trees.h"
#include "graspcd/mujoco/primitives.h"

namespace graspcd::grasp {

namespace {

bool less(const Vec3& a, const Vec3& b) {
  return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
}

// The distance from p to the closed box b (Ericson (2005), 5.1.4).
double point_box_distance(const Vec3& p, const Obb& b) {
  const Vec3 local = b.axes.transpose() * (p - b.center);
  return (local.cwiseAbs() - b.half).cwiseMax(0.0).norm();
}

// The distance from p to some triangle of the tree at most `cap` away, or infinity when there is
// none: a depth-first search that leaves every node whose box lies farther than the cap (a box
// holds its triangles; the comparison leaves a margin for the box's rounding), so that a point far
// from the surface costs a few box tests.
double triangle_within(const ObbTree& tree, const Vec3& p, double cap,
                       std::vector<std::int32_t>& stack) {
  const std::vector<ObbNode>& nodes = tree.nodes();
  const std::vector<Triangle>& triangles = tree.triangles();
  if (nodes.empty()) return std::numeric_limits<double>::infinity();
  const double slack = 1e-9 * (1 + nodes.front().box.half.maxCoeff());
  stack.assign(1, 0);
  while (!stack.empty()) {
    const std::int32_t index = stack.back();
    stack.pop_back();
    const ObbNode& node = nodes[static_cast<std::size_t>(index)];
    if (point_box_distance(p, node.box) - slack > cap) continue;
    if (node.is_leaf()) {
      for (std::int32_t k = 0; k < node.count; ++k) {
        const double d =
            point_triangle_distance(p, triangles[static_cast<std::size_t>(node.first + k)]);
        if (d <= cap) return d;
      }
      continue;
    }
    stack.push_back(node.right);
    stack.push_back(index + 1);
  }
  return std::numeric_limits<double>::infinity();
}

}  // namespace

// MuJoCo 2.2's mesh_graph (built when the model is compiled by qhull, the Quickhull algorithm of
// Barber, Dobkin and Huhdanpaa, ACM TOMS 22(4), 1996; user_mesh.cc, MakeGraph): at
// mesh_graphadr, the ints numvert, numface, then vert_edgeadr[numvert], vert_globalid[numvert],
// edge_localid[numvert + 3 numface] and face_globalid[3 numface], the faces' vertices as indices
// into the mesh's vertices.
std::vector<Triangle> mesh_hull_triangles(const mjModel* m, int mesh_id) {
  const int adr = m->mesh_graphadr[mesh_id];
  if (adr < 0) return {};
  const int* graph = m->mesh_graph + adr;
  const int numvert = graph[0];
  const int numface = graph[1];
  const int* face_globalid = graph + 2 + 3 * numvert + 3 * numface;
  const int vadr = m->mesh_vertadr[mesh_id];
  std::vector<Triangle> out(static_cast<std::size_t>(numface));
  for (int f = 0; f < numface; ++f) {
    Triangle& t = out[static_cast<std::size_t>(f)];
    for (int k = 0; k < 3; ++k) {
      const float* v = m->mesh_vert + 3 * (vadr + face_globalid[3 * f + k]);
      t.v[static_cast<std::size_t>(k)] = Vec3(v[0], v[1], v[2]);
    }
  }
  return out;
}

GeomSurface::GeomSurface(std::vector<Triangle> local) : tree_(ObbTree::build(std::move(local))) {
  closedness_ = graspcd::closedness(tree_);
  for (const Triangle& t : tree_.triangles()) {
    for (const Vec3& v : t.v) vertices_.push_back(v);
  }
  std::sort(vertices_.begin(), vertices_.end(), less);
  vertices_.erase(std::unique(vertices_.begin(), vertices_.end()), vertices_.end());
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -lo;
  for (const Vec3& v : vertices_) {
    radius_ = std::max(radius_, v.norm());
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  aligned_center_ = (lo + hi) / 2;
  aligned_half_ = (hi - lo) / 2;
}

const SurfaceProbes& GeomSurface::probes(double spacing) const {
  const auto found = probes_.find(spacing);
  if (found != probes_.end()) return found->second;
  // Each point with the triangle (in leaf order) it came from; each point kept once, with the
  // first triangle that has it.
  std::vector<std::pair<Vec3, std::size_t>> probes;
  const std::vector<Triangle>& triangles = tree_.triangles();
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const Triangle& t = triangles[f];
    for (int k = 0; k < 3; ++k) {
      const Vec3& a = t.v[static_cast<std::size_t>(k)];
      const Vec3& b = t.v[static_cast<std::size_t>((k + 1) % 3)];
      probes.emplace_back(a, f);
      const int n = static_cast<int>(std::ceil((b - a).norm() / spacing));
      for (int i = 1; i < n; ++i) {
        probes.emplace_back(a + (b - a) * (static_cast<double>(i) / n), f);
      }
    }
  }
  std::sort(probes.begin(), probes.end(), [](const auto& a, const auto& b) {
    return less(a.first, b.first) || (a.first == b.first && a.second < b.second);
  });
  probes.erase(std::unique(probes.begin(), probes.end(),
                           [](const auto& a, const auto& b) { return a.first == b.first; }),
               probes.end());
  std::stable_sort(probes.begin(), probes.end(),
                   [](const auto& a, const auto& b) { return a.second < b.second; });
  SurfaceProbes& out = probes_[spacing];
  out.start.assign(triangles.size() + 1, 0);
  out.points.reserve(probes.size());
  for (const auto& [p, f] : probes) {
    out.points.push_back(p);
    ++out.start[f + 1];
  }
  for (std::size_t f = 0; f < triangles.size(); ++f) out.start[f + 1] += out.start[f];
  return out;
}

ProbeDepth deepest_probe_inside(const GeomSurface& solid, const GeomSurface& probed,
                                const Pose& pose, double spacing, double floor,
                                std::vector<Vec3>& placed) {
  ProbeDepth out;
  const ObbTree& tree = solid.tree();
  const Obb& root = tree.root().box;
  const Pose inverse{pose.R.transpose(), -(pose.R.transpose() * pose.t)};
  const Obb solid_box = transform(inverse, root);  // in the probed surface's frame
  const std::vector<ObbNode>& nodes = probed.tree().nodes();
  const SurfaceProbes& probes = probed.probes(spacing);
  // The probes of the leaves that meet the solid's root box, placed, that lie deeper than the
  // floor inside both boxes; the others' depths inside the boxes bound theirs.
  placed.clear();
  std::vector<std::int32_t> stack;
  stack.reserve(64);
  stack.push_back(0);
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
    for (std::size_t i = probes.start[first]; i < probes.start[last]; ++i) {
      const Vec3 x = apply_pose(pose, probes.points[i]);
      const Vec3 local = root.axes.transpose() * (x - root.center);
      const double in_root = (root.half - local.cwiseAbs()).minCoeff();
      const double in_aligned =
          (solid.aligned_half() - (x - solid.aligned_center()).cwiseAbs()).minCoeff();
      const double inside_boxes = std::min(in_root, in_aligned);
      if (inside_boxes < 0) continue;
      if (inside_boxes <= floor) {
        out.bound = std::max(out.bound, inside_boxes);
        continue;
      }
      placed.push_back(x);
    }
  }
  // Of those, the ones farther from the surface than the floor (and than the deepest so far) and
  // inside the solid, in the order of what they cost: a triangle within that distance (found by
  // a search that visits only the boxes that near), the inside test, and only then the distance
  // to the surface, exactly.
  // A ball free of the surface holds points of one side: the side of a probe inside the last
  // such ball found is its centre's (the radius shrunk far beyond the distance's rounding).
  const double ball = 4 * spacing;
  bool have_ball = false;
  Vec3 ball_centre = Vec3::Zero();
  bool ball_inside = false;
  for (const Vec3& x : placed) {
    const double enough = std::max(floor, out.depth);
    const double near = triangle_within(tree, x, enough, stack);
    if (near <= enough) {
      out.bound = std::max(out.bound, near);
      continue;
    }
    bool inside = false;
    if (have_ball && (x - ball_centre).norm() < ball * (1 - 1e-6)) {
      inside = ball_inside;
    } else {
      inside = point_side(tree, x) != PointSide::kOutside;
      have_ball = triangle_within(tree, x, ball, stack) > ball;
      ball_centre = x;
      ball_inside = inside;
    }
    if (!inside) continue;
    out.depth = nearest_surface_distance(tree, x, enough, stack);
  }
  out.bound = std::max(out.bound, out.depth);
  return out;
}

SurfaceCache::SurfaceCache(const mjModel* m) : m_(m) {}

SurfaceCache::~SurfaceCache() = default;

std::unique_ptr<GeomSurface>* SurfaceCache::slot(int g, bool hull) {
  const int type = m_->geom_type[g];
  if (type == mjGEOM_MESH && m_->geom_dataid[g] >= 0) {
    return &(hull ? hulls_ : meshes_)[m_->geom_dataid[g]];
  }
  if (!mujoco::is_primitive(type)) return nullptr;
  const mjtNum* s = m_->geom_size + 3 * g;
  const int used = type == mjGEOM_SPHERE                               ? 1
                   : type == mjGEOM_CAPSULE || type == mjGEOM_CYLINDER ? 2
                                                                       : 3;
  PrimitiveKey key{static_cast<double>(type), 0, 0, 0};
  for (int k = 0; k < used; ++k) key[static_cast<std::size_t>(k + 1)] = s[k];
  return &primitives_[key];
}

const GeomSurface* SurfaceCache::surface(int g) {
  std::unique_ptr<GeomSurface>* s = slot(g, false);
  if (s == nullptr) return nullptr;
  if (!*s) {
    std::vector<Triangle> local = geom_triangles(m_, g);
    if (local.empty()) return nullptr;
    *s = std::make_unique<GeomSurface>(std::move(local));
  }
  return s->get();
}

bool SurfaceCache::closed(int g) {
  std::unique_ptr<GeomSurface>* s = slot(g, false);
  if (s == nullptr) return false;
  if (*s) return (*s)->closed();
  if (m_->geom_type[g] == mjGEOM_MESH && m_->mesh_facenum[m_->geom_dataid[g]] == 0) return false;
  // A mesh's closedness from its faces alone (the same counts as its tree's): its tree is built
  // only when a measure needs it. A primitive's tessellation is small and closed: built.
  if (m_->geom_type[g] != mjGEOM_MESH) {
    const GeomSurface* primitive = surface(g);
    return primitive != nullptr && primitive->closed();
  }
  const int mesh = m_->geom_dataid[g];
  const auto known = closed_.find(mesh);
  if (known != closed_.end()) return known->second;
  const bool c = graspcd::closedness(geom_triangles(m_, g)).closed();
  closed_.emplace(mesh, c);
  return c;
}

const GeomSurface* SurfaceCache::hull(int g) {
  if (m_->geom_type[g] != mjGEOM_MESH || m_->geom_dataid[g] < 0) return surface(g);
  std::unique_ptr<GeomSurface>* s = slot(g, true);
  if (!*s) {
    std::vector<Triangle> local = mesh_hull_triangles(m_, m_->geom_dataid[g]);
    if (local.empty()) return surface(g);
    *s = std::make_unique<GeomSurface>(std::move(local));
  }
  return s->get();
}

}  // namespace graspcd::grasp
