// graspcd validate SCENE.xml [--method M | --all-methods] [--max-steps N] [--config F] [--out DIR]
// [--json] [--decomposed DIR]: the scene's grasp, every registered pair checked against CGAL at
// every closing grasp step (src/graspcd/study/validate.h). Exit code 1 on any missed collision.
// graspcd validate --objects DIR [--hand H] [--fit | --scale S] [--up A] [--yaw D] [--shard i/N]
// [--out OUT]: every OBJ/STL under DIR through the --object workflow, one row per object
// (src/graspcd/study/object_set.h); graspcd validate --merge FILE... joins the shards. Their exit
// code: 1 when a method missed a collision or gave a false one on some object, else 2 when an
// object was refused, else 0 (object_set_exit_code()).
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "command.h"
#include "graspcd/io/output_files.h"
#include "graspcd/io/text_input.h"
#include "graspcd/io/warnings.h"
#include "graspcd/mujoco/model_loading.h"
#include "graspcd/mujoco/registry.h"
#include "graspcd/study/object_set.h"
#include "graspcd/study/study.h"
#include "graspcd/study/validate.h"
#include "graspcd/study/validate_output.h"
#include "graspcd/version/envelope.h"
#include "method.h"
#include "object_placement.h"
#include "progress.h"

namespace graspcd::cli {

namespace {

struct ValidateCliOptions {
  MethodOptions method;
  std::string scene;
  std::string config;
  std::string out_dir;     // empty: nothing written
  std::string decomposed;  // --decomposed DIR: the grasp runs on the object's convex pieces
  bool all_methods = false;
  bool json = false;
  int steps = 400;
  std::string phases = "closing,squeeze";  // --phases
  // --objects DIR: an object set through the --object workflow (object_set.h).
  std::string objects;
  std::string shard;               // --shard i/N of the set
  std::vector<std::string> merge;  // --merge FILE...: join the shards
  PlacementOptions placement;      // of each object (object_placement.h)
};

// The exit code when a method missed a collision (the output is complete).
constexpr int kExitMissed = 1;
// The exit code of bad input (main.cpp's for an io::InputError); for an object set, when an
// object was refused and every object checked agreed with CGAL (the output is complete).
constexpr int kExitBadInput = 2;

// The scene is named before its config: a config that cannot be read is reported only when the
// scene itself loads (a file that is no scene is refused as such, whatever its config).
[[noreturn]] void config_refused(const std::string& scene, const io::InputError& error) {
  mujoco::load_model(scene);
  throw error;
}

// The methods to check: --all-methods, --method, or the config's (SCENE's, or the template's for
// --objects); cap and switch from the command line when given, else from the config.
std::vector<study::TesterSpec> testers_of(ValidateCliOptions& o, const CLI::App& app,
                                          const std::string& scene) {
  const std::string config_path = o.config.empty() ? mujoco::pair_config_path(scene) : o.config;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(scene, ec)) {
    throw io::InputError(scene, 0, "cannot open the scene");
  }
  if (!std::filesystem::is_regular_file(config_path, ec)) {
    config_refused(scene, io::InputError(config_path, 0, "cannot open the pair config"));
  }
  mujoco::RegistryConfig config;
  try {
    config = mujoco::load_registry_config(config_path);
  } catch (const io::InputError& e) {
    config_refused(scene, e);
  }
  DetectorOptions detector = config.detector;
  if (app.count("--cap") > 0) detector.cap = o.method.cap;
  if (app.count("--switch") > 0) detector.switch_passes = o.method.switch_passes;
  std::vector<Method> methods;
  if (o.all_methods) {
    // perceptron-nodisp proves almost no node pair of a mesh disjoint, so its query tests nearly
    // every triangle pair (docs/stress.md, "Known limitations"): asked for by name only.
    for (Method m : all_methods()) {
      if (m != Method::kPerceptronNoDisp) methods.push_back(m);
    }
  } else if (app.count("--method") > 0) {
    finish_method_options(o.method);
    methods = {o.method.method};
  } else {
    methods = {config.method};
  }
  std::vector<study::TesterSpec> specs;
  for (Method m : methods) specs.push_back(study::detector_tester(m, detector));
  return specs;
}

// An object set's exit code: a method that missed a collision or gave a false one on some object
// is the worst finding (1; on the template hands' triangle pairs every method answers exactly,
// so a false collision is a defect too), then an object refused (2, bad input), else 0. Every
// object has its row either way.
int object_set_exit_code(const nlohmann::json& doc) {
  if (doc["missed_any"].get<bool>() || doc["false_any"].get<bool>()) return kExitMissed;
  return doc["refused"].get<int>() > 0 ? kExitBadInput : 0;
}

void print_object_set(const nlohmann::json& doc, bool json) {
  if (json) {
    nlohmann::json with_envelope = doc;
    add_envelope(with_envelope);
    std::cout << with_envelope.dump(2) << '\n';
  } else {
    std::cout << study::object_set_text(doc);
  }
}

// --objects DIR: the set (or one shard of it), printed and, with --out, written as
// OUT/objects.json or OUT/objects.shard-i-of-N.json.
int run_object_set(ValidateCliOptions& o, const CLI::App& app) {
  // A bad --up is a usage error before any object is read (the message of object_scene.h).
  const std::vector<std::string> axes = {"x", "y", "z", "-x", "-y", "-z"};
  if (std::find(axes.begin(), axes.end(), o.placement.up) == axes.end()) {
    throw UsageError("validate: --up must be one of x, y, z, -x, -y, -z (not '" + o.placement.up +
                     "')");
  }
  study::ObjectSetOptions options;
  options.hand = hand_template(o.placement.hand, "validate");
  const std::vector<study::TesterSpec> testers = testers_of(o, app, options.hand.scene);
  options.dir = o.objects;
  options.placement = object_placement(o.placement, "");
  options.max_steps = o.steps;
  options.out_dir = o.out_dir;
  if (!o.shard.empty()) {
    try {
      options.shard = study::parse_shard(o.shard);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("validate: ") + e.what());
    }
  }
  Progress progress("validate");
  options.log = [&progress](const std::string& line) { progress.update(line); };
  // The table's rows are printed as the objects are checked (the JSON document at the end).
  if (!o.json) {
    options.on_row = [&progress](const nlohmann::json& so_far, const nlohmann::json& row) {
      std::string text = study::object_set_row(so_far, row);
      if (so_far["rows"].size() == 1) text = study::object_set_head(so_far) + text;
      progress.print(text);
    };
  }
  nlohmann::json doc;
  try {
    doc = study::validate_object_set(options, testers);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("validate: ") + e.what());
  }
  if (!o.out_dir.empty()) study::write_object_set(o.out_dir, doc);
  progress.done("checked the objects of " + o.objects);
  if (o.json) {
    print_object_set(doc, true);
  } else {
    if (doc["rows"].empty()) std::cout << study::object_set_head(doc);
    std::cout << study::object_set_tail(doc);
  }
  return object_set_exit_code(doc);
}

// --merge FILE...: the shards joined, printed and, with --out, written as OUT/objects.json.
int run_object_merge(ValidateCliOptions& o) {
  const nlohmann::json doc = study::merge_object_shards(o.merge);
  if (!o.out_dir.empty()) study::write_object_set(o.out_dir, doc);
  print_object_set(doc, o.json);
  return object_set_exit_code(doc);
}

int run_validate_command(ValidateCliOptions& o, const CLI::App& app) {
  const int modes =
      (o.scene.empty() ? 0 : 1) + (o.objects.empty() ? 0 : 1) + (o.merge.empty() ? 0 : 1);
  if (modes != 1) throw UsageError("validate: give one of SCENE, --objects DIR or --merge FILE...");
  check_placement_options(app, "validate", "--objects", !o.objects.empty());
  if (o.objects.empty() && app.count("--shard") > 0) {
    throw UsageError("validate: --shard goes with --objects");
  }
  // --out: checked (and created) before the work; left out again when nothing was written in it.
  std::optional<io::RemoveIfEmpty> created;
  if (!o.out_dir.empty() && io::prepare_output_folder(o.out_dir)) created.emplace(o.out_dir);
  if (!o.merge.empty()) return run_object_merge(o);
  if (!o.objects.empty()) return run_object_set(o, app);
  const std::vector<study::TesterSpec> testers = testers_of(o, app, o.scene);
  study::ValidateOptions options;
  options.config_path = o.config;
  options.max_steps = o.steps;
  options.out_dir = o.out_dir;
  options.decomposed_dir = o.decomposed;
  try {
    options.phases = study::parse_validate_phases(o.phases);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("validate: --phases: ") + e.what());
  }
  Progress progress("validate");
  long checked = 0;
  options.on_step = [&](const std::string& phase, long step) {
    ++checked;
    if (phase == "closing") {
      // The closing may end before --max-steps: the share is a lower bound.
      progress.update(o.scene + ": closing grasp step " + std::to_string(step) + " of at most " +
                          std::to_string(o.steps) + " checked",
                      static_cast<double>(step) / std::max(1, o.steps), true);
    } else {
      progress.update(o.scene + ": " + phase + " physics step " + std::to_string(step) +
                      " checked (" + std::to_string(checked) + " states so far)");
    }
  };
  const study::ValidationReport report = study::validate_scene(o.scene, testers, options);
  progress.done("checked " + o.scene + ": " + std::to_string(checked) + " states");
  if (report.states_with_contact() == 0) {
    warnings().add("validate_no_contact",
                   o.scene +
                       ": no checked state had a contact to check (no pair ever touched): "
                       "'no missed collision' says nothing about this scene",
                   "scene");
  }
  if (o.json) {
    nlohmann::json doc = study::validation_json(report);
    add_envelope(doc);
    std::cout << doc.dump(2) << '\n';
  } else {
    std::cout << study::validation_text(report);
  }
  return report.missed_any() ? kExitMissed : 0;
}

}  // namespace

Command add_validate_command(CLI::App& parent) {
  auto o = std::make_shared<ValidateCliOptions>();
  CLI::App* app = parent.add_subcommand(
      "validate",
      "Check a scene's grasp against CGAL: every registered pair through the closing and squeeze");
  app->add_option("SCENE", o->scene, "The scene: an MJCF file with its SCENE.pairs.json");
  app->add_option("--objects", o->objects,
                  "A folder of objects (every mesh file under it: OBJ, STL, OFF, PLY, glTF/GLB, "
                  "COLLADA): one row per object, each "
                  "grasped in the --hand template as graspcd grasp --object does");
  app->add_option("--shard", o->shard,
                  "--objects: only shard i of N of the set (every N-th object from the i-th)");
  app->add_option("--merge", o->merge,
                  "Join --objects shard files (OUT/objects.shard-i-of-N.json) into one table")
      ->expected(1, -1);
  add_placement_options(
      *app, o->placement,
      {{Placement::kHand,
        "--objects: the template: project, robotiq, shadow, allegro or a template scene file"},
       {Placement::kFit, "--objects: scale each object into the template's room"},
       {Placement::kScale, "--objects: file units to metres for every object"},
       {Placement::kUp, "--objects: the file axis that points up: x, y, z, -x, -y, -z"},
       {Placement::kYaw, "--objects: then a turn about the up direction, degrees"}});
  add_method_options(*app, o->method, MethodDefaults::kSceneConfig);
  app->add_flag("--all-methods", o->all_methods,
                "Check every method but perceptron-nodisp (default: the config's method)")
      ->excludes("--method");
  app->add_option("--max-steps,--steps", o->steps,
                  "Most closing grasp steps (--steps: the same, kept as an alias)")
      ->transform(positive_integer())
      ->capture_default_str();
  app->add_option("--phases", o->phases,
                  "The phases checked: all, or some of closing, squeeze, lift, hold (comma-"
                  "separated); the closing after each grasp step, the others every 5 physics "
                  "steps (a grasp step's worth)")
      ->capture_default_str();
  app->add_option("--config", o->config,
                  "Pair config (JSON); default SCENE.pairs.json beside the scene");
  app->add_option("--out", o->out_dir,
                  "Write the first disagreement of each method and pair into this folder (only "
                  "when there is one; default: nothing is written)");
  app->add_flag("--json", o->json, "Print one JSON document instead of the table");
  app->add_option("--decomposed", o->decomposed,
                  "A folder written by graspcd decompose: the grasp runs on the object's convex "
                  "pieces under MuJoCo's native collision; the checks stay on the true meshes");
  app->footer(wrap_help(
      "Runs the scene's grasp (as graspcd grasp, driven by the pair config's method) and, after "
      "every closing grasp step and every 5th physics step of the squeeze and its settling "
      "(--phases: the lift and the hold too), checks each registered pair with each method "
      "asked for (--method, --all-methods, or the config's method; --all-methods leaves out "
      "perceptron-nodisp, which proves almost no node pair of a mesh disjoint and so tests nearly "
      "every triangle pair: hours on example 3, ask for it by name) against CGAL's exact brute "
      "force over "
      "the same triangles in the same pose: the pair's answer (the surfaces intersect or not) "
      "and its set of intersecting triangle pairs. The methods query the MuJoCo layer's own trees, "
      "built from MuJoCo's float vertices in the geom frames, in all-contacts mode, one detector "
      "per pair kept across the steps; box-box pairs are checked with the method's box test "
      "against CGAL's exact box overlap. Use it on a new scene or object before trusting its "
      "timings.\n"
      "Output: a header line, then one row per method and pair: the steps checked, those that "
      "agree, those where CGAL says the pair intersects (truth), missed collisions (CGAL "
      "intersects, the method not), false collisions (the reverse), triangle pairs CGAL has and "
      "the method missed (tri_missed) and the reverse (tri_false), and the first step of any "
      "disagreement ('-' for none). Then per method the totals and, for each disagreeing pair, "
      "its first disagreement with the command that reproduces it: the two meshes exactly as the "
      "detector saw them (OBJ, geom frames, face order kept, every coordinate read back as the "
      "same double) and the pose line are written into --out (when given; nothing is written "
      "into the current folder otherwise), and 'graspcd meshpair A B --poses P' with the "
      "method's options prints the method's answer again (add --exact for CGAL's); box pairs "
      "write one boxbox line. A line '# contacts: N of M closing grasp steps, K of L squeeze "
      "states had a contact to check' counts, per phase, the states at which CGAL found some "
      "pair intersecting; with none in any phase, the result says so and a warning says that "
      "'no missed collision' means nothing there. A line '# checked: ...' says which phases "
      "were checked, how many states of each, whether --max-steps cut the closing short, and "
      "which phases were not checked. The squeeze is checked by default because the hand "
      "presses hardest there; --phases all checks the lift and the hold as well. Progress on "
      "stderr: the state checked, the time so far and, in the closing, at most how long is "
      "left, on a terminal one line rewritten, otherwise one line every 5 s "
      "(GRASPCD_PROGRESS_SECONDS).\n"
      "--json: one document: scene, config, grasp_method, steps (closing grasp steps checked), "
      "steps_with_contact (of those), phases (the names checked), checks (per phase: phase, "
      "states, with_contact, physics_steps between two checked states, 0 for the closing's "
      "grasp steps), max_steps, cut_short, gripped, "
      "cgal, exact_seconds, "
      "tester_seconds, nonfinite_skips (pair checks skipped on a placement with NaN, inf or a "
      "number beyond 1e10), missed_any, methods (method, missed_any, seconds, pairs: pair, geom1, "
      "geom2, "
      "path, "
      "steps, agree, truth_hits, missed, false_contacts, pair_mismatch, missed_tri_pairs, "
      "false_tri_pairs, first_disagreement: null or phase, step, truth, answer, truth_pairs, "
      "answer_pairs, files, command), decomposed (null, or dir, source, pieces, geoms).\n"
      "--decomposed DIR: the truth side of the race. The grasp runs as 'graspcd "
      "grasp SCENE --decomposed DIR' does: the object's geoms of the mesh DIR decomposes keep "
      "their mass without colliding, one geom per convex piece collides in their place under "
      "MuJoCo's native collision, SCENE.pairs.json drives the hand. At each closing grasp step "
      "of that grasp, every pair the config registers is checked as above on the true meshes "
      "(the original geoms, not the pieces) in the poses the pieces' contacts produced: the "
      "methods against CGAL. A line '# decomposed: ...' follows the header. A DIR without "
      "decomposition.json, or a SCENE without a mesh of its source, is bad input (exit code "
      "2).\n"
      "Exit code: 0 when no method missed a collision or an intersecting triangle pair (false "
      "collisions are reported, not failures: the perceptron may leave boxes it cannot separate "
      "within its cap), 1 when one did, 2 for bad input (a missing or bad scene or config: one "
      "line 'FILE: message').\n"
      "--objects DIR: every mesh file under DIR (.obj, .stl, .off, .ply, .gltf, .glb, .dae; "
      "recursively, sorted by path) goes "
      "through the graspcd grasp --object workflow (--hand, --fit or --scale, --up, --yaw: the "
      "same for every object; the start state checked) and is validated as above. One row per "
      "object: its scale, the closing grasp steps checked, the steps with a contact to check, "
      "CGAL's hits (pair checks that intersect), missed/false collisions per method, and the "
      "grasp's verdict (held; gripped, not held: REASON; not gripped: REASON), each row printed "
      "as soon as its object is checked. An object that "
      "cannot be checked (a bad mesh, a start state that is not valid) is a row 'refused' with "
      "its one-line error, and a line 'warning: FILE:LINE: message' on stderr (the line where "
      "the loader names one); the others go on. Exit code: 1 when some method missed a "
      "collision or a triangle pair, or gave a false one, on some object (on the template "
      "hands' triangle pairs every method answers exactly, so a false collision is a defect "
      "too), else 2 when some object was refused (bad input), else 0; every object has its row "
      "either way. --out OUT writes the document as "
      "OUT/objects.json (with --shard i/N: OUT/objects.shard-i-of-N.json) and the first "
      "disagreements under OUT/OBJECT/. --json prints the document: objects_dir, hand, template, "
      "settings, objects (the whole set), shard, rows (object, status, error, scale, fitted, "
      "size, steps, steps_with_contact, states and states_with_contact (every phase checked), "
      "cgal_hits, gripped, held, reason, methods: method, "
      "checks, agree, missed, false_contacts, missed_tri_pairs, false_tri_pairs), missed_any, "
      "false_any, refused (the number of objects refused).\n"
      "--merge FILE...: joins the shard files of one split of one set (same objects, settings "
      "and N, each shard once) into the table of the whole set (--out OUT: OUT/objects.json); "
      "a missing shard is named with its objects (exit code 2); the exit code of the joined set "
      "is --objects' own. cluster/"
      "validate_objects.sbatch runs the shards as a Slurm array job.\n"
      "Examples:\n"
      "  graspcd validate mjcf/example3.xml\n"
      "  graspcd validate mjcf/hand_boxes.xml --all-methods --max-steps 100 --json\n"
      "  graspcd decompose mjcf/meshes/cup.obj --out /tmp/cup8 --pieces 8\n"
      "  graspcd validate mjcf/example1.xml --decomposed /tmp/cup8\n"
      "  graspcd validate --objects ../shared/models/objects/mujoco --fit --method sat --out "
      "/tmp/o\n"
      "  graspcd validate --objects DIR --fit --shard 0/4 --out /tmp/o\n"
      "  graspcd validate --merge /tmp/o/objects.shard-*-of-4.json --out /tmp/o"));
  auto exit_code = std::make_shared<int>(0);
  return Command{app, [o, app, exit_code] { *exit_code = run_validate_command(*o, *app); },
                 exit_code};
}

}  // namespace graspcd::cli
