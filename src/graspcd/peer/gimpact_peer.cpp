// Bullet's GImpact behind graspcd's meshes and poses (gimpact_peer.h). Compiled with
// BT_USE_DOUBLE_PRECISION (src/CMakeLists.txt) against Bullet's -float64 libraries.
#include "graspcd/peer/gimpact_peer.h"

#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btCollisionObject.h>
#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btTriangleIndexVertexArray.h>
#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>
#include <BulletCollision/Gimpact/btGImpactShape.h>

#include <stdexcept>
#include <vector>

static_assert(sizeof(btScalar) == sizeof(double), "the GImpact peer needs double-precision Bullet");

namespace graspcd::peer {

struct GimpactMesh::Impl {
  std::vector<double> vertices;  // x y z per vertex: Bullet reads them in place
  std::vector<int> indices;      // three per face
  btTriangleIndexVertexArray array;
  std::unique_ptr<btGImpactMeshShape> shape;
  btCollisionObject object;
  std::size_t triangles = 0;
};

GimpactMesh::GimpactMesh(const TriangleMesh& mesh) : impl_(std::make_unique<Impl>()) {
  if (mesh.faces.empty()) throw std::invalid_argument("GimpactMesh: a mesh without faces");
  const auto n = static_cast<std::int64_t>(mesh.vertices.size());
  for (const Vec3& v : mesh.vertices)
    impl_->vertices.insert(impl_->vertices.end(), {v.x(), v.y(), v.z()});
  for (const auto& f : mesh.faces) {
    for (const std::int32_t i : f) {
      if (i < 0 || i >= n) throw std::invalid_argument("GimpactMesh: a face index out of range");
      impl_->indices.push_back(i);
    }
  }
  impl_->triangles = mesh.faces.size();
  btIndexedMesh part;
  part.m_numTriangles = static_cast<int>(mesh.faces.size());
  part.m_triangleIndexBase = reinterpret_cast<const unsigned char*>(impl_->indices.data());
  part.m_triangleIndexStride = 3 * static_cast<int>(sizeof(int));
  part.m_numVertices = static_cast<int>(mesh.vertices.size());
  part.m_vertexBase = reinterpret_cast<const unsigned char*>(impl_->vertices.data());
  part.m_vertexStride = 3 * static_cast<int>(sizeof(double));
  part.m_indexType = PHY_INTEGER;
  part.m_vertexType = PHY_DOUBLE;
  impl_->array.addIndexedMesh(part, PHY_INTEGER);
  impl_->shape = std::make_unique<btGImpactMeshShape>(&impl_->array);
  // Margins 0: the surfaces as they are (GImpact's default margin is 0.01 m).
  impl_->shape->setMargin(0);
  impl_->shape->updateBound();
  impl_->object.setCollisionShape(impl_->shape.get());
}

GimpactMesh::~GimpactMesh() = default;
GimpactMesh::GimpactMesh(GimpactMesh&&) noexcept = default;
GimpactMesh& GimpactMesh::operator=(GimpactMesh&&) noexcept = default;
std::size_t GimpactMesh::triangle_count() const { return impl_->triangles; }

namespace {

// Counts the contact points GImpact adds (touching or penetrating) instead of handing them to a
// persistent manifold, which would keep 4.
class CountingResult : public btManifoldResult {
 public:
  CountingResult(const btCollisionObjectWrapper* a, const btCollisionObjectWrapper* b)
      : btManifoldResult(a, b) {}
  void addContactPoint(const btVector3& /*normal*/, const btVector3& /*point*/,
                       btScalar depth) override {
    if (depth <= 0) ++contacts;
  }
  std::uint64_t contacts = 0;
};

btTransform to_bullet(const Pose& p) {
  const btMatrix3x3 basis(p.R(0, 0), p.R(0, 1), p.R(0, 2), p.R(1, 0), p.R(1, 1), p.R(1, 2),
                          p.R(2, 0), p.R(2, 1), p.R(2, 2));
  return btTransform(basis, btVector3(p.t.x(), p.t.y(), p.t.z()));
}

}  // namespace

struct GimpactQuery::Impl {
  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  Impl() { btGImpactCollisionAlgorithm::registerAlgorithm(&dispatcher); }
};

GimpactQuery::GimpactQuery() : impl_(std::make_unique<Impl>()) {}
GimpactQuery::~GimpactQuery() = default;

GimpactQueryResult GimpactQuery::collide(const GimpactMesh& a, const GimpactMesh& b,
                                         const Pose& b_in_a) {
  const btTransform ta = btTransform::getIdentity();
  const btTransform tb = to_bullet(b_in_a);
  a.impl_->object.setWorldTransform(ta);
  b.impl_->object.setWorldTransform(tb);
  const btCollisionObjectWrapper wa(nullptr, a.impl_->shape.get(), &a.impl_->object, ta, -1, -1);
  const btCollisionObjectWrapper wb(nullptr, b.impl_->shape.get(), &b.impl_->object, tb, -1, -1);
  btCollisionAlgorithm* algorithm =
      impl_->dispatcher.findAlgorithm(&wa, &wb, nullptr, BT_CONTACT_POINT_ALGORITHMS);
  CountingResult result(&wa, &wb);
  const btDispatcherInfo info;
  algorithm->processCollision(&wa, &wb, info, &result);
  algorithm->~btCollisionAlgorithm();
  impl_->dispatcher.freeCollisionAlgorithm(algorithm);
  GimpactQueryResult out;
  out.contacts = result.contacts;
  out.intersect = result.contacts > 0;
  return out;
}

}  // namespace graspcd::peer
