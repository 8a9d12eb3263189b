#include "graspcd/core/mesh_features.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include "graspcd/core/tolerances.h"

namespace graspcd {

std::vector<FaceVertexIds> weld_vertex_ids(const std::vector<Triangle>& faces) {
  // Each corner by the bits of its coordinates (+ 0.0 folds -0.0 into 0.0; equal bits are equal
  // coordinates), sorted, then numbered run by run.
  using Bits = std::array<std::uint64_t, 3>;
  std::vector<std::pair<Bits, std::size_t>> corners;  // (bits, 3 * face + k)
  corners.reserve(3 * faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    for (std::size_t k = 0; k < 3; ++k) {
      Bits bits;
      for (std::size_t c = 0; c < 3; ++c) {
        const double x = faces[f].v[k][static_cast<Eigen::Index>(c)] + 0.0;
        std::memcpy(&bits[c], &x, sizeof x);
      }
      corners.emplace_back(bits, 3 * f + k);
    }
  }
  std::sort(corners.begin(), corners.end());
  std::vector<FaceVertexIds> ids(faces.size());
  std::uint64_t id = 0;
  for (std::size_t r = 0; r < corners.size(); ++r) {
    if (r > 0 && corners[r].first != corners[r - 1].first) ++id;
    if (id >> 31) throw std::length_error("weld_vertex_ids: more than 2^31 distinct vertices");
    ids[corners[r].second / 3][corners[r].second % 3] = static_cast<std::uint32_t>(id);
  }
  return ids;
}

// Feature edges by dihedral angle: weld vertices by exact coordinates (weld_vertex_ids), gather the
// faces of each undirected edge, and compare the unit normals of edges with exactly two faces.
std::vector<std::uint8_t> sharp_edge_masks(const std::vector<Triangle>& faces) {
  return sharp_edge_masks(faces, weld_vertex_ids(faces));
}

std::vector<std::uint8_t> sharp_edge_masks(const std::vector<Triangle>& faces,
                                           const std::vector<FaceVertexIds>& ids) {
  if (ids.size() != faces.size()) {
    throw std::invalid_argument("sharp_edge_masks: " + std::to_string(ids.size()) + " ids for " +
                                std::to_string(faces.size()) + " faces");
  }
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::pair<std::size_t, unsigned>>>
      edges;
  std::vector<Vec3> normals(faces.size());
  std::vector<std::uint8_t> masks(faces.size(), 0);
  const double cos_sharp = std::cos(tol::kSharpEdgeAngle);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const Triangle& t = faces[f];
    const Vec3 n = (t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]);
    const double len = n.norm();
    normals[f] = len > 0 && std::isfinite(len) ? Vec3(n / len) : Vec3::Zero();
    for (unsigned k = 0; k < 3; ++k) {
      std::uint32_t p = ids[f][k], q = ids[f][(k + 1) % 3];
      if (q < p) std::swap(p, q);
      edges[{p, q}].emplace_back(f, k);
    }
  }
  for (const auto& [key, users] : edges) {
    bool sharp = users.size() != 2;
    if (!sharp) {
      const Vec3& n0 = normals[users[0].first];
      const Vec3& n1 = normals[users[1].first];
      sharp = n0.isZero() || n1.isZero() || n0.dot(n1) < cos_sharp;
    }
    if (!sharp) continue;
    for (const auto& [f, k] : users) masks[f] = static_cast<std::uint8_t>(masks[f] | (1u << k));
  }
  return masks;
}

}  // namespace graspcd
