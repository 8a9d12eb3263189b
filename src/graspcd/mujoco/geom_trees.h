// The geoms of a model that a pair config selects, and their OBB trees (docs/design.md, "The MuJoCo
// layer"): the glob matching of patterns (pair_config.h) against geom and body names, the
// served geom types, the faces of MuJoCo's meshes (zero-area faces left out, core/
// mesh_hygiene.h), and one tree per mesh and per primitive shape, in the geom frame, built once
// and shared by every geom of that mesh or shape. Immutable once built: the registry (registry.h)
// owns one GeomTrees per model and the served calls only read it.
//
// Served geom types: mesh, box, sphere, capsule, cylinder, ellipsoid. A mesh's tree is built from
// MuJoCo's mesh (one per mesh); a primitive's from its tessellation (primitives.h: a box exactly,
// curved primitives circumscribed, with the documented tolerance), one per (type, size).
#pragma once

#include <mujoco/mujoco.h>

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "graspcd/core/contact.h"
#include "graspcd/core/containment.h"
#include "graspcd/core/obb_tree.h"
#include "graspcd/mujoco/scene_names.h"

namespace graspcd::mujoco {

// True when `name` matches the glob `pattern` ('*' only).
bool glob_match(const std::string& pattern, const std::string& name);
// The collidable geoms (contype or conaffinity non-zero) that a pattern of the config selects
// ("geom:GLOB", "body:GLOB" or "GLOB"), in id order; empty when none.
std::vector<int> match_geoms(const mjModel* m, const std::string& pattern);
// The geoms a pattern selects, each checked to be of a served type. Throws std::runtime_error
// starting with `source` for an unserved type (naming the pattern, the geom and its type) or a
// pattern that matches no collidable geom.
std::vector<int> resolve_pattern(const mjModel* m, const std::string& pattern,
                                 const std::string& source);

// True for the geom types graspcd serves: mesh, box, sphere, capsule, cylinder, ellipsoid.
bool served_geom_type(int type);
// "geom 3 'floor' of type plane, which graspcd does not serve (...)": the tail of the error for a
// geom whose type is not served.
std::string unserved_geom(const mjModel* m, int g);
// The name of a model object (mjOBJ_GEOM, mjOBJ_BODY, mjOBJ_MESH, ...), empty when it has none.
std::string object_name(const mjModel* m, int type, int id);

// The mesh's faces in the mesh frame, as doubles converted from MuJoCo's floats, in face order.
std::vector<Triangle> mesh_triangles(const mjModel* m, int mesh_id);

// The tree of one mesh (or of one primitive's tessellation) and, for each face id, the face's slot
// in the tree's leaf-ordered triangles. Also the sharp-edge masks of the faces (contact.h), by
// face id.
// Face ids are the tree's: a mesh's zero-area faces are dropped before the build (core/
// mesh_hygiene.h), and source_face maps each tree face id to MuJoCo's face id in the mesh.
struct MeshTree {
  ObbTree tree;
  Closedness closedness;  // of the tree's triangles: containment is decided for closed ones only
  std::vector<std::int32_t> source_face;  // tree face id -> MuJoCo face id (mesh trees)
  std::vector<std::int32_t> slot_of_face;
  std::vector<std::uint8_t> sharp_masks;
  std::vector<FaceVertexIds> vertex_ids;  // per face: its welded vertices (the manifold's patches)
  double radius = 0;  // the largest distance of a vertex from the geom frame's origin
  std::uint8_t sharp(std::int32_t f) const { return sharp_masks[static_cast<std::size_t>(f)]; }
  const FaceVertexIds& vertices(std::int32_t f) const {
    return vertex_ids[static_cast<std::size_t>(f)];
  }
  const Triangle& face(std::int32_t f) const {
    return tree.triangles()[static_cast<std::size_t>(slot_of_face[static_cast<std::size_t>(f)])];
  }
};

// Where construction reports a non-fatal finding: (code, one-line message).
using WarningSink = std::function<void(const std::string& code, const std::string& message)>;

// The trees of one model's geoms: one per mesh, one per primitive (type, size), looked up by geom.
class GeomTrees {
 public:
  explicit GeomTrees(const mjModel* m = nullptr);
  GeomTrees(const GeomTrees&) = delete;
  GeomTrees& operator=(const GeomTrees&) = delete;
  GeomTrees(GeomTrees&&) = default;
  GeomTrees& operator=(GeomTrees&&) = default;

  // Builds the tree of geom `g` (a served type) unless its mesh's or shape's exists already.
  // Throws std::runtime_error starting with `source` for a mesh with no face of non-zero area or a
  // primitive that cannot be tessellated; reports dropped zero-area faces to `warn`
  // ("mesh_zero_area_faces"), a mesh of the hand called so by `names`.
  void add_geom(const mjModel* m, int g, const std::string& source, const WarningSink& warn,
                const SceneNames& names = {});

  // The tree of a mesh id, or nullptr when no geom of the mesh was added.
  const MeshTree* mesh_tree(int mesh_id) const {
    const auto it = meshes_.find(mesh_id);
    return it == meshes_.end() ? nullptr : &it->second;
  }
  // The tree of a geom, or nullptr when it was not added. O(1).
  const MeshTree* geom_tree(int geom) const {
    return geom >= 0 && static_cast<std::size_t>(geom) < by_geom_.size()
               ? by_geom_[static_cast<std::size_t>(geom)]
               : nullptr;
  }
  std::size_t tree_count() const { return meshes_.size() + primitives_.size(); }
  std::size_t primitive_tree_count() const { return primitives_.size(); }

 private:
  const MeshTree& mesh_tree_of(const mjModel* m, int mesh, const std::string& source,
                               const WarningSink& warn, const SceneNames& names);
  const MeshTree& primitive_tree_of(const mjModel* m, int g, const std::string& source);

  std::unordered_map<int, MeshTree> meshes_;  // by mesh id
  // By (geom type, size[0..2]) with the sizes the type does not use set to 0. std::map: stable
  // element addresses, which by_geom_ holds.
  std::map<std::array<double, 4>, MeshTree> primitives_;
  std::vector<const MeshTree*> by_geom_;  // by geom id
};

}  // namespace graspcd::mujoco
