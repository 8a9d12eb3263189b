#include "graspcd/peer/fcl_querier.h"

#include <map>
#include <vector>

namespace graspcd::peer {

namespace {

using study::MeshPair;
using study::MeshScene;
using study::Querier;

class FclQuerier : public Querier {
 public:
  FclQuerier(const MeshScene& scene, FclBv bv) {
    for (int mesh : scene.meshes()) {
      // The face soup as an indexed mesh (three vertices per face), so FCL sees our doubles and
      // its primitive ids are our face ids.
      TriangleMesh m;
      const std::vector<Triangle>& faces = scene.faces(mesh);
      for (std::size_t f = 0; f < faces.size(); ++f) {
        const auto base = static_cast<std::int32_t>(3 * f);
        for (const Vec3& v : faces[f].v) m.vertices.push_back(v);
        m.faces.push_back({base, base + 1, base + 2});
      }
      meshes_.emplace(mesh, FclMesh(m, bv));
    }
  }
  void reset(std::size_t) override {}
  QueryResult query(std::size_t, const MeshPair& pair, const ObbTree&, const ObbTree&,
                    const Pose& b_in_a, std::vector<TrianglePair>* out, QueryCounters&) override {
    const FclQueryResult r =
        fcl_collide(meshes_.at(pair.mesh1), meshes_.at(pair.mesh2), b_in_a, false, out);
    QueryResult q;
    q.intersect = r.intersect;
    q.pair_count = r.pair_count;
    return q;
  }

 private:
  std::map<int, FclMesh> meshes_;
};

}  // namespace

std::unique_ptr<Querier> make_fcl_querier(const MeshScene& scene, FclBv bv) {
  return std::make_unique<FclQuerier>(scene, bv);
}

std::vector<study::PeerMethod> fcl_table_methods() {
  std::vector<study::PeerMethod> v;
  for (FclBv bv : {FclBv::kObb, FclBv::kRss}) {
    v.push_back(
        {fcl_bv_name(bv), [bv](const MeshScene& scene) { return make_fcl_querier(scene, bv); }});
  }
  return v;
}

}  // namespace graspcd::peer
