// FCL as the peer in the study's comparisons: a thin adapter from graspcd's meshes and poses to
// FCL 0.7's BVHModel and collide(). Used by the study and the benchmarks only, never by
// src/graspcd/core or src/graspcd/mujoco (docs/design.md, "Layers").
//
// FCL: J. Pan, S. Chitta, D. Manocha, "FCL: A General Purpose Library for Collision and Proximity
// Queries", IEEE ICRA 2012. Its OBB trees follow S. Gottschalk, M. C. Lin, D. Manocha, "OBBTree:
// A Hierarchical Structure for Rapid Interference Detection", SIGGRAPH 1996; its RSS trees follow
// Larsen, Gottschalk, Lin, Manocha, "Fast Proximity Queries with Swept Sphere Volumes", 1999.
//
// FCL's headers are kept out of this one (pimpl), so users of the adapter compile without them.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "graspcd/core/geometry.h"
#include "graspcd/core/tree_query.h"

namespace graspcd::peer {

// The bounding volume of FCL's tree: OBB (Gottschalk's OBB tree, the like of ours) or RSS
// (rectangle swept spheres, FCL's fastest for mesh-mesh collision).
enum class FclBv { kObb, kRss };

const char* fcl_bv_name(FclBv bv);

struct FclQueryResult {
  bool intersect = false;
  // Intersecting triangle pairs FCL reported (0 or 1 in first-contact mode).
  std::uint64_t pair_count = 0;
  // Box (BV) tests FCL's traversal made: its num_bv_tests statistic.
  std::uint64_t bv_tests = 0;
};

class FclMesh;

// FCL's front list (detail::BVHFrontList, the BVTT front of the previous query) for one pair of
// meshes: passed to fcl_collide, the next query starts from it instead of the roots (temporal
// coherence). FCL disables its early stop when a front list is used, and may then report an
// intersecting pair twice (pair_count counts both; the set of pairs is unchanged). Move-only.
class FclFront {
 public:
  FclFront();
  ~FclFront();
  FclFront(FclFront&&) noexcept;
  FclFront& operator=(FclFront&&) noexcept;
  FclFront(const FclFront&) = delete;
  FclFront& operator=(const FclFront&) = delete;
  std::size_t size() const;  // node pairs on the front
  void clear();

  struct Impl;  // holds the BVHFrontList; defined in fcl_peer.cpp

 private:
  friend FclQueryResult fcl_collide(const FclMesh& a, const FclMesh& b, const Pose& b_in_a,
                                    bool first_contact, std::vector<TrianglePair>* pairs,
                                    FclFront* front);
  std::unique_ptr<Impl> impl_;
};

// A mesh as FCL's fcl::BVHModel<fcl::OBBd> or fcl::BVHModel<fcl::RSSd>, built once (FCL's default
// build: mean split along the box's longest axis, one triangle per leaf) in the mesh's own frame.
// Triangle k of the model is face k of the input, so FCL's primitive ids are our face indices.
// Move-only.
class FclMesh {
 public:
  // Throws std::invalid_argument on a mesh without faces or a face index out of range, and
  // std::runtime_error when FCL reports a build error.
  explicit FclMesh(const TriangleMesh& mesh, FclBv bv = FclBv::kObb);
  FclMesh(const std::vector<Vec3>& vertices, const std::vector<std::array<std::int32_t, 3>>& faces,
          FclBv bv = FclBv::kObb);
  ~FclMesh();
  FclMesh(FclMesh&&) noexcept;
  FclMesh& operator=(FclMesh&&) noexcept;
  FclMesh(const FclMesh&) = delete;
  FclMesh& operator=(const FclMesh&) = delete;

  FclBv bv() const { return bv_; }
  std::size_t triangle_count() const;
  int bv_count() const;  // nodes of FCL's tree

  struct Impl;  // holds the BVHModel; defined in fcl_peer.cpp

 private:
  friend FclQueryResult fcl_collide(const FclMesh& a, const FclMesh& b, const Pose& b_in_a,
                                    bool first_contact, std::vector<TrianglePair>* pairs,
                                    FclFront* front);
  FclBv bv_;
  std::unique_ptr<Impl> impl_;
};

// FCL's collide() of `a` (at the identity) and `b` placed by `b_in_a` (x_A = R x_B + t, as in
// graspcd::collide). first_contact: CollisionRequest num_max_contacts = 1, FCL stops at the first
// intersecting triangle pair; otherwise num_max_contacts is unbounded and FCL reports every
// intersecting pair. enable_contact stays false in both modes: FCL then records each intersecting
// pair exactly once with its primitive ids, whereas with enable_contact it records 0 to 2 contact
// points per pair (0 when its contact-point clipping finds none, so pairs would go missing).
// `pairs`, if given, receives the pairs as face indices (a's, b's), in FCL's order. Both bounding
// volumes run FCL's own oriented traversal node (what fcl::collide does for OBB, with statistics
// on for bv_tests). `front`, if given, is FCL's front list of the previous query of the same
// pair, and is updated.
// Throws std::invalid_argument when a and b use different bounding volumes.
FclQueryResult fcl_collide(const FclMesh& a, const FclMesh& b, const Pose& b_in_a,
                           bool first_contact, std::vector<TrianglePair>* pairs = nullptr,
                           FclFront* front = nullptr);

// FCL's one OBB test, fcl::obbDisjoint (RAPID's 15-axis test with early exit, Gottschalk et al.
// 1996) on box A at the identity with half-extents `a` and box B with rotation `B`, centre `T`
// (both in A's frame) and half-extents `b`. True when FCL finds a separating axis.
bool fcl_obb_disjoint(const Mat3& B, const Vec3& T, const Vec3& a, const Vec3& b);

}  // namespace graspcd::peer
