// Running a user's mesh in a template hand: `graspcd grasp --object` and, per object,
// `graspcd validate --objects`. An ObjectRun makes a folder of its own, writes the object's scene
// there (object_scene.h; its messages name the files as the user knows them, ObjectScene::names),
// runs the grasp and, with `write_scene`, keeps the scene.
//
// Without `write_scene` the folder is graspcd-object-XXXXXX under the system's temporary folder
// ($TMPDIR, else /tmp), removed with the run. With `write_scene` DIR the run leaves DIR/STEM.xml,
// DIR/STEM.pairs.json and DIR/STEM.meshes (STEM: the mesh file's stem). It checks them before
// the work: it never replaces a file it reads (the template, its pair config, the mesh) and,
// without `force`, none graspcd did not write (a STEM.xml without kGeneratedMarker, and the files
// beside it). The scene is written and simulated in a private folder DIR/.graspcd-STEM-XXXXXX
// (two runs of one stem into DIR each simulate their own) and renamed into place at the end, DIR
// locked (flock) meanwhile, so that two runs ending together leave one run's files. Every folder
// the run made is removed on errors and on INT, TERM and HUP (io/output_files.h).
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "graspcd/grasp/grasp.h"
#include "graspcd/grasp/hand_templates.h"
#include "graspcd/grasp/object_scene.h"
#include "graspcd/io/output_files.h"

namespace graspcd::grasp {

// An object of this many triangles or more makes the grasp wait long before its first step:
// MuJoCo 2.2 compiles a mesh (inside mj_loadXML) in a time that grows faster than its faces
// (docs/objects.md, "Large meshes": a run takes 8 s of CPU at 100,000 faces, 21 s at
// 200,000), and nothing can be printed meanwhile. wait_notice() says so before it starts.
inline constexpr std::size_t kLargeObjectFaces = 100000;

// The default of ObjectRunOptions::load_timeout (`grasp --load-timeout`), s.
inline constexpr double kDefaultLoadTimeout = 300;

struct ObjectRunOptions {
  std::string file;  // the user's mesh
  HandTemplate hand;
  std::string write_scene;  // DIR: keep the scene there; empty: a temporary folder
  bool force = false;       // write_scene may replace files graspcd did not write
  // The most seconds grasp() may take before the first closing step (MuJoCo compiling the
  // scene, graspcd's trees, the start check): past it the run ends as on an error, exit code 2,
  // its folders removed (io::Deadline). 0: no limit.
  double load_timeout = 0;
};

// What ran, as the output describes it.
struct ObjectRunDescription {
  std::string file;  // the user's mesh, as given
  std::string hand;  // the template's name
  ObjectScene scene;
  bool kept = false;  // scene names the kept files (else removed ones)
};

class ObjectRun {
 public:
  // Checks the targets and makes the run's folder. Throws io::InputError naming the target it
  // must not replace or the folder it cannot write.
  explicit ObjectRun(const ObjectRunOptions& options);

  // Writes the scene of `placement` (its file: the run's) into the folder; its messages name the
  // files as ObjectScene::names has them, the pair config of a kept scene as DIR/STEM.pairs.json.
  // Its time is the grasp's "scene" part (grasp_cost.h). Throws io::InputError naming a bad mesh
  // or template; std::invalid_argument for a bad `up`.
  const ObjectScene& write(const ObjectPlacement& placement);

  const std::string& scene() const { return description_.scene.scene; }
  const mujoco::SceneNames& names() const { return description_.scene.names; }
  const ObjectRunDescription& description() const { return description_; }
  // The time of write(): the "scene" part (grasp_cost.h).
  const GraspCost& cost() const { return cost_; }

  // For an object of kLargeObjectFaces or more: one line saying that the grasp will wait (and
  // for how long at most, with load_timeout), to print before grasp(); else "".
  std::string wait_notice() const;

  // run_grasp on the written scene with its names, under load_timeout until the first closing
  // step; then the scene is kept (with `write_scene`), also when the grasp refuses it (so that
  // it can be edited). The result's scene is the kept scene, or the user's mesh.
  GraspResult grasp(GraspOptions options);

 private:
  void keep();

  ObjectRunOptions options_;
  std::optional<io::RemoveIfEmpty> created_;  // DIR, when this run created it
  io::CleanupGuard folder_;                   // the temporary or private folder
  ObjectRunDescription description_;
  GraspCost cost_;  // the scene's writing
};

}  // namespace graspcd::grasp
