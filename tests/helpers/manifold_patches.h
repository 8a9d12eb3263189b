// Contact-manifold test inputs: candidates grouped into patches by shared vertex ids, and a
// bit-for-bit comparison of contacts (contact_manifold_*_test.cpp).
#pragma once

#include <cstdint>
#include <cstring>
#include <vector>

#include "graspcd/core/contact_manifold.h"
#include "graspcd/core/geometry.h"
#include "graspcd/core/mesh_features.h"
#include "graspcd/core/triangle_contact.h"

namespace graspcd::testing {

// Candidates with their vertex ids: the candidates of one group share vertex `group` on geom 1
// (one patch when their normals agree), every other id is the candidate's own.
struct PatchCandidates {
  std::vector<TriContact> candidates;
  std::vector<FaceVertexIds> a, b;
  void add(int group, const Vec3& pos, const Vec3& normal, double depth) {
    const auto i = static_cast<std::uint32_t>(candidates.size());
    candidates.push_back(TriContact{pos, normal.normalized(), depth});
    a.push_back({static_cast<std::uint32_t>(group), 1000 + 2 * i, 1001 + 2 * i});
    b.push_back({5000 + 3 * i, 5001 + 3 * i, 5002 + 3 * i});
  }
  ContactManifold build_with(const ManifoldOptions& options) const {
    return build_contact_manifold_by_ids(candidates, a, b, options);
  }
};

// Whether the two lists hold the same contacts, every double bit for bit.
inline bool same_bits(const std::vector<TriContact>& x, const std::vector<TriContact>& y) {
  if (x.size() != y.size()) return false;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (std::memcmp(x[i].pos.data(), y[i].pos.data(), sizeof(double) * 3) != 0 ||
        std::memcmp(x[i].normal.data(), y[i].normal.data(), sizeof(double) * 3) != 0 ||
        std::memcmp(&x[i].depth, &y[i].depth, sizeof(double)) != 0) {
      return false;
    }
  }
  return true;
}

}  // namespace graspcd::testing
