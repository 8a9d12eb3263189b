// `graspcd validate`: a scene's grasp, checked at every closing grasp step against
// CGAL. Each registered pair's answer (intersect or not) and its set of intersecting triangle
// pairs, for every method asked for, is compared with CGAL's exact brute force over the same
// triangles in the same pose (exact::mesh_mesh_pairs; for box-box pairs exact::box_box_overlap).
//
// What is checked, precisely:
// - The grasp runs once served by graspcd (grasp/grasp.h) with the pair config's method (the
//   trajectory the user times). After each closing grasp step (the state after its last physics
//   step, as the study records it), every pair of the attached registry is posed from
//   d->geom_xpos / d->geom_xmat (mujoco::relative_pose, geom2 in geom1's frame, geom1 the geom
//   MuJoCo passes first: the lower type, then the lower id).
// - Tree pairs (meshes and tessellated primitives): each method's tester queries the registry's
//   trees, built from MuJoCo's float vertices in the geom frames, in all-contacts mode. The truth
//   is CGAL on the same triangles (the trees' faces in face order, geom2's moved by the same pose
//   in doubles).
// - Box-box pairs: each tester's box test on the two geom boxes, against CGAL's exact overlap.
// - Each tester keeps its state across the steps of the run (warm planes, caches), one per pair,
//   as the served pairs' detectors do.
// - The phases (ValidatePhases, `--phases`): the closing after each grasp step; the squeeze (with
//   its settling), the lift and the hold after every `physics_steps_per_grasp_step`-th physics
//   step of each (a grasp step's worth, 5 steps of 2 ms by default). By default the closing and
//   the squeeze, where the hand presses on what it closed on.
// A method that answered the same as the truth at every pair and step lets the grasp take the same
// path whichever method drives it, so checking every method on one trajectory is the same as
// running the grasp with each up to its first disagreement.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "graspcd/core/geometry.h"
#include "graspcd/core/obb.h"
#include "graspcd/core/obb_tree.h"
#include "graspcd/core/separators.h"
#include "graspcd/core/tree_query.h"
#include "graspcd/grasp/decomposed_scene.h"
#include "graspcd/mujoco/scene_names.h"

namespace graspcd::study {

// The answers under test: one tester per method, with state for `pairs` pairs.
class PairTester {
 public:
  virtual ~PairTester() = default;
  // Tree pair `pair`: b placed in a's frame; fills `tri_pairs` (face ids, any order) with every
  // intersecting triangle pair found and returns whether the trees intersect.
  virtual bool tree_query(std::size_t pair, const ObbTree& a, const ObbTree& b, const Pose& b_in_a,
                          std::vector<TrianglePair>& tri_pairs) = 0;
  // Box-box pair `pair`: true when the boxes are proven disjoint.
  virtual bool box_disjoint(std::size_t pair, const Obb& a, const Obb& b) = 0;
};

// A named way to make a tester (for `pairs` pairs), e.g. detector_tester().
struct TesterSpec {
  std::string name;
  // What reproduces a tree pair's answer from the written files: "graspcd meshpair A B <args>
  // --poses P" and "graspcd boxbox <args> FILE" get these arguments (e.g. "--method sat").
  std::string cli_args;
  std::function<std::unique_ptr<PairTester>(std::size_t pairs)> make;
};

// A served pair's Detector of `method` with `options`, one per pair.
TesterSpec detector_tester(Method method, const DetectorOptions& options);

// Which phases of the grasp are checked (grasp.h's phases; the squeeze includes its settling).
struct ValidatePhases {
  bool closing = true;
  bool squeeze = true;
  bool lift = false;
  bool hold = false;
};

// `--phases` text: "all" or a comma-separated list of closing, squeeze, lift, hold (none twice,
// at least one). Throws std::invalid_argument saying what is wrong.
ValidatePhases parse_validate_phases(const std::string& text);

struct ValidateOptions {
  std::string config_path;  // pair config; empty: SCENE.pairs.json beside the scene
  int max_steps = 400;      // most closing grasp steps
  ValidatePhases phases;
  // Where the first disagreement of each (method, pair) is written (created when needed); empty:
  // nothing is written.
  std::string out_dir;
  // Called after each checked state: its phase ("closing", "squeeze", "lift", "hold") and its
  // step (the closing's grasp step, or the phase's physics step), e.g. for progress.
  std::function<void(const std::string& phase, long step)> on_step;
  // A folder written by `graspcd decompose` (empty: none): the grasp runs with the object replaced
  // by its convex pieces under MuJoCo's native collision (grasp::run_decomposed_grasp, as
  // `graspcd grasp --decomposed`), and at its poses every registered pair is checked on the true
  // meshes (the original geoms, grasp::true_object_model), as without it.
  std::string decomposed_dir;
  // How messages name the files of a scene graspcd wrote (grasp::GraspOptions::names).
  mujoco::SceneNames names;
};

// The first disagreement of a (method, pair), and the files that reproduce it.
struct Disagreement {
  std::string phase = "closing";  // ValidatePhases' name of its phase
  long step = 0;                  // 1-based closing grasp step, or physics step of the phase
  bool truth = false;             // CGAL: the pair intersects
  bool answer = false;            // the method
  std::uint64_t truth_pairs = 0;  // intersecting triangle pairs (tree pairs)
  std::uint64_t answer_pairs = 0;
  // Written files (empty when ValidateOptions::out_dir is empty): tree pairs the two meshes as OBJ
  // (geom frames, the detector's doubles, face order kept) and the pose line (meshpair's 12
  // numbers); box-box pairs the boxbox line (30 numbers).
  std::vector<std::string> files;
  std::string command;  // the graspcd command that reproduces the method's answer
};

// One (method, pair) row of the table.
struct PairRow {
  std::string pair;  // "geom1/geom2" by name ("geom<id>" for an unnamed geom)
  int geom1 = 0;
  int geom2 = 0;
  bool box_box = false;
  int steps = 0;                       // states checked (every phase)
  int agree = 0;                       // steps with the same answer and the same triangle pairs
  int truth_hits = 0;                  // steps where CGAL says the pair intersects
  int missed = 0;                      // CGAL intersects, the method says not: a missed collision
  int false_contacts = 0;              // the method intersects, CGAL says not
  int pair_mismatch = 0;               // both intersect, but the triangle pairs differ
  std::uint64_t missed_tri_pairs = 0;  // triangle pairs CGAL has and the method lacks
  std::uint64_t false_tri_pairs = 0;   // triangle pairs the method has and CGAL lacks
  bool disagreed = false;
  Disagreement first;  // valid when disagreed
};

struct MethodTable {
  std::string method;
  std::vector<PairRow> rows;
  double seconds = 0;  // the method's query time over the run
  // Any missed collision or missed triangle pair (a contact the method would not give MuJoCo).
  bool missed_any() const;
};

// The states checked in one phase.
struct PhaseChecks {
  std::string phase;      // "closing", "squeeze", "lift" or "hold"
  int states = 0;         // states checked (the closing: its grasp steps)
  int with_contact = 0;   // those at which CGAL found some pair intersecting
  int physics_steps = 0;  // physics steps between two checked states (the closing: 0, per step)
};

struct ValidationReport {
  std::string scene;
  std::string config;
  std::string grasp_method;    // the method that drove the grasp
  int steps = 0;               // closing grasp steps checked
  int steps_with_contact = 0;  // those at which CGAL found some pair intersecting
  // Every phase asked for, in the grasp's order (the closing's entry has `steps`).
  std::vector<PhaseChecks> phases;
  int states_with_contact() const;  // over every phase
  // ValidateOptions::max_steps, and whether the closing ran that many grasp steps: --max-steps
  // cut it short (the hand had not said it was done before).
  int max_steps = 0;
  bool cut_short = false;
  bool gripped = false;  // the grasp's verdict (grasp::GraspResult::gripped)
  bool held = false;     // grasp::GraspResult::held
  std::string reason;    // why not held (grasp::GraspResult::reason); empty when held
  std::vector<MethodTable> methods;
  double exact_seconds = 0;   // CGAL's time over the run
  double tester_seconds = 0;  // the testers' time over the run
  // (step, pair) checks skipped because a geom's placement held NaN, inf or a number beyond 1e10
  // (mujoco::bad_geom_placement, the rule of the served path): nothing to check on such a pose.
  std::uint64_t nonfinite_skips = 0;
  // ValidateOptions::decomposed_dir: the folder and what was replaced (pieces 0 without it).
  std::string decomposed_dir;
  grasp::DecomposedScene decomposed;
  bool missed_any() const;
};

// Runs the grasp of `scene` and checks every tester at every closing grasp step. Throws
// io::InputError for a missing or bad scene or config (as `graspcd grasp`).
ValidationReport validate_scene(const std::string& scene, const std::vector<TesterSpec>& testers,
                                const ValidateOptions& options = {});

}  // namespace graspcd::study
