// graspcd grasp SCENE | --object FILE | SCENE --decomposed DIR: the grasp of paper section 9
// (grasp/grasp.h), a user's mesh in a template hand (grasp/object_run.h) or the object as its
// convex pieces (grasp/decomposed_scene.h); prints the text or the JSON (grasp/grasp_output.h).

#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "command.h"
#include "graspcd/grasp/decomposed_scene.h"
#include "graspcd/grasp/drive_config.h"
#include "graspcd/grasp/grasp.h"
#include "graspcd/grasp/grasp_output.h"
#include "graspcd/grasp/object_run.h"
#include "graspcd/mujoco/registry.h"
#include "graspcd/study/contact_judge.h"
#include "graspcd/version/envelope.h"
#include "method.h"
#include "object_placement.h"

namespace graspcd::cli {

namespace {

struct GraspCliOptions {
  MethodOptions method;
  std::string scene;
  std::string config;
  bool native = false;
  bool json = false;
  bool quiet = false;  // --quiet: the text without the per-step lines
  bool require_held = false;
  int max_steps = 400;
  double contact_reuse = 0;  // --contact-reuse M: the config's "contact_reuse" overridden
  bool exact = false;        // --exact: exact contacts every step (--contact-reuse 0)
  std::string manifold;  // --manifold support|moment|force[N]: the config's reduction overridden
  std::string object;    // --object FILE: a user's mesh in a template scene
  PlacementOptions placement;  // its placement (object_placement.h)
  std::string decomposed;      // --decomposed DIR: the object's collision by its convex pieces
  bool judge = false;          // --judge: every closing step's contacts against CGAL (the race)
  bool force = false;          // --force: --write-scene may replace files graspcd did not write
  int noslip = 0;              // --noslip N: MuJoCo's noslip iterations (default: the scene's)
  bool multiccd = false;       // --multiccd: MuJoCo's multi-point convex collision for the run
  int timestep_divisor = 1;    // --timestep-divisor K: the scene's step / K, K x the steps
};

// --judge: per closing grasp step, phantom and missed contacts (contact_judge.h).
nlohmann::json judge_json(const study::ContactJudgeSummary& j) {
  const double steps = j.steps > 0 ? j.steps : 1;
  return {{"steps", j.steps},
          {"contacts", j.contacts},
          {"phantom", j.phantom},
          {"missed", j.missed},
          {"phantom_by_geom", j.phantom_by_geom},
          {"missed_by_geom", j.missed_by_geom},
          {"truth_hits", j.truth_hits},
          {"contact_error_per_step", static_cast<double>(j.phantom + j.missed) / steps},
          {"cgal_first_contact", j.cgal_first_contact},
          {"cgal_first_contact_body", j.cgal_first_contact_body},
          {"phantom_distance", study::kPhantomDistance}};
}

// The race's judge on model m: the object and the support of the "grasp" section of the pair
// config at config_path (drive_config.h), the body "object" and no support (the world body only,
// which the judge always leaves out) when there is no such file or section (examples 1-3).
std::unique_ptr<study::ContactJudge> make_judge(const mjModel* m, const std::string& config_path) {
  std::optional<grasp::DriveConfig> drive;
  std::error_code ec;
  if (std::filesystem::is_regular_file(config_path, ec))
    drive = grasp::load_drive_config(config_path);
  if (!drive) return std::make_unique<study::ContactJudge>(m);
  return std::make_unique<study::ContactJudge>(m, drive->object, drive->support);
}

// The rules between the options that CLI11 does not check.
void check_usage(const GraspCliOptions& options, const CLI::App& app) {
  if (options.object.empty() == options.scene.empty()) {
    throw UsageError("grasp: give either SCENE or --object FILE");
  }
  check_placement_options(app, "grasp", "--object", !options.object.empty());
  if (app.count("--contact-reuse") > 0 && (options.native || !options.decomposed.empty())) {
    throw UsageError("grasp: --contact-reuse goes with graspcd's contacts, not --native");
  }
  if (options.exact && (options.native || !options.decomposed.empty())) {
    throw UsageError("grasp: --exact goes with graspcd's contacts, not --native or --decomposed");
  }
  if (options.exact && app.count("--contact-reuse") > 0) {
    throw UsageError("grasp: --exact is --contact-reuse 0: give one of them");
  }
  if (options.force && options.placement.write_scene.empty()) {
    throw UsageError("grasp: --force goes with --write-scene");
  }
  if (!options.decomposed.empty() && !options.object.empty()) {
    throw UsageError(
        "grasp: --decomposed goes with SCENE (write the --object scene with "
        "--write-scene first)");
  }
}

// The grasp's options from the command line's: the config's overridden where given.
grasp::GraspOptions grasp_options(const GraspCliOptions& options, const CLI::App& app) {
  grasp::GraspOptions grasp;
  grasp.config_path = options.config;
  grasp.native = options.native;
  grasp.max_steps = options.max_steps;
  if (app.count("--contact-reuse") > 0) grasp.contact_reuse = options.contact_reuse;
  if (options.exact) grasp.contact_reuse = 0.0;
  if (app.count("--manifold") > 0) {
    const auto choice = grasp::parse_manifold_choice(options.manifold);
    if (!choice || options.native || !options.decomposed.empty()) {
      throw UsageError(
          "grasp: --manifold takes support, moment or force, optionally with the "
          "contacts per pair 1-50 (force4), and goes with graspcd's contacts, not --native");
    }
    grasp.reduction = choice->reduction;
    grasp.max_contacts = choice->max_contacts;
  }
  if (app.count("--noslip") > 0) grasp.noslip_iterations = options.noslip;
  if (app.count("--multiccd") > 0) grasp.multiccd = options.multiccd;
  grasp.timestep_divisor = options.timestep_divisor;
  grasp.true_penetration = true;  // every run of the command measures it
  if (app.count("--method") > 0) grasp.method = options.method.method;
  if (app.count("--cap") > 0) grasp.cap = options.method.cap;
  if (app.count("--switch") > 0) grasp.switch_passes = options.method.switch_passes;
  return grasp;
}

// --object FILE: the run's template and folders (checked before the work).
grasp::ObjectRunOptions object_run_options(const GraspCliOptions& options) {
  grasp::ObjectRunOptions run;
  run.file = options.object;
  run.hand = hand_template(options.placement.hand, "grasp");
  run.write_scene = options.placement.write_scene;
  run.force = options.force;
  return run;
}

// Its scene, written before the grasp; a bad --up is a usage error.
void write_object(const GraspCliOptions& options, grasp::ObjectRun& run) {
  try {
    run.write(object_placement(options.placement, options.object));
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("grasp: ") + e.what());
  }
}

void run_grasp_command(GraspCliOptions& options, const CLI::App& app, int* exit_code) {
  finish_method_options(options.method);
  check_usage(options, app);
  grasp::GraspOptions grasp = grasp_options(options, app);
  std::optional<grasp::ObjectRun> object;
  if (!options.object.empty()) write_object(options, object.emplace(object_run_options(options)));
  // --judge: built on the first closing step's model, with the object and support bodies of the
  // drive config the grasp reads (--config, else SCENE.pairs.json: for --decomposed the original
  // scene's, for --object the written template's); the grasp has already checked that config.
  std::unique_ptr<study::ContactJudge> judge;
  if (options.judge) {
    const std::string scene = object ? object->scene() : options.scene;
    const std::string config_path =
        options.config.empty() ? mujoco::pair_config_path(scene) : options.config;
    grasp.on_grasp_step = [&judge, config_path](const mjModel* m, const mjData* d, int step) {
      if (!judge) judge = make_judge(m, config_path);
      judge->judge_step(m, d, step);
    };
  }
  std::optional<grasp::DecomposedScene> decomposed;
  grasp::GraspResult result;
  if (object) {
    result = object->grasp(grasp);
  } else if (!options.decomposed.empty()) {
    decomposed.emplace();
    result = grasp::run_decomposed_grasp(options.scene, options.decomposed, grasp, &*decomposed);
  } else {
    result = grasp::run_grasp(options.scene, grasp);
  }
  const grasp::ObjectRunDescription* ran = object ? &object->description() : nullptr;
  const grasp::DecomposedScene* pieces = decomposed ? &*decomposed : nullptr;
  if (options.json) {
    nlohmann::json doc = grasp::grasp_json(result, ran, pieces, options.decomposed);
    if (judge) doc["judge"] = judge_json(judge->summary());
    add_envelope(doc);
    std::cout << doc.dump(2) << '\n';
  } else {
    std::cout << grasp::grasp_text(result, ran, pieces, options.quiet);
    if (judge) {
      const study::ContactJudgeSummary j = judge->summary();
      std::cout << "# judged by CGAL over " << j.steps << " closing steps: " << j.contacts
                << " hand-object contacts, " << j.phantom << " phantom, " << j.missed
                << " missed\n";
    }
  }
  if (options.require_held && !result.held) *exit_code = 1;
}

}  // namespace

Command add_grasp_command(CLI::App& parent) {
  auto options = std::make_shared<GraspCliOptions>();
  CLI::App* app = parent.add_subcommand(
      "grasp", "Run a grasp (paper section 9): per grasp step, contacts and detection time");
  CLI::Option* scene =
      app->add_option("SCENE", options->scene, "The scene: an MJCF file of mjcf/ (or --object)");
  app->add_option("--object", options->object,
                  "A mesh (OBJ, STL, OFF, PLY, glTF/GLB or COLLADA) grasped in a template scene "
                  "instead of SCENE")
      ->excludes(scene);
  add_placement_options(
      *app, options->placement,
      {{Placement::kScale, "--object: file units to metres (default 1: the file is in metres)"},
       {Placement::kFit,
        "--object: scale the object to the template's room instead (said on the first line)"},
       {Placement::kHand,
        "--object: the template: project (the arm and 4-finger hand), robotiq (the Robotiq "
        "2F-85), shadow (the Shadow hand), or a template scene file"},
       {Placement::kUp, "--object: the file axis that points up: x, y, z, -x, -y, -z"},
       {Placement::kYaw, "--object: then a turn about the up direction, degrees"},
       {Placement::kPose,
        "--object: the object's rotation as a quaternion W X Y Z (instead of --up, --yaw)"},
       {Placement::kOffset,
        "--object: then moved DX DY metres across gravity from the hand's centre (the support "
        "point; for the templates: along the world x and y)"},
       {Placement::kWriteScene,
        "--object: write the scene (FILE's stem .xml and .pairs.json) into this folder and keep "
        "it (default: a temporary folder, removed)"}});
  app->add_flag("--force", options->force,
                "--write-scene: replace files in DIR that graspcd did not write (never the "
                "template or the object the run reads)");
  app->add_flag("--require-held", options->require_held,
                "Exit with code 1 when the object was not held");
  add_method_options(*app, options->method, MethodDefaults::kSceneConfig);
  app->add_flag("--native", options->native,
                "MuJoCo's own collision (convex hulls) instead of graspcd's callback");
  app->add_option("--decomposed", options->decomposed,
                  "A folder written by graspcd decompose: the object collides as its convex "
                  "pieces, under MuJoCo's native collision (implies --native)");
  app->add_flag("--judge", options->judge,
                "Judge every closing step's hand-object contacts against the true meshes (CGAL)");
  app->add_flag("--json", options->json, "Print one JSON document instead of text");
  app->add_flag("--quiet", options->quiet,
                "Text without the per-step lines: the object line (--object) and the '#' summary "
                "lines (no effect with --json)");
  app->add_option("--config", options->config,
                  "Pair config (JSON); default SCENE.pairs.json beside the scene");
  app->add_option("--noslip", options->noslip,
                  "MuJoCo's noslip solver iterations (mjOption.noslip_iterations, 0: off) for "
                  "every configuration (default: the scene's, MuJoCo's 0)")
      ->check(CLI::Range(0, 1000));
  app->add_flag("--multiccd", options->multiccd,
                "MuJoCo's multi-point convex collision (mjENBL_MULTICCD) for what MuJoCo "
                "collides itself: --native's hulls, --decomposed's pieces, the pairs graspcd "
                "does not serve (--multiccd=false: off; default: the scene's flag, MuJoCo's off)");
  app->add_option("--timestep-divisor", options->timestep_divisor,
                  "The scene's time step divided by K, with K times the physics steps per grasp "
                  "step, so that the drive is the same in time (a finer run of the same grasp; "
                  "JSON timestep and physics_steps_per_grasp_step record what ran)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  app->add_option("--max-steps", options->max_steps, "Most closing grasp steps")
      ->check(positive_number())
      ->capture_default_str();
  app->add_option("--manifold", options->manifold,
                  "The contacts per served pair: support (the support polygon, the default), "
                  "moment (each patch's net normal direction and moment about its centre of "
                  "pressure kept: an anchor and support extremes) or force (the support points "
                  "of 8 per pair reduced to the budget with each patch's summed depth and "
                  "centre of pressure kept), optionally followed by the contacts per pair "
                  "(force4: at most 4); overrides the config's \"reduction\" "
                  "and \"max_contacts\"");
  app->add_option("--contact-reuse", options->contact_reuse,
                  "Metres in [0, 0.001]: reuse a touching pair's contacts, their depths "
                  "refreshed, while it moved less than this since its last exact query (faster; "
                  "contacts that begin or end within it wait for the next query; the hard scenes "
                  "pass at 2e-5, not at 5e-5); 0: exact contacts every step (--exact; "
                  "default: the config's \"contact_reuse\", else 2e-5)")
      ->check(number_in_range(0.0, mujoco::RegistryConfig::kMaxContactReuse));
  app->add_flag("--exact", options->exact,
                "Exact contacts every step: each served pair queried at every physics step, "
                "none reused (--contact-reuse 0; in a pair config \"contact_reuse\": 0). The "
                "default reuses a pair's contacts while it moves less than 20 um");
  app->footer(wrap_help(kGraspHelp));
  auto exit_code = std::make_shared<int>(0);
  return Command{app,
                 [options, app, exit_code] { run_grasp_command(*options, *app, exit_code.get()); },
                 exit_code};
}

}  // namespace graspcd::cli
