// HACD (Mamou and Ghorbel, ICIP 2009) through Debian's libHACD: see hacd.h.
#include "graspcd/decompose/hacd.h"

#include <hacdHACD.h>
#include <libqhull_r/libqhull_r.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

namespace graspcd::decompose {

namespace {

// HACD works in its own frame: the points shifted to their barycentre and scaled so that the
// bounding box diagonal is 2 * kHacdScale (NormalizeData); the connection distance is in those
// units. Bullet's demos keep the library's defaults, which we state here.
constexpr double kHacdScale = 1000.0;
constexpr double kHacdConnectDistance = 30.0;  // 1.5% of the diagonal
constexpr double kHacdCompacityWeight = 0.1;   // alpha, Mamou and Ghorbel eq. (5)
constexpr double kHacdVolumeWeight = 0.0;      // beta

// A flat cluster (its points on one plane, e.g. a cup's flat bottom) has no solid hull, and MuJoCo
// refuses a mesh without volume: it becomes a slab, its points and the same points moved by
// kFlatThickness x (the mesh's bounding box diagonal) against the cluster's outward normal (the
// faces' area-weighted normal: into the object for a mesh oriented outward).
constexpr double kFlatThickness = 0.005;

// The convex hull of `points` by qhull (the reentrant C library, as core/obb.cpp and MuJoCo's mesh
// compiler use it; "Qt": triangulated facets), faces turned outward (a face whose normal points
// toward the vertex centroid, inside a convex body, is flipped). Empty when the points have no
// full-dimensional hull (flat, collinear, fewer than 4).
TriangleMesh qhull_hull(const std::vector<Vec3>& points) {
  TriangleMesh hull;
  if (points.size() < 4) return hull;
  std::vector<double> coords;
  for (const Vec3& p : points) coords.insert(coords.end(), {p.x(), p.y(), p.z()});
  static std::FILE* const quiet = std::fopen("/dev/null", "w");
  qhT qh_storage;
  qhT* qh = &qh_storage;  // the name the qhull macros expect
  qh_zero(qh, quiet);
  char command[] = "qhull Qt";
  const int exit_code = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coords.data(), False,
                                     command, nullptr, quiet);
  if (exit_code == 0) {
    std::vector<int> index(points.size(), -1);
    facetT* facet = nullptr;
    FORALLfacets {
      std::array<std::int32_t, 3> f{};
      int count = 0;
      vertexT *vertex = nullptr, **vertexp = nullptr;
      FOREACHvertex_(facet->vertices) {
        const auto id = static_cast<std::size_t>(qh_pointid(qh, vertex->point));
        if (index[id] < 0) {
          index[id] = static_cast<int>(hull.vertices.size());
          hull.vertices.push_back(points[id]);
        }
        if (count < 3) f[static_cast<std::size_t>(count)] = index[id];
        ++count;
      }
      if (count == 3) hull.faces.push_back(f);
    }
  }
  qh_freeqhull(qh, !qh_ALL);
  int long_left = 0, total_left = 0;
  qh_memfreeshort(qh, &long_left, &total_left);
  if (exit_code != 0 || hull.faces.size() < 4) return TriangleMesh{};
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& v : hull.vertices) centroid += v;
  centroid /= static_cast<double>(hull.vertices.size());
  for (auto& f : hull.faces) {
    const Vec3& a = hull.vertices[static_cast<std::size_t>(f[0])];
    const Vec3 normal = (hull.vertices[static_cast<std::size_t>(f[1])] - a)
                            .cross(hull.vertices[static_cast<std::size_t>(f[2])] - a);
    if (normal.dot(centroid - a) > 0) std::swap(f[1], f[2]);
  }
  return hull;
}

// HACD's call-back is a plain function (no user pointer): the merges' progress reaches the
// options' callback through the calling thread's slot. HACD reports the percentage
// 100 (1 - clusters / faces), which ends at 100 (1 - max_pieces / faces).
struct HacdProgress {
  const std::function<void(double)>* callback = nullptr;
  double end_percent = 100;
};
thread_local HacdProgress hacd_progress;

bool hacd_callback(const char* message, double percent, double, std::size_t) {
  const HacdProgress& p = hacd_progress;
  // Stage messages start with "+" and carry no percentage.
  if (p.callback == nullptr || message == nullptr || message[0] == '+') return true;
  (*p.callback)(std::clamp(percent / p.end_percent, 0.0, 1.0));
  return true;
}

}  // namespace

Partition hacd_partition(const TriangleMesh& mesh, const HacdOptions& options) {
  if (mesh.faces.empty()) throw std::runtime_error("HACD: the mesh has no faces");
  if (options.max_pieces < 1) throw std::runtime_error("HACD: at least one piece");
  // HACD normalises the points in place and writes them back: give it a copy.
  std::vector<HACD::Vec3<HACD::Real>> hacd_points;
  hacd_points.reserve(mesh.vertices.size());
  for (const Vec3& v : mesh.vertices) hacd_points.emplace_back(v.x(), v.y(), v.z());
  std::vector<HACD::Vec3<long>> triangles;
  triangles.reserve(mesh.faces.size());
  for (const auto& f : mesh.faces) triangles.emplace_back(f[0], f[1], f[2]);

  HACD::HACD hacd;
  hacd.SetPoints(hacd_points.data());
  hacd.SetNPoints(hacd_points.size());
  hacd.SetTriangles(triangles.data());
  hacd.SetNTriangles(triangles.size());
  hacd.SetScaleFactor(kHacdScale);
  hacd.SetConnectDist(kHacdConnectDistance);
  hacd.SetCompacityWeight(kHacdCompacityWeight);
  hacd.SetVolumeWeight(kHacdVolumeWeight);
  hacd.SetNClusters(options.max_pieces);
  // No concavity threshold: merge down to max_pieces (hacd.h).
  hacd.SetConcavity(std::numeric_limits<double>::max());
  // Concavity measured also at the faces' centres. Not at the points facing them across the
  // object (AddExtraDistPoints): in this HACD those points are flagged "distance only" even when
  // they are the cluster's own vertices, which drops them from the cluster's hull (a tetrahedron
  // as one cluster gets a hull of 2 points).
  hacd.SetAddFacesPoints(true);
  hacd.SetAddExtraDistPoints(false);
  hacd.SetAddNeighboursDistPoints(false);
  struct Slot {  // the thread's progress slot, cleared on every return
    explicit Slot(const HacdOptions& o, std::size_t faces) {
      hacd_progress.callback = o.progress ? &o.progress : nullptr;
      hacd_progress.end_percent = std::max(
          1e-9, 100.0 * (1.0 - static_cast<double>(o.max_pieces) / static_cast<double>(faces)));
    }
    ~Slot() { hacd_progress = HacdProgress{}; }
    Slot(const Slot&) = delete;
    Slot& operator=(const Slot&) = delete;
  } slot(options, mesh.faces.size());
  if (options.progress) hacd.SetCallBack(&hacd_callback);
  if (!hacd.Compute(/*fullCH=*/false, /*exportDistPoints=*/false)) {
    throw std::runtime_error("HACD: the decomposition failed");
  }

  Partition out;
  out.clusters = hacd.GetNClusters();
  const long* partition = hacd.GetPartition();
  out.cluster_of_face.reserve(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    out.cluster_of_face.push_back(static_cast<std::size_t>(partition[f]));
  }
  return out;
}

Decomposition pieces_of_partition(const TriangleMesh& mesh, const Partition& partition) {
  if (partition.cluster_of_face.size() != mesh.faces.size()) {
    throw std::runtime_error("pieces_of_partition: the partition is not the mesh's");
  }
  // Each cluster's piece: the convex hull of its faces' vertices (qhull; HACD's own hulls are
  // simplified and built from its normalised points), a flat one as a slab.
  Decomposition out;
  const std::size_t clusters = partition.clusters;
  std::vector<std::vector<std::int32_t>> cluster_vertices(clusters);
  std::vector<Vec3> outward(clusters, Vec3::Zero());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const std::size_t c = partition.cluster_of_face[f];
    if (c >= clusters) throw std::runtime_error("pieces_of_partition: a cluster out of range");
    const Triangle t = mesh.triangle(f);
    outward[c] += (t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]);
    cluster_vertices[c].insert(cluster_vertices[c].end(), mesh.faces[f].begin(),
                               mesh.faces[f].end());
  }
  Vec3 lo = mesh.vertices.front(), hi = lo;
  for (const Vec3& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const double thickness = kFlatThickness * (hi - lo).norm();
  for (std::size_t c = 0; c < clusters; ++c) {
    std::vector<std::int32_t>& ids = cluster_vertices[c];
    if (ids.empty()) continue;  // no face chose this cluster
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    std::vector<Vec3> points;
    for (const std::int32_t i : ids) points.push_back(mesh.vertices[static_cast<std::size_t>(i)]);
    TriangleMesh hull = qhull_hull(points);
    if (hull.faces.empty() && outward[c].norm() > 0) {
      const Vec3 inward = -thickness * outward[c].normalized();
      const std::size_t n = points.size();
      for (std::size_t k = 0; k < n; ++k) points.push_back(points[k] + inward);
      hull = qhull_hull(points);
      if (!hull.faces.empty()) ++out.slabs;
    }
    if (hull.faces.empty()) {
      ++out.flat_clusters;
      continue;
    }
    out.pieces.push_back(ConvexPiece{std::move(hull)});
  }
  if (out.pieces.empty()) throw std::runtime_error("HACD: no piece has a volume (a flat mesh?)");
  return out;
}

TriangleMesh convex_hull(const std::vector<Vec3>& points) { return qhull_hull(points); }

Decomposition hacd_decompose(const TriangleMesh& mesh, const HacdOptions& options) {
  return pieces_of_partition(mesh, hacd_partition(mesh, options));
}

}  // namespace graspcd::decompose
