// FCL as the peer: the adapter (fcl_peer.h). FCL: Pan, Chitta, Manocha, ICRA 2012; OBB trees:
// Gottschalk, Lin, Manocha, SIGGRAPH 1996. API as in /usr/include/fcl (FCL 0.7.0, Debian 12).
#include "graspcd/peer/fcl_peer.h"

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBB.h>
#include <fcl/math/bv/RSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/detail/traversal/collision/mesh_collision_traversal_node.h>
#include <fcl/narrowphase/detail/traversal/collision_node.h>

#include <limits>
#include <stdexcept>
#include <string>

namespace graspcd::peer {

// Exactly one of the two models is set, the one of FclMesh::bv().
struct FclMesh::Impl {
  std::unique_ptr<fcl::BVHModel<fcl::OBBd>> obb;
  std::unique_ptr<fcl::BVHModel<fcl::RSSd>> rss;
};

struct FclFront::Impl {
  fcl::detail::BVHFrontList list;
};

FclFront::FclFront() : impl_(std::make_unique<Impl>()) {}
FclFront::~FclFront() = default;
FclFront::FclFront(FclFront&&) noexcept = default;
FclFront& FclFront::operator=(FclFront&&) noexcept = default;
std::size_t FclFront::size() const { return impl_->list.size(); }
void FclFront::clear() { impl_->list.clear(); }

namespace {

// One query through FCL's traversal node for the bounding volume (statistics on).
template <class Node, class Model>
std::uint64_t traverse(const Model& a, const Model& b, const fcl::Transform3d& tf,
                       const fcl::CollisionRequestd& request, fcl::CollisionResultd& result,
                       fcl::detail::BVHFrontList* front) {
  static const fcl::Transform3d identity = fcl::Transform3d::Identity();
  Node node;
  if (!fcl::detail::initialize(node, a, identity, b, tf, request, result)) {
    throw std::runtime_error("fcl_collide: FCL's initialize failed");
  }
  node.enable_statistics = true;
  fcl::detail::collide(&node, front);
  return static_cast<std::uint64_t>(node.num_bv_tests);
}

// beginModel / addSubModel / endModel (BVH_model.h); every call returns BVH_OK (0) on success.
// Vec3 is fcl::Vector3d (both Eigen::Vector3d), so the vertices go in as they are.
template <class Bv>
std::unique_ptr<fcl::BVHModel<Bv>> build_model(
    const std::vector<Vec3>& vertices, const std::vector<std::array<std::int32_t, 3>>& faces) {
  if (faces.empty()) throw std::invalid_argument("FclMesh: a mesh without faces");
  const auto n = static_cast<std::int64_t>(vertices.size());
  std::vector<fcl::Triangle> triangles;
  triangles.reserve(faces.size());
  for (const auto& f : faces) {
    for (const std::int32_t k : f) {
      if (k < 0 || k >= n) throw std::invalid_argument("FclMesh: a face index out of range");
    }
    triangles.emplace_back(static_cast<std::size_t>(f[0]), static_cast<std::size_t>(f[1]),
                           static_cast<std::size_t>(f[2]));
  }
  auto model = std::make_unique<fcl::BVHModel<Bv>>();
  const auto check = [](int code, const char* step) {
    if (code != fcl::BVH_OK) {
      throw std::runtime_error(std::string("FclMesh: FCL's ") + step + " returned " +
                               std::to_string(code));
    }
  };
  check(model->beginModel(static_cast<int>(triangles.size()), static_cast<int>(vertices.size())),
        "beginModel");
  check(model->addSubModel(vertices, triangles), "addSubModel");
  check(model->endModel(), "endModel");
  model->computeLocalAABB();
  return model;
}

}  // namespace

const char* fcl_bv_name(FclBv bv) { return bv == FclBv::kObb ? "fcl-obb" : "fcl-rss"; }

FclMesh::FclMesh(const TriangleMesh& mesh, FclBv bv) : FclMesh(mesh.vertices, mesh.faces, bv) {}

FclMesh::FclMesh(const std::vector<Vec3>& vertices,
                 const std::vector<std::array<std::int32_t, 3>>& faces, FclBv bv)
    : bv_(bv), impl_(std::make_unique<Impl>()) {
  if (bv == FclBv::kObb) {
    impl_->obb = build_model<fcl::OBBd>(vertices, faces);
  } else {
    impl_->rss = build_model<fcl::RSSd>(vertices, faces);
  }
}

FclMesh::~FclMesh() = default;
FclMesh::FclMesh(FclMesh&&) noexcept = default;
FclMesh& FclMesh::operator=(FclMesh&&) noexcept = default;

std::size_t FclMesh::triangle_count() const {
  return static_cast<std::size_t>(impl_->obb ? impl_->obb->num_tris : impl_->rss->num_tris);
}

int FclMesh::bv_count() const {
  return impl_->obb ? impl_->obb->getNumBVs() : impl_->rss->getNumBVs();
}

FclQueryResult fcl_collide(const FclMesh& a, const FclMesh& b, const Pose& b_in_a,
                           bool first_contact, std::vector<TrianglePair>* pairs, FclFront* front) {
  if (a.bv() != b.bv()) {
    throw std::invalid_argument("fcl_collide: the two meshes use different bounding volumes");
  }
  fcl::Transform3d tf = fcl::Transform3d::Identity();
  tf.linear() = b_in_a.R;
  tf.translation() = b_in_a.t;
  // CollisionRequest(num_max_contacts, enable_contact); FCL stops once num_max_contacts pairs
  // are recorded (CollisionRequest::isSatisfied), so the maximum never stops it.
  const fcl::CollisionRequestd request(
      first_contact ? std::size_t{1} : std::numeric_limits<std::size_t>::max(), false);
  fcl::CollisionResultd result;
  fcl::detail::BVHFrontList* list = front ? &front->impl_->list : nullptr;
  FclQueryResult out;
  // fcl::collide dispatches BVHModel<OBBd> pairs to orientedMeshCollide, which is this traversal
  // on the models as built, nothing copied. For BVHModel<RSSd> pairs FCL 0.7's fcl::collide
  // takes the generic BVHCollideImpl, which copies both models, transforms B's vertices and
  // rebuilds its tree on every call
  // (https://github.com/flexible-collision-library/fcl/issues/38), so both go through the node
  // here.
  if (a.bv() == FclBv::kObb) {
    out.bv_tests = traverse<fcl::detail::MeshCollisionTraversalNodeOBB<double>>(
        *a.impl_->obb, *b.impl_->obb, tf, request, result, list);
  } else {
    out.bv_tests = traverse<fcl::detail::MeshCollisionTraversalNodeRSS<double>>(
        *a.impl_->rss, *b.impl_->rss, tf, request, result, list);
  }
  out.intersect = result.isCollision();
  out.pair_count = result.numContacts();
  if (pairs) {
    for (std::size_t i = 0; i < result.numContacts(); ++i) {
      const fcl::Contactd& c = result.getContact(i);
      pairs->push_back({static_cast<std::int32_t>(c.b1), static_cast<std::int32_t>(c.b2)});
    }
  }
  return out;
}

bool fcl_obb_disjoint(const Mat3& B, const Vec3& T, const Vec3& a, const Vec3& b) {
  // fcl::Matrix3d and fcl::Vector3d are Eigen's Matrix3d and Vector3d: no conversion.
  return fcl::obbDisjoint<double>(B, T, a, b);
}

}  // namespace graspcd::peer
