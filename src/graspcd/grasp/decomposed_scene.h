// A scene whose object is replaced, for collision only, by its convex decomposition (`graspcd
// decompose`, docs/design.md "Convex decomposition"), so that MuJoCo's native collision runs on
// the pieces: the route MuJoCo's documentation recommends for a non-convex object.
#pragma once

#include <mujoco/mujoco.h>

#include <string>
#include <vector>

#include "graspcd/grasp/decomposed_pieces.h"
#include "graspcd/grasp/grasp.h"
#include "graspcd/mujoco/mujoco_ptr.h"

namespace graspcd::grasp {

struct DecomposedScene {
  std::string scene;       // the written MJCF (beside the original, so its relative paths hold)
  std::string source;      // the decomposed mesh file, as decomposition.json names it
  int mesh_assets = 0;     // <mesh> assets of the scene that read the source file
  int replaced_geoms = 0;  // geoms of those meshes, now without collision
  int pieces = 0;          // convex pieces per replaced geom
  std::vector<std::string>
      piece_files;  // piece K's file, DIR/NAME (as decomposition.json names it)
};

// Writes a copy of the scene `scene_path` (tinyxml2; the main file only, its includes are left as
// they are) in which every <mesh> asset whose file has the file name of the decomposition's
// source (DIR/decomposition.json, "source") gets one sibling <mesh> per piece (the piece's OBJ by
// absolute path, its scale the asset's divided by the decomposition's "scale", so that the pieces
// lie where the scene's mesh lies whatever scale they were written at), and every <geom> of such
// a mesh:
//  - stays, for its mass and inertia, but no longer collides (contype = conaffinity = 0);
//  - gets one sibling <geom> per piece with all its attributes (pos, quat, class, friction,
//    contype, ...) but name (NAME__piece_K), mesh, and mass 0 (the density attribute dropped),
//    so the body's dynamics stay those of the original geom and only its collision changes.
// MuJoCo places each piece by its own centre of mass and the geom's pos and quat, so the pieces
// stand where the mesh stood. The copy is written into the scene's folder as a hidden file whose
// name is unique (removed by the caller); its <include>s and meshdir keep working.
// Before, the pieces are checked against the scene's mesh file (or else the manifest's source):
// pieces whose bounding box is not the mesh's at the decomposition's scale
// (decompose::placement_mismatch: a scale applied twice, or forgotten) are refused. A manifest
// without a scale (written before graspcd 0.5) is read as scale 1, with the warning
// "decomposition_scale".
// Throws io::InputError (grasp.h) naming DIR for a missing or bad decomposition.json, naming
// DIR/decomposition.json for pieces that do not lie where the mesh lies, naming the scene when it
// cannot be read, holds no mesh of the source file, or its folder cannot be written.
DecomposedScene write_decomposed_scene(const std::string& scene_path,
                                       const std::string& decomposition_dir);

// The grasp of `scene_path` with its object decomposed: write_decomposed_scene, run_grasp under
// MuJoCo's native collision with SCENE's pair config (options.config_path when given) driving the
// hand, the written scene removed on return. `written` (when given) gets the DecomposedScene
// before the grasp runs. The result names `scene_path`; a io::InputError about the written scene
// names `scene_path` too ("with DIR: ..."). Used by graspcd grasp --decomposed and by validate's
// truth side (study/validate.h).
GraspResult run_decomposed_grasp(const std::string& scene_path,
                                 const std::string& decomposition_dir, GraspOptions options,
                                 DecomposedScene* written = nullptr);

}  // namespace graspcd::grasp
