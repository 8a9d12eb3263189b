// Trajectory files: one recorded grasp as the viewer (report/viewer-src) and the
// figures (report/draw_figures.py) read it, in JSON.
//
//   meshes    once, in their geom frames (MuJoCo's recentred vertices, its faces)
//   geoms     every geom but planes: name, type (mesh, box, capsule, cylinder, sphere), mesh id,
//             MuJoCo's size, role (segment, object, support: the body below the pair config's
//             "grasp" support, or hand), its finger segment letter and whether it collides
//             (contype or conaffinity non-zero; a visual geom does not)
//   gravity   the scene's gravity (m/s^2), which the figures draw pointing down
//   steps     per closing grasp step: every listed geom's position (3) and rotation (9, row-major,
//             MuJoCo's geom_xmat), graspcd's contacts (the recording's) and MuJoCo's
//             native convex-hull contacts at the same joint positions (mj_forward without graspcd)
//   times_ns  per method, the detection time of each grasp step (median over the timed repeats
//             of the study's replay), when the study timed the scene
//   obb       per mesh of a served pair, the boxes of its OBB tree at depths 0 to kObbLevels-1
//             (depth-first node order), in the mesh's geom frame
// Contacts with a plane geom (the floor) are left out. Lengths are rounded to 1e-6 m and
// rotations and normals to 1e-6, which keeps the files (and the viewer's page) small.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "graspcd/core/separators.h"
#include "graspcd/study/recording.h"

namespace graspcd::study {

inline constexpr int kObbLevels = 4;  // depths 0..3 (the paper's Figure 17)

// Per method name, detection time per grasp step in ns.
using StepTimes = std::vector<std::pair<std::string, std::vector<double>>>;

// The boxes of `tree` at depth `depth` (the root is depth 0), in depth-first order. A leaf above
// that depth stands for itself at every deeper level.
std::vector<Obb> boxes_at_depth(const ObbTree& tree, int depth);

// Writes `recording` as a trajectory file to `path`. `scene` (may be null: the box hand has no
// served meshes) gives the OBB trees; `times` the per-step detection times (may be empty).
// Loads the recording's scene again for the native contacts. Throws io::InputError naming the
// file it cannot write (`named`, default `path`) or the scene it cannot load.
void write_trajectory(const std::string& path, const Recording& recording, const MeshScene* scene,
                      const StepTimes& times, const std::string& named = "");

struct TrajectoryOptions {
  std::vector<Method> methods = {Method::kSat, Method::kSatCached, Method::kNeuroSat};
  int repeats = 1;  // timed replays per method (per-step medians)
  int max_steps = 400;
  std::string out_name;  // how messages name the written file (default: its path)
};

// Whether `path` is a trajectory file graspcd wrote (a JSON object with graspcd's envelope and
// the keys write_trajectory writes: schema, meshes, geoms, steps).
bool is_trajectory_file(const std::string& path);

// The rules of an output (io/output_files.h) for the trajectory file `out` of a run on `scene`,
// before the work: it never replaces a file the run reads (the scene, the files it includes and
// its assets name, its pair config), and replaces an existing regular file only when it is a
// trajectory graspcd wrote, or with `force`. A device (/dev/stdout) passes. Throws io::InputError
// naming `out`.
void check_trajectory_target(const std::string& out, const std::string& scene, bool force);

// `graspcd trajectory`: records the grasp of `scene` served by graspcd (SAT), replays it with each
// method for its per-step detection times (all contacts, as Table 1) and writes the trajectory to
// `path`. A scene whose finger segments are not meshes (the box hand) gets neither times nor OBB
// trees. Throws io::InputError for a bad scene, std::runtime_error otherwise.
void export_grasp(const std::string& scene, const std::string& path,
                  const TrajectoryOptions& options);

// Median over the repeats of each step of `step_ns` ([repeat][step]).
std::vector<double> step_medians(const std::vector<std::vector<double>>& step_ns);

}  // namespace graspcd::study
