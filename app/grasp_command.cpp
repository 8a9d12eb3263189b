// graspcd grasp SCENE | --object FILE | SCENE --decomposed DIR: the grasp of paper section 9
// (grasp/grasp.h), a user's mesh in a template hand (grasp/object_run.h) or the object as its
// convex pieces (grasp/decomposed_scene.h); prints the text or the JSON (grasp/grasp_output.h).

#include <cstdint>
#include <iostream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "command.h"
#include "graspcd/grasp/decomposed_scene.h"
#include "graspcd/grasp/drive_config.h"
#include "graspcd/grasp/grasp.h"
#include "graspcd/grasp/grasp_output.h"
#include "graspcd/grasp/object_batch.h"
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
  std::string drive;           // --drive FILE: --hand is a hand file, wrapped (hand_wrapper.h)
  std::string decomposed;      // --decomposed DIR: the object's collision by its convex pieces
  bool judge = false;          // --judge: every closing step's contacts against CGAL (the race)
  bool force = false;          // --force: --write-scene may replace files graspcd did not write
  int noslip = 0;              // --noslip N: MuJoCo's noslip iterations (default: the scene's)
  bool multiccd = false;       // --multiccd: MuJoCo's multi-point convex collision for the run
  double load_timeout = grasp::kDefaultLoadTimeout;  // --load-timeout: --object's wait, s
  std::string write_run;        // --write-run FILE: the run record (docs/run-record.md)
  bool six_directions = false;  // --six-directions: the test after the hold
  int placements = 0;           // --placements N: a batch of N grasps of --object (0: one grasp)
  std::uint64_t seed = 1;       // --seed S: the batch's placements
  double max_offset = 0.005;    // --max-offset M: the batch's offsets, m
  int timestep_divisor = 1;     // --timestep-divisor K: the scene's step / K, K x the steps
};

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
  if (!options.drive.empty() && options.object.empty()) {
    throw UsageError("grasp: --drive goes with --object and --hand HAND_FILE");
  }
  if (app.count("--load-timeout") > 0 && options.object.empty()) {
    throw UsageError("grasp: --load-timeout goes with --object");
  }
  if (options.force && options.placement.write_scene.empty()) {
    throw UsageError("grasp: --force goes with --write-scene");
  }
  if (!options.write_run.empty() && !options.object.empty() &&
      options.placement.write_scene.empty()) {
    throw UsageError(
        "grasp: --write-run with --object needs --write-scene DIR (the scene the record is "
        "judged on)");
  }
  const bool batch = app.count("--placements") > 0;
  if (!options.decomposed.empty() && !options.object.empty() && !batch) {
    throw UsageError(
        "grasp: --decomposed goes with SCENE or with --object and --placements (or write the "
        "--object scene with --write-scene first)");
  }
  for (const char* o : {"--seed", "--max-offset"}) {
    if (app.count(o) > 0 && !batch)
      throw UsageError(std::string("grasp: ") + o + " goes with --placements");
  }
  if (batch) {
    if (options.object.empty()) throw UsageError("grasp: --placements goes with --object");
    for (const char* o : {"--pose", "--offset", "--write-scene", "--fit"}) {
      if (app.count(o) > 0) {
        throw UsageError(std::string("grasp: ") + o +
                         " goes with one grasp, not --placements (a batch draws its placements "
                         "and keeps one scale)");
      }
    }
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
  grasp.write_run = options.write_run;
  grasp.six_directions = options.six_directions;
  if (app.count("--method") > 0) grasp.method = options.method.method;
  if (app.count("--cap") > 0) grasp.cap = options.method.cap;
  if (app.count("--switch") > 0) grasp.switch_passes = options.method.switch_passes;
  return grasp;
}

// --object FILE: the run's template and folders (checked before the work).
grasp::ObjectRunOptions object_run_options(const GraspCliOptions& options) {
  grasp::ObjectRunOptions run;
  run.file = options.object;
  run.hand = options.drive.empty()
                 ? hand_template(options.placement.hand, "grasp")
                 : hand_with_drive(options.placement.hand, options.drive, "grasp");
  run.write_scene = options.placement.write_scene;
  run.force = options.force;
  run.load_timeout = options.load_timeout;
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

// One line of a batch (JSON Lines, docs/objects.md "A batch of grasps"): the placement, and the
// grasp's document or why it did not run.
nlohmann::json batch_line(const grasp::BatchGrasp& b, int index, const grasp::ObjectBatch& batch,
                          const GraspCliOptions& options, const study::ContactJudge* judge) {
  static const char* const kOutcomes[] = {"grasped", "skipped", "cannot_start"};
  const grasp::ObjectPlacement& p = b.placement;
  nlohmann::json placement = {{"index", index},      {"seed", options.seed},
                              {"up", p.up},          {"yaw_deg", p.yaw_degrees},
                              {"offset", p.offset},  {"scale", b.placed.scale},
                              {"pos", b.placed.pos}, {"quat", b.placed.quat}};
  nlohmann::json line;
  if (b.outcome == grasp::BatchOutcome::kGrasped) {
    grasp::ObjectRunDescription ran = batch.description();
    ran.scene.scale = b.placed.scale;
    ran.scene.size = b.placed.size;
    ran.scene.pos = b.placed.pos;
    ran.scene.quat = b.placed.quat;
    line = grasp::grasp_json(b.result, &ran, batch.decomposed(), options.decomposed);
    if (judge) line["judge"] = study::contact_judge_json(judge->summary());
  } else {
    line = {{"scene", b.result.scene}, {"refusal", b.refusal}};
  }
  line["outcome"] = kOutcomes[static_cast<int>(b.outcome)];
  line["placement"] = placement;
  line["cost"] = grasp::cost_json(b.result.cost);
  return line;
}

// The batch's text line of one placement.
std::string batch_text(const grasp::BatchGrasp& b, int index) {
  std::ostringstream out;
  const grasp::ObjectPlacement& p = b.placement;
  out << "placement " << index << ": up " << p.up << ", yaw " << p.yaw_degrees << " deg, offset "
      << p.offset[0] << " " << p.offset[1] << " m: ";
  switch (b.outcome) {
    case grasp::BatchOutcome::kGrasped:
      out << (b.result.held ? "held" : "not held");
      if (!b.result.held) out << " (" << b.result.reason << ")";
      break;
    case grasp::BatchOutcome::kSkipped:
      out << "skipped: " << b.refusal;
      break;
    case grasp::BatchOutcome::kCannotStart:
      out << "cannot start: " << b.refusal;
      break;
  }
  const grasp::PartTime total = b.result.cost.total();
  out << "; " << total.cpu_s << " s CPU\n";
  return out.str();
}

// --placements N: the batch (grasp/object_batch.h), one line per placement as it ends, then the
// summary.
void run_batch(const GraspCliOptions& options, const CLI::App& app, grasp::GraspOptions grasp,
               int* exit_code) {
  grasp::BatchPlacementOptions draw;
  draw.count = options.placements;
  draw.seed = options.seed;
  draw.max_offset = options.max_offset;
  if (app.count("--up") > 0) draw.ups = {options.placement.up};
  if (app.count("--yaw") > 0) draw.yaw_degrees = options.placement.yaw;
  grasp::ObjectBatchOptions batch_options;
  batch_options.run = object_run_options(options);
  grasp::ObjectPlacement base = object_placement(options.placement, options.object);
  std::vector<grasp::ObjectPlacement> placements;
  try {
    placements = grasp::draw_placements(base, draw);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("grasp: ") + e.what());
  }
  batch_options.first = placements.front();
  batch_options.decomposed = options.decomposed;
  // --judge: a judge per grasp, built on its first closing step.
  std::unique_ptr<study::ContactJudge> judge;
  std::string config_path = options.config;
  if (options.judge) {
    grasp.on_grasp_step = [&judge, &config_path](const mjModel* m, const mjData* d, int step) {
      if (!judge) judge = make_judge(m, config_path);
      judge->judge_step(m, d, step);
    };
  }
  batch_options.grasp = grasp;
  std::optional<grasp::ObjectBatch> batch;
  try {
    batch.emplace(batch_options);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("grasp: ") + e.what());
  }
  if (config_path.empty()) config_path = mujoco::pair_config_path(batch->description().scene.scene);
  int counts[3] = {0, 0, 0};
  int held = 0;
  grasp::GraspCost total;
  for (std::size_t k = 0; k < placements.size(); ++k) {
    judge.reset();
    grasp::BatchGrasp b = batch->grasp(placements[k]);
    ++counts[static_cast<int>(b.outcome)];
    if (b.outcome == grasp::BatchOutcome::kGrasped && b.result.held) ++held;
    grasp::CostTimer write(&b.result.cost, grasp::CostPart::kWrite);
    const int index = static_cast<int>(k);
    if (options.json) {
      nlohmann::json line = batch_line(b, index, *batch, options, judge.get());
      write.stop();
      line["cost"] = grasp::cost_json(b.result.cost);
      std::cout << line.dump() << std::endl;
    } else {
      const std::string text = batch_text(b, index);
      write.stop();
      std::cout << text << std::flush;
    }
    total += b.result.cost;
  }
  const int grasped = counts[static_cast<int>(grasp::BatchOutcome::kGrasped)];
  const int skipped = counts[static_cast<int>(grasp::BatchOutcome::kSkipped)];
  const int cannot = counts[static_cast<int>(grasp::BatchOutcome::kCannotStart)];
  if (options.json) {
    nlohmann::json summary = {{"outcome", "summary"},
                              {"object", options.object},
                              {"hand", batch->description().hand},
                              {"seed", options.seed},
                              {"placements", options.placements},
                              {"grasped", grasped},
                              {"skipped", skipped},
                              {"cannot_start", cannot},
                              {"held", held},
                              {"cost", grasp::cost_json(total)}};
    add_envelope(summary);
    std::cout << summary.dump() << std::endl;
  } else {
    std::cout << "# batch of " << options.placements << " placements (seed " << options.seed
              << "): " << grasped << " grasped, " << skipped << " skipped, " << cannot
              << " cannot start, " << held << " held\n"
              << grasp::cost_text(total);
  }
  if (options.require_held && held < grasped) *exit_code = 1;
}

void run_grasp_command(GraspCliOptions& options, const CLI::App& app, int* exit_code) {
  finish_method_options(options.method);
  check_usage(options, app);
  grasp::GraspOptions grasp = grasp_options(options, app);
  if (app.count("--placements") > 0) {
    run_batch(options, app, grasp, exit_code);
    return;
  }
  std::optional<grasp::ObjectRun> object;
  if (!options.object.empty()) {
    write_object(options, object.emplace(object_run_options(options)));
    // A large object: the wait is announced before it starts (nothing is printed during it).
    if (const std::string notice = object->wait_notice(); !notice.empty()) {
      std::cerr << "[grasp] " << notice << std::endl;
    }
  }
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
  // The output's own building is the cost's "write" part, measured up to the cost itself.
  grasp::CostTimer write(&result.cost, grasp::CostPart::kWrite);
  if (options.json) {
    nlohmann::json doc = grasp::grasp_json(result, ran, pieces, options.decomposed);
    if (judge) doc["judge"] = study::contact_judge_json(judge->summary());
    write.stop();
    doc["cost"] = grasp::cost_json(result.cost);
    add_envelope(doc);
    std::cout << doc.dump(2) << '\n';
  } else {
    std::ostringstream text;
    text << grasp::grasp_text(result, ran, pieces, options.quiet);
    if (judge) {
      const study::ContactJudgeSummary j = judge->summary();
      text << "# judged by CGAL over " << j.steps << " closing steps: " << j.contacts
           << " hand-object contacts, " << j.phantom << " phantom, " << j.missed << " missed\n";
    }
    write.stop();
    std::cout << text.str() << grasp::cost_text(result.cost);
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
        "2F-85), shadow (the Shadow hand), allegro (the Allegro hand), or a template scene "
        "file; with --drive, a hand file"},
       {Placement::kUp, "--object: the file axis that points up: x, y, z, -x, -y, -z"},
       {Placement::kYaw, "--object: then a turn about the up direction, degrees"},
       {Placement::kOffset,
        "--object: then moved across gravity from the hand's centre by DX DY m (along the "
        "world x axis made perpendicular to up, and up x that)"},
       {Placement::kPose,
        "--object: the object's rotation as a quaternion W X Y Z (instead of --up, --yaw)"},
       {Placement::kWriteScene,
        "--object: write the scene (FILE's stem .xml and .pairs.json) into this folder and keep "
        "it (default: a temporary folder, removed)"}});
  app->add_option("--drive", options->drive,
                  "--object: --hand is a hand file (a Menagerie-style MJCF of the hand alone), "
                  "this its drive (JSON: the \"grasp\" section of a pair config and a \"mount\" "
                  "saying where the object goes; docs/hands.md): graspcd writes the scene around "
                  "the hand, unchanged");
  app->add_flag("--force", options->force,
                "--write-scene: replace files in DIR that graspcd did not write (never the "
                "template or the object the run reads)");
  app->add_option(
         "--load-timeout", options->load_timeout,
         "--object: the most seconds before the first grasp step (MuJoCo compiling the "
         "object's mesh, graspcd's trees, the start check); past it the run stops, exit "
         "code 2. A mesh of 100,000 triangles or more is announced before the wait: MuJoCo "
         "takes about 20 s of CPU to compile one of 200,000")
      ->check(positive_number())
      ->capture_default_str();
  app->add_option("--placements", options->placements,
                  "--object: a batch of N grasps, each a placement drawn from --seed (the up axis "
                  "among the six unless --up, the yaw in [0, 360) unless --yaw, an offset within "
                  "--max-offset): the scene compiled once, one line per placement (JSON Lines "
                  "with --json), then a summary")
      ->check(integer_in_range(1, 1000000));
  app->add_option("--seed", options->seed, "--placements: the seed of the placements")
      ->transform(decimal_integer(0, std::numeric_limits<std::uint64_t>::max()))
      ->capture_default_str();
  app->add_option("--max-offset", options->max_offset,
                  "--placements: the largest offset across gravity from the hand's centre, m")
      ->check(number_in_range(0.0, kMaxOffset))
      ->capture_default_str();
  app->add_flag("--require-held", options->require_held,
                "Exit with code 1 when the object was not held (--placements: when any grasp "
                "that ran was not)");
  add_method_options(*app, options->method, MethodDefaults::kSceneConfig);
  app->add_flag("--native", options->native,
                "MuJoCo's own collision (convex hulls) instead of graspcd's callback");
  app->add_option("--decomposed", options->decomposed,
                  "A folder written by graspcd decompose: the object collides as its convex "
                  "pieces, under MuJoCo's native collision (implies --native)");
  app->add_flag("--judge", options->judge,
                "Judge every closing step's hand-object contacts against the true meshes (CGAL)");
  app->add_flag("--json", options->json, "Print one JSON document instead of text");
  app->add_option("--write-run", options->write_run,
                  "Write the run record to FILE: the header, the start state and one JSON line "
                  "per physics step with the contacts, for graspcd judge (docs/run-record.md); "
                  "written whole at the end, also when the start is refused");
  app->add_flag("--six-directions", options->six_directions,
                "After the hold, the six-direction test: six runs from the held state, the "
                "support taken away, gravity off, the object pulled by its weight along +-x, "
                "+-y, +-z of the hand for 1 s; each passes when the object still touches the "
                "hand and moved less than 1 cm ('# six directions: held in N of 6')");
  app->add_flag("--quiet", options->quiet,
                "Text without the per-step lines: the object line (--object) and the '#' summary "
                "lines (no effect with --json)");
  app->add_option("--config", options->config,
                  "Pair config (JSON); default SCENE.pairs.json beside the scene");
  app->add_option("--noslip", options->noslip,
                  "MuJoCo's noslip solver iterations (mjOption.noslip_iterations, 0: off) for "
                  "every configuration (default: the scene's, MuJoCo's 0)")
      ->transform(integer_in_range(0, 1000));
  app->add_flag("--multiccd", options->multiccd,
                "MuJoCo's multi-point convex collision (mjENBL_MULTICCD) for what MuJoCo "
                "collides itself: --native's hulls, --decomposed's pieces, the pairs graspcd "
                "does not serve (--multiccd=false: off; default: the scene's flag, MuJoCo's off)");
  app->add_option("--timestep-divisor", options->timestep_divisor,
                  "The scene's time step divided by K, with K times the physics steps per grasp "
                  "step, so that the drive is the same in time (a finer run of the same grasp; "
                  "JSON timestep and physics_steps_per_grasp_step record what ran)")
      ->transform(integer_in_range(1, 64))
      ->capture_default_str();
  app->add_option("--max-steps", options->max_steps, "Most closing grasp steps")
      ->transform(positive_integer())
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
