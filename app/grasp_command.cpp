// graspcd grasp SCENE.xml [--method M] [--cap N] [--switch N] [--native] [--json]
// [--config PAIRS.json] [--max-steps N] [--quiet]: runs the grasp of paper section 9
// (grasp/grasp.h) and prints, per grasp step, contacts and detection time, then a summary. graspcd
// grasp --object FILE [--scale S] [--write-scene DIR]: the same with a user's mesh in the
// template scene (example 1's arm and hand, the cup swapped for FILE). graspcd grasp SCENE
// --decomposed DIR: the object collides as its convex pieces (natively).

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "command.h"
#include "graspcd/core/geometry.h"
#include "graspcd/core/warnings.h"
#include "graspcd/grasp/decomposed_scene.h"
#include "graspcd/grasp/drive_config.h"
#include "graspcd/grasp/grasp.h"
#include "graspcd/grasp/object_scene.h"
#include "graspcd/io/mesh_io.h"
#include "graspcd/io/output_files.h"
#include "graspcd/io/text_input.h"
#include "graspcd/mujoco/mujoco_messages.h"
#include "graspcd/mujoco/registry.h"
#include "graspcd/study/contact_judge.h"
#include "graspcd/version/envelope.h"
#include "hand_template.h"
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
};

namespace fs = std::filesystem;

struct ObjectRun {
  std::string file;  // the user's mesh, as given
  std::string hand;
  grasp::ObjectScene scene;
  bool kept = false;  // --write-scene: scene names the kept file (else a removed temporary one)
};

// --write-scene DIR: the files the run leaves, DIR/STEM.xml, DIR/STEM.pairs.json and the folder
// DIR/STEM.meshes. The scene is written and simulated in a private folder DIR/.graspcd-STEM-XXXXXX
// (another run writing the same stem into DIR simulates its own), and its files are renamed into
// place at the end, DIR locked (flock) meanwhile; the private folder is removed on errors and on
// INT, TERM and HUP (io/output_files.h).
struct SceneTargets {
  fs::path dir;
  std::string stem;
  fs::path scene() const { return dir / (stem + ".xml"); }
  fs::path pairs() const { return dir / (stem + ".pairs.json"); }
  fs::path meshes() const { return dir / (stem + ".meshes"); }
};

// Whether `scene` is a scene graspcd generated: its header carries grasp::kGeneratedMarker.
bool generated_by_graspcd(const fs::path& scene) {
  std::ifstream in(scene, std::ios::binary);
  std::string head(4096, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return head.find(grasp::kGeneratedMarker) != std::string::npos;
}

bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  return fs::exists(a, ec) && fs::exists(b, ec) && fs::equivalent(a, b, ec);
}

// Before the work: the run never replaces a file it reads (the template, its pair config, the
// object's mesh), and, without --force, none that graspcd did not write (a STEM.xml without the
// marker, and the STEM.pairs.json and STEM.meshes beside it). One line 'FILE: message', exit 2.
void check_scene_targets(const SceneTargets& t, const std::string& template_scene,
                         const std::string& object_file, bool force) {
  const fs::path template_pairs = fs::path(template_scene).replace_extension(".pairs.json");
  std::error_code ec;
  const bool ours = generated_by_graspcd(t.scene());
  for (const fs::path& target : {t.scene(), t.pairs(), t.meshes()}) {
    if (same_file(target, template_scene) || same_file(target, template_pairs)) {
      throw io::InputError(target.string(), 0,
                           "is the template this run reads: not overwritten (write the scene "
                           "into another folder)");
    }
    const fs::path object = fs::absolute(object_file).lexically_normal();
    const fs::path folder = fs::absolute(target).lexically_normal();
    if (same_file(target, object_file) || object.string().rfind(folder.string() + "/", 0) == 0) {
      throw io::InputError(target.string(), 0,
                           "holds the object this run reads: not overwritten (write the scene "
                           "into another folder)");
    }
    if (!force && fs::exists(fs::symlink_status(target, ec)) && !ours) {
      throw io::InputError(
          target.string(), 0,
          "exists and graspcd did not write it (no '" + std::string(grasp::kGeneratedMarker) +
              "' in " + t.scene().filename().string() + "): not overwritten; --force replaces it");
    }
  }
}

// The written files renamed from the private folder `work` into place, replacing graspcd's
// earlier ones (moved into `work`, removed with it); DIR is locked meanwhile so that two runs
// ending together leave one run's files, not a mix. Throws InputError naming the file.
void keep_scene(const SceneTargets& t, const fs::path& work) {
  const int lock = ::open(t.dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (lock >= 0) ::flock(lock, LOCK_EX);
  const auto move = [&](const std::string& name, const std::string& old) {
    const fs::path target = t.dir / name;
    std::error_code ec;
    if (fs::exists(fs::symlink_status(target, ec))) fs::rename(target, work / old, ec);
    fs::rename(work / name, target, ec);
    if (ec) {
      if (lock >= 0) ::close(lock);
      throw io::InputError(target.string(), 0, "cannot write: " + ec.message());
    }
  };
  move(t.meshes().filename().string(), "replaced.meshes");
  move(t.pairs().filename().string(), "replaced.pairs.json");
  move(t.scene().filename().string(), "replaced.xml");
  if (lock >= 0) ::close(lock);
}

std::string segments_text(const grasp::GraspResult& g, const grasp::GraspStepRecord& r) {
  std::string out;
  for (std::size_t s = 0; s < r.touching.size(); ++s) {
    if (!r.touching[s]) continue;
    if (!out.empty()) out += ',';
    out += g.segments[s];
  }
  return out.empty() ? "-" : out;
}

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

// "# object FILE at scale S (given|fitted) ... in the HAND template": the first line of the text.
std::string object_line(const ObjectRun& o) {
  std::ostringstream out;
  out << "# object " << o.file << " at scale " << std::setprecision(6) << o.scene.scale
      << (o.scene.fitted ? " (fitted)" : " (given)") << ", " << std::setprecision(3)
      << o.scene.size[0] << " x " << o.scene.size[1] << " x " << o.scene.size[2] << " m, in the "
      << o.hand << " template";
  return out.str();
}

// The true meshes' penetration (true_penetration.h) as a phrase of the verdict line: "true
// meshes: deepest penetration 0.412 mm (geom 'left_pad', hand, grasp step 57, t = 0.570 s, in the
// closing), hand 0.412 mm, support 0.101 mm, over 640 grasp steps; partial: ...; not measured:
// ...".
std::string true_penetration_text(const grasp::TruePenetration& p) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(3) << "true meshes: deepest penetration " << p.max * 1e3
      << " mm";
  if (p.step > 0) {
    out << " (" << p.geom << ", " << p.side << ", grasp step " << p.step << ", t = " << p.time
        << " s, in " << p.phase << ")";
  }
  out << ", hand " << p.hand_max * 1e3 << " mm, support " << p.support_max * 1e3 << " mm, over "
      << p.measures << " grasp steps (" << p.pairs << " geom pairs)";
  for (const std::string& line : p.partial) out << "; partial: " << line;
  for (const std::string& line : p.unmeasured) out << "; not measured: " << line;
  return out.str();
}

// quiet: without the per-step table (its header line and one line per grasp step).
void print_text(const grasp::GraspResult& r, const std::optional<ObjectRun>& object,
                const std::optional<grasp::DecomposedScene>& decomposed,
                const std::optional<study::ContactJudgeSummary>& judged, bool quiet) {
  std::ostringstream out;
  if (object) out << object_line(*object) << '\n';
  out << std::fixed;
  if (!quiet) {
    out << "step contacts detection_ns box_tests triangle_tests object_z segments\n";
    for (const grasp::GraspStepRecord& s : r.steps) {
      out << s.step << ' ' << s.contacts << ' ' << s.detection_ns << ' ' << s.box_tests << ' '
          << s.triangle_tests << ' ' << std::setprecision(6) << s.object_z << ' '
          << segments_text(r, s) << '\n';
    }
  }
  out << "# method " << r.method << "; first contact (grasp step):";
  for (std::size_t s = 0; s < r.first_contact.size(); ++s) {
    out << ' ' << r.segments[s] << '=';
    if (r.first_contact[s] > 0) {
      out << r.first_contact[s];
    } else {
      out << '-';
    }
  }
  out << '\n';
  out << std::setprecision(4) << "# gripped " << (r.gripped ? "yes" : "no") << "; held "
      << (r.held ? "yes" : "no") << (grasp::push_note(r).empty() ? "" : ", " + grasp::push_note(r))
      << (grasp::tilt_note(r).empty() ? "" : ", " + grasp::tilt_note(r))
      << (r.reason.empty() ? "" : ": " + r.reason) << "; object z (origin) " << r.object_z_initial
      << " -> " << r.object_z_gripped << " (before the lift) -> " << r.object_z_final
      << " m (final), rose " << r.object_rise << " m of the hand's " << r.hand_travel
      << " m, lowest " << r.hold_min_z << " m and drift " << r.hold_drift
      << " m in the hold; grip point rose " << r.grip_rise << " m; tilt " << r.tilt_final_deg
      << " deg final, " << r.tilt_deg << " deg largest; fastest " << r.max_speed
      << " m/s, kinetic energy at most " << std::setprecision(6) << r.kinetic_energy_max << " J; "
      << true_penetration_text(r.true_penetration) << '\n';
  out << "# detection ns " << r.detection_ns_close << " closing, " << r.detection_ns_total
      << " total; " << r.physics_steps << " physics steps, " << std::setprecision(2) << r.sim_time
      << " s simulated, " << std::setprecision(4) << r.step_wall_ms << " ms per physics step; "
      << r.contained_calls << " containment findings; " << r.nonfinite_skips
      << " non-finite skips; " << r.reused_calls << " reused; noslip " << r.noslip_iterations
      << " iterations; multiccd " << (r.multiccd ? "on" : "off") << '\n';
  if (decomposed) {
    out << "# decomposed: " << decomposed->replaced_geoms << " geom(s) of " << decomposed->source
        << " collide as " << decomposed->pieces << " convex pieces each (native)\n";
  }
  if (judged) {
    out << "# judged by CGAL over " << judged->steps << " closing steps: " << judged->contacts
        << " hand-object contacts, " << judged->phantom << " phantom, " << judged->missed
        << " missed\n";
  }
  std::cout << out.str();
}

void print_json(const grasp::GraspResult& r, const std::optional<ObjectRun>& object,
                const std::optional<grasp::DecomposedScene>& decomposed, const std::string& dir,
                const std::optional<study::ContactJudgeSummary>& judged) {
  nlohmann::json steps = nlohmann::json::array();
  for (const grasp::GraspStepRecord& s : r.steps) {
    nlohmann::json segments = nlohmann::json::array();
    for (std::size_t i = 0; i < s.touching.size(); ++i) {
      if (s.touching[i]) segments.push_back(r.segments[i]);
    }
    steps.push_back({{"step", s.step},
                     {"contacts", s.contacts},
                     {"detection_ns", s.detection_ns},
                     {"box_tests", s.box_tests},
                     {"front_skips", s.front_skips},
                     {"triangle_tests", s.triangle_tests},
                     {"served_calls", s.served_calls},
                     {"contained", s.contained},
                     {"nonfinite_skips", s.nonfinite_skips},
                     {"object_z", s.object_z},
                     {"segments", segments}});
  }
  nlohmann::json first = nlohmann::json::object();
  for (std::size_t i = 0; i < r.first_contact.size(); ++i) {
    const std::string& name = r.segments[i];
    if (r.first_contact[i] > 0) {
      first[name] = r.first_contact[i];
    } else {
      first[name] = nullptr;
    }
  }
  nlohmann::json doc = {
      {"scene", r.scene},
      {"method", r.method},
      {"native", r.native},
      {"steps", steps},
      {"first_contact", first},
      {"gripped", r.gripped},
      {"held", r.held},
      {"reason", r.reason.empty() ? nlohmann::json() : nlohmann::json(r.reason)},
      {"object_rise", r.object_rise},
      {"hand_travel", r.hand_travel},
      {"slip_time", r.slip_time >= 0 ? nlohmann::json(r.slip_time) : nlohmann::json()},
      {"pushed", r.squeeze_push},
      {"pushed_during_squeeze", r.pushed_during_squeeze},
      {"dropped_at", r.dropped_at ? nlohmann::json(*r.dropped_at) : nlohmann::json()},
      {"object_z_initial", r.object_z_initial},
      {"object_z_gripped", r.object_z_gripped},
      {"object_z_final", r.object_z_final},
      {"hold_min_z", r.hold_min_z},
      {"hold_drift", r.hold_drift},
      {"grip_rise", r.grip_rise},
      {"tilt_deg", r.tilt_deg},
      {"tilt_final_deg", r.tilt_final_deg},
      {"max_speed", r.max_speed},
      {"kinetic_energy_max", r.kinetic_energy_max},
      {"true_penetration_max", r.true_penetration.max},
      {"true_penetration_step",
       r.true_penetration.step > 0 ? nlohmann::json(r.true_penetration.step) : nlohmann::json()},
      {"true_penetration",
       {{"max", r.true_penetration.max},
        {"step",
         r.true_penetration.step > 0 ? nlohmann::json(r.true_penetration.step) : nlohmann::json()},
        {"time",
         r.true_penetration.step > 0 ? nlohmann::json(r.true_penetration.time) : nlohmann::json()},
        {"phase",
         r.true_penetration.step > 0 ? nlohmann::json(r.true_penetration.phase) : nlohmann::json()},
        {"geom",
         r.true_penetration.step > 0 ? nlohmann::json(r.true_penetration.geom) : nlohmann::json()},
        {"side",
         r.true_penetration.step > 0 ? nlohmann::json(r.true_penetration.side) : nlohmann::json()},
        {"hand_max", r.true_penetration.hand_max},
        {"support_max", r.true_penetration.support_max},
        {"measures", r.true_penetration.measures},
        {"pairs", r.true_penetration.pairs},
        {"probe_spacing", grasp::kTrueProbeSpacing},
        {"partial", r.true_penetration.partial},
        {"unmeasured", r.true_penetration.unmeasured}}},
      {"noslip_iterations", r.noslip_iterations},
      {"multiccd", r.multiccd},
      {"ejected", r.ejected ? nlohmann::json{{"t", r.ejected->time},
                                             {"speed", r.ejected->speed},
                                             {"cause", r.ejected->cause}}
                            : nlohmann::json()},
      {"detection_ns_close", r.detection_ns_close},
      {"detection_ns_total", r.detection_ns_total},
      {"physics_steps", r.physics_steps},
      {"sim_time", r.sim_time},
      {"ms_per_physics_step", r.step_wall_ms},
      {"max_contacts", r.max_contacts},
      {"mean_contacts", r.mean_contacts},
      {"max_pair_contacts", r.max_pair_contacts},
      {"rest",
       {{"max_speed", r.rest_max_speed},
        {"max_penetration", r.rest_max_penetration},
        {"energy_early", r.rest_energy_early},
        {"energy_late", r.rest_energy_late}}},
      {"contact_buffer_full", r.contact_buffer_full},
      {"constraint_buffer_full", r.constraint_buffer_full},
      {"contained_calls", r.contained_calls},
      {"nonfinite_skips", r.nonfinite_skips},
      {"reused_calls", r.reused_calls}};
  if (object) {
    const grasp::ObjectScene& o = object->scene;
    doc["object"] = {{"file", object->file},
                     {"hand", object->hand},
                     {"scale", o.scale},
                     {"fitted", o.fitted},
                     {"size", o.size},
                     {"pos", o.pos},
                     {"quat", o.quat},
                     {"scene", object->kept ? nlohmann::json(o.scene) : nlohmann::json()}};
  }
  if (decomposed) {
    doc["decomposed"] = {{"dir", dir},
                         {"source", decomposed->source},
                         {"pieces", decomposed->pieces},
                         {"geoms", decomposed->replaced_geoms}};
  }
  if (judged) doc["judge"] = judge_json(*judged);
  add_envelope(doc);
  std::cout << doc.dump(2) << '\n';
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

void run_grasp_command(GraspCliOptions& options, const CLI::App& app, int* exit_code) {
  finish_method_options(options.method);
  check_usage(options, app);
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
  grasp.true_penetration = true;  // every run of the command measures it
  if (app.count("--method") > 0) grasp.method = options.method.method;
  if (app.count("--cap") > 0) grasp.cap = options.method.cap;
  if (app.count("--switch") > 0) grasp.switch_passes = options.method.switch_passes;
  std::optional<grasp::TempFolder> temp;
  std::optional<ObjectRun> object;
  std::string scene = options.scene;
  // --decomposed: the scene with the object's pieces, beside SCENE (removed on return), run
  // natively; the pair config (the drive section of a real hand) stays SCENE's
  // (grasp::run_decomposed_grasp).
  std::optional<grasp::DecomposedScene> decomposed;
  if (!options.decomposed.empty()) decomposed.emplace();
  std::optional<SceneTargets> targets;
  std::optional<io::RemoveIfEmpty> created;  // --write-scene: DIR, when this run created it
  io::CleanupGuard work;  // --write-scene: the private folder the scene is written in
  // Temporary names -> the user's, for the messages and warnings.
  std::vector<std::pair<std::string, std::string>> renames;
  if (!options.object.empty()) {
    const PlacementOptions& p = options.placement;
    const HandTemplate hand = hand_template(p.hand, "grasp");
    const std::string template_pairs =
        fs::path(hand.scene).replace_extension(".pairs.json").string();
    const std::string stem = fs::path(options.object).stem().string();
    fs::path folder;
    if (p.write_scene.empty()) {
      temp.emplace();
      folder = temp->path();
    } else {
      // Checked before the work: a folder that cannot be written, a file the run reads or one
      // graspcd did not write.
      if (io::prepare_output_folder(p.write_scene)) created.emplace(p.write_scene);
      targets = SceneTargets{p.write_scene, stem};
      check_scene_targets(*targets, hand.scene, options.object, options.force);
      work = io::make_private_folder(p.write_scene, ".graspcd-" + stem, p.write_scene);
      folder = work.path();
    }
    const std::string written = (folder / (stem + ".pairs.json")).string();
    renames = {{written, template_pairs}, {(folder / (stem + ".xml")).string(), options.object}};
    object = ObjectRun{options.object, p.hand, {}};
    try {
      object->scene = grasp::write_object_scene(object_placement(p, options.object), hand.scene,
                                                p.hand, folder.string(), hand.fit, hand.moved);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("grasp: ") + e.what());
    }
    scene = object->scene.scene;
  }
  // Errors name the user's file, never the temporary scene (removed when this returns).
  const auto named = [&](const std::string& file) {
    for (const auto& [from, to] : renames) {
      if (file == from) return to;
    }
    return file;
  };
  // --judge: built on the first closing step's model, with the object and support bodies of the
  // drive config the grasp reads (--config, else SCENE.pairs.json: for --decomposed the original
  // scene's, for --object the written template's); the grasp has already checked that config.
  std::unique_ptr<study::ContactJudge> judge;
  if (options.judge) {
    const std::string config_path =
        options.config.empty() ? mujoco::pair_config_path(scene) : options.config;
    grasp.on_grasp_step = [&judge, config_path](const mjModel* m, const mjData* d, int step) {
      if (!judge) judge = make_judge(m, config_path);
      judge->judge_step(m, d, step);
    };
  }
  // --write-scene: the written scene is kept whatever the grasp's outcome (a refused start
  // state too: the user edits the scene), but not when the run is interrupted.
  const auto keep_written = [&] {
    if (!targets || object->kept) return;
    keep_scene(*targets, work.path());
    object->kept = true;
    object->scene.scene = targets->scene().string();
    object->scene.pairs = targets->pairs().string();
    object->scene.meshes = targets->meshes().string();
  };
  grasp::GraspResult result;
  try {
    result = decomposed ? grasp::run_decomposed_grasp(options.scene, options.decomposed, grasp,
                                                      &*decomposed)
                        : grasp::run_grasp(scene, grasp);
  } catch (const grasp::GraspInputError& e) {
    // A refused object that is far too large says what its units likely are, on the same line.
    const std::string hint =
        object && !object->scene.units_hint.empty() ? "; " + object->scene.units_hint : "";
    const bool in_scene = object && e.file() == object->scene.scene;
    keep_written();
    if (in_scene) {
      throw io::InputError(options.object, 0, "in the template scene: " + e.message() + hint);
    }
    throw io::InputError(named(e.file()), e.line(), e.message() + hint);
  } catch (const mujoco::MujocoError& e) {
    const std::string hint =
        object && !object->scene.units_hint.empty() ? "; " + object->scene.units_hint : "";
    keep_written();
    throw io::InputError(named(scene), 0, e.what() + hint);
  }
  if (object) {
    keep_written();
    result.scene = targets ? object->scene.scene : options.object;
    // The warnings name the kept files, or the user's object and the template's pair config.
    if (targets) renames = {{work.path().string(), targets->dir.string()}};
    name_user_files(renames, options.placement.hand);
  }
  std::optional<study::ContactJudgeSummary> judged;
  if (judge) judged = judge->summary();
  if (options.json) {
    print_json(result, object, decomposed, options.decomposed, judged);
  } else {
    print_text(result, object, decomposed, judged, options.quiet);
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
  app->footer(wrap_help(
      "The fingers close in grasp steps of 0.003 rad (5 physics steps each, computed-torque "
      "control of every joint); a finger segment stops at its first contact with the object "
      "(graspcd's detector for the registered pairs, or MuJoCo's with --native). When every "
      "finger touches (or after --max-steps), the hand squeezes, the arm lifts the wrist by 6 cm "
      "over 1 s and holds for 2 s. --method, --cap and --switch override the config's.\n"
      "Text output: a header line 'step contacts detection_ns box_tests triangle_tests object_z "
      "segments', then one line per grasp step: its number, the finger-object contacts after "
      "it, the tree query time in ns summed over its physics steps and all registered pairs "
      "(0 with --native), the box and triangle tests, object_z (the height in m of the object "
      "body's origin: with --object the point (0, 0, 0) of FILE as placed, not its lowest point "
      "nor its centre of mass), and the "
      "segments in contact (comma-separated, '-' for none); --quiet leaves out the header and "
      "these lines. Then three summary lines starting with '#': the first-contact grasp step of "
      "each segment ('-' for never); 'gripped yes|no; "
      "held yes[, tilted N°]|no[: REASON]' (REASON 'ejected at t = T s (S m/s)' for an object "
      "thrown out, grasp/grasp.h) with 'object z (origin)': the heights of the object body's "
      "origin (as object_z) at the start, before the lift and at the end, its rise and the hand's "
      "travel, its grip point's rise, its tilt since the lift (final and largest), its top speed, "
      "its largest kinetic energy and the true meshes' penetration ('true meshes: deepest "
      "penetration D mm (GEOM, hand|support, grasp step S, t = T s, in PHASE), hand H mm, support "
      "S mm, over M grasp steps (P geom pairs)', then '; partial: ...' and '; not measured: ...' "
      "for open meshes, see below); the "
      "detection time of the closing steps and of the whole "
      "run, the physics steps, simulated seconds and wall ms per physics step, the "
      "containment findings (served calls whose surfaces did not meet but a segment lay wholly "
      "inside the closed object: a contact the surface test cannot see), and the non-finite "
      "skips (served calls whose geom placement held NaN, inf or a number beyond 1e10: no "
      "contacts, no query), the reused calls (answered by a pair's kept contacts, "
      "--contact-reuse), and MuJoCo's noslip iterations.\n"
      "--json: one document with the same: scene, method, native, steps (step, contacts, "
      "detection_ns, box_tests, front_skips (front node pairs, or leaf pairs whose triangles "
      "were apart, still apart by their last gap, kept without a box or triangle test), "
      "triangle_tests, served_calls, contained, nonfinite_skips, "
      "object_z, segments), first_contact (segment -> step or null), gripped, held, reason "
      "(null when held), object_rise and hand_travel (m, from the start of the lift to the end "
      "of the hold), slip_time (s, or null), pushed (m, the object's largest move over the "
      "squeeze and settling) and pushed_during_squeeze (more than 1 cm), dropped_at (s, or "
      "null), "
      "object_z_initial, object_z_gripped, object_z_final (the object body's origin, as object_z), "
      "hold_min_z, hold_drift, grip_rise "
      "(m, the rise of the object's grip point), tilt_deg and tilt_final_deg (the object's "
      "rotation since the start of the lift: the largest and the final, degrees), max_speed "
      "(the object's top speed, m/s), kinetic_energy_max (the object's largest kinetic energy, "
      "J, every physics step), true_penetration_max (m) and true_penetration_step (its grasp "
      "step, or null when none was found) with true_penetration {max, step, time, phase, geom, "
      "side (hand or support), hand_max, support_max, measures (grasp steps measured), pairs, "
      "probe_spacing (m), partial, unmeasured} (see below), noslip_iterations, multiccd, "
      "ejected ({t, "
      "speed, cause}: when, how fast and why the "
      "object was seen thrown out, cause speed, below or away; null when not), "
      "detection_ns_close, detection_ns_total, physics_steps, sim_time, ms_per_physics_step, "
      "max_contacts, mean_contacts (finger-object contacts per physics step), max_pair_contacts "
      "(the most one geom pair had in a step), rest (the hold's last second: the object's "
      "max_speed in m/s, its deepest contact max_penetration in m, the kinetic energy of the "
      "window's halves energy_early and energy_late in J), contact_buffer_full and "
      "constraint_buffer_full (MuJoCo's counters: steps whose nconmax or njmax was reached), "
      "contained_calls, nonfinite_skips, reused_calls, warnings.\n"
      "Verdicts: before the grasp, the start state is checked: an object that penetrates the "
      "hand, a finger or its support by more than 0.5 mm, or lies wholly inside one (or one "
      "inside it), is bad input (one line 'SCENE: the start state is not valid: ...', exit code "
      "2). With --native and --decomposed the meshes are also checked as the convex hulls MuJoCo "
      "collides: a hull that holds another geom by more than 0.5 mm is refused as a limit of the "
      "hull (or the pieces), not of the scene ('SCENE: cannot start with --native: MuJoCo "
      "collides mesh 'M' as its convex hull, which geom 'G' lies D mm inside at the start (...)', "
      "exit code 2). Gripped: just before the lift, two hand geoms touch the object with opposing "
      "contact normals (negative dot product). Held: gripped, not ejected, the object's grip "
      "point (the mean of its contacts with the hand before the lift) rose at least 80% of the "
      "hand's travel, and the object moved less than 1 cm in the hand during the hold; a held "
      "object turned 2 degrees or more since the lift is 'held yes, tilted N°', one the squeeze "
      "moved more than 1 cm before the lift 'held yes, pushed N cm during the squeeze' (still "
      "held: --require-held passes). Dropped: gripped, then no hand contact for the rest of the "
      "run, and more than 1 cm below the hand's path at the end. Ejected: faster "
      "than 2 m/s, more than twice its reach below its start, or out of the scene. Otherwise "
      "REASON says why: 'ejected at t = T s (S m/s)', 'no segment reached the object', 'no two "
      "touching segments push from opposing sides', 'dropped at t = T s', 'slipped at t = T s', "
      "'its grip rose X cm "
      "of the hand's Y cm travel'. "
      "--require-held: exit code 1 when not held.\n"
      "True meshes' penetration: whatever geometry collides (graspcd's contacts, --native's "
      "hulls, --decomposed's pieces), after every 5th physics step of every phase (each grasp "
      "step, also in the squeeze, lift and hold) each object geom is measured against every "
      "geom the contype/conaffinity filter lets collide with it, on the true meshes (for "
      "--decomposed the object as it was): the deepest of each one's vertices and points "
      "along its edges (at most 1 mm apart) inside the other's closed solid, by the start "
      "check's exact inside test, both ways; against a plane, the object's depth below it. A "
      "geom is the support's when it belongs to the world body (a floor) or to the pair "
      "config's 'support' body, else the hand's. An open mesh has no inside: only the other "
      "side's inside is tested ('partial', one line per open geom); two open meshes, and "
      "height fields, are not measured ('unmeasured'). A vertex measure can underestimate a "
      "depth (two edges crossing), never invent one; an object thrown through its support "
      "shows as the support's depth. The time it takes is outside the physics steps' wall "
      "time.\n"
      "--noslip N: MuJoCo's noslip solver (mjOption.noslip_iterations: N iterations after the "
      "main solver that remove the contacts' slip) in every configuration; default the "
      "scene's (0, off); JSON noslip_iterations records what ran.\n"
      "--multiccd: MuJoCo's multi-point convex collision (mjOption.enableflags |= "
      "mjENBL_MULTICCD; MJCF <flag multiccd=\"enable\"/>) for the run. MuJoCo 2.2 applies it in "
      "its general convex routine: a pair of a mesh with a mesh, box, cylinder or capsule (and "
      "cylinder, capsule and box pairs that routine takes), not a sphere or ellipsoid; after "
      "the first contact it tilts the two geoms 1e-3 rad either way about the contact's two "
      "tangents and keeps each distinct contact found, at the first one's depth: up to 5 per "
      "pair instead of 1. Plane-mesh (a floor), box-box and capsule-box have routines of their "
      "own and do not change. It reaches --native's hulls, --decomposed's pieces and, in a "
      "served run, only the pairs graspcd does not serve (the object on its table); graspcd's "
      "contacts are its own. Without the flag the scene's MJCF decides (<flag "
      "multiccd=\"enable\"/>, MuJoCo's default off); --multiccd=false turns it off. JSON "
      "multiccd records what ran; the text's summary says 'multiccd on|off'.\n"
      "Warnings: the pair registry's findings that do not stop the grasp (a served geom with a "
      "margin, an open mesh inside which containment is not checked), one line 'warning: "
      "CONFIG: message' each on stderr, and in the JSON's warnings.\n"
      "Errors: a missing or unreadable scene or config, a bad MJCF (MuJoCo's message on one "
      "line, e.g. a mesh file it cannot find), a config that is bad or whose pattern matches no "
      "geom, print one line 'FILE: message' on stderr and exit with code 2. A simulation that "
      "goes non-finite (MuJoCo finds NaN or a number beyond 1e10 in qpos, qvel, qacc or ctrl and "
      "resets) stops the grasp with one line 'graspcd: error: SCENE: the simulation went "
      "non-finite ...' and exit code 2.\n"
      "--object FILE: a new object without writing a scene. The template (--hand) is a shipped "
      "scene with its object replaced by FILE: project (mjcf/example1.xml: the project's arm and "
      "4-finger hand), robotiq (mjcf/real_robotiq_mug.xml: the Robotiq 2F-85) or shadow "
      "(mjcf/real_shadow_glass.xml: the Shadow hand; the last two need ../shared/models), or "
      "any template scene file (docs/design.md, 'Object scenes'). FILE is an OBJ, STL (binary "
      "or ASCII), OFF, PLY, glTF 2.0/GLB or COLLADA file (docs/objects.md); one MuJoCo 2.2 "
      "cannot read is written into the scene's folder as STEM.converted.obj. FILE keeps its "
      "units (glTF and COLLADA are in metres; --scale S multiplies them: 0.001 for "
      "millimetres) unless --fit scales it to the "
      "template's room (project: 7 cm wide, 8 cm tall). The file's --up axis points against "
      "gravity, turned by --yaw degrees about it (or --pose W X Y Z); its lowest point along "
      "gravity is placed 0.5 mm above the template's support point, centred on it. Pairs and "
      "drive: the template's .pairs.json. The output names FILE as the scene; its first line is "
      "'# object FILE at scale S (fitted|given), W x D x H m, in the HAND template' (JSON: "
      "'object': file, hand, scale, fitted, size, pos, quat, scene: the kept scene, null without "
      "--write-scene). --write-scene DIR keeps the scene for graspcd validate or study: "
      "DIR/STEM.xml, DIR/STEM.pairs.json and DIR/STEM.meshes/ (FILE's copy, and links to the "
      "hand's meshes); FILE is named relative to DIR and the hand by absolute paths, so DIR can "
      "be moved or copied (cp -r) and loads while the hand stays installed. The scene is written "
      "and simulated in a private folder DIR/.graspcd-STEM-XXXXXX (two runs writing one stem "
      "into DIR each simulate their own object) and renamed into place at the end (kept when the "
      "start state is refused, so that it can be edited). Never replaced: the template and pair "
      "config the run reads, FILE itself; replaced only with --force: a STEM.xml without the "
      "marker line 'graspcd-generated: object scene' of graspcd's header, and a STEM.pairs.json "
      "or STEM.meshes not beside such a STEM.xml. A DIR under a file or read-only, a missing "
      "TMPDIR (without --write-scene), a bad FILE: one line 'FILE: message', exit code 2, before "
      "the grasp. INT, TERM and HUP remove the temporary and private folders and exit with code "
      "128 + the signal. Warnings name the user's files (the template's pair config for a "
      "temporary scene) and call a hand's mesh the hand's. An object more than 1 m across is the "
      "warning 'mesh_units', and a refusal of its scene says on its line what its units likely "
      "are ('...; the object is 60 m across at --scale 1: is the file in millimetres? try --scale "
      "0.001').\n"
      "--decomposed DIR: the route MuJoCo's documentation recommends for a non-convex object. "
      "DIR is a folder written by 'graspcd decompose MESH --out DIR'; every geom of SCENE whose "
      "mesh asset reads a file named as MESH keeps its mass but no longer collides, and one "
      "geom per convex piece (mass 0, the geom's other attributes, the asset's scale) collides "
      "in its place under MuJoCo's native collision. The scene is written beside SCENE under a "
      "hidden name and removed at the end; SCENE.pairs.json still drives the hand. A last line "
      "'# decomposed: G geom(s) of MESH collide as N convex pieces each (native)' (JSON: "
      "'decomposed': dir, source, pieces, geoms). A DIR without decomposition.json, or a SCENE "
      "without a mesh of MESH, is one line naming it, exit code 2.\n"
      "--judge: the race's contact fidelity. After each closing grasp step, every "
      "contact between the object and a hand geom is judged against the true meshes by CGAL "
      "(the object and a support it stands on are the pair config's 'grasp' section's "
      "'object' and 'support', else the body 'object' and none; a hand geom is every "
      "collidable geom outside the object, the support body and the world body, so the grasp's "
      "contacts are judged and the object's on a table are not): a phantom when its point lies "
      "more than 1 mm from the hand geom's surface or the object's true surface; and every hand "
      "geom whose true surface meets the object's (CGAL) without any contact with the object at "
      "that step is a missed contact. Primitive hand geoms are judged on graspcd's tessellation "
      "(a box exactly). The judging time is outside the physics steps' wall time. A last line "
      "'# judged by CGAL over S closing steps: C hand-object contacts, P phantom, M missed' "
      "(JSON: 'judge': steps, contacts, phantom, missed, phantom_by_geom and missed_by_geom "
      "(hand geom -> count), truth_hits, contact_error_per_step, cgal_first_contact (hand geom -> "
      "step), cgal_first_contact_body (hand body -> step), "
      "phantom_distance).\n"
      "Examples:\n"
      "  graspcd grasp mjcf/example1.xml --method perceptron\n"
      "  graspcd grasp --object my_mug.obj --scale 0.001 --write-scene /tmp/my_mug\n"
      "  graspcd grasp --object drill.obj --hand robotiq --up y --yaw 90 --require-held\n"
      "  graspcd decompose mjcf/meshes/cup.obj --out /tmp/cup8 --pieces 8\n"
      "  graspcd grasp mjcf/example1.xml --decomposed /tmp/cup8"));
  auto exit_code = std::make_shared<int>(0);
  return Command{app,
                 [options, app, exit_code] { run_grasp_command(*options, *app, exit_code.get()); },
                 exit_code};
}

}  // namespace graspcd::cli
