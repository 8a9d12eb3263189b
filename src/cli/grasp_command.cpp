// graspcd grasp SCENE.xml [--method M] [--cap N] [--switch N] [--native] [--json]
// [--config PAIRS.json] [--max-steps N]: runs the grasp of paper section 9 (bridge/grasp.h) and
// prints, per grasp step, contacts and detection time, then a summary.
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "bridge/grasp.h"
#include "cli/command.h"
#include "cli/method.h"
#include "io/text_input.h"

namespace graspcd::cli {

namespace {

struct GraspCliOptions {
  MethodOptions method;
  std::string scene;
  std::string config;
  bool native = false;
  bool json = false;
  int max_steps = 400;
};

std::string segments_text(const bridge::GraspResult& g, const bridge::GraspStepRecord& r) {
  std::string out;
  for (std::size_t s = 0; s < r.touching.size(); ++s) {
    if (!r.touching[s]) continue;
    if (!out.empty()) out += ',';
    out += g.segments[s];
  }
  return out.empty() ? "-" : out;
}

void print_text(const bridge::GraspResult& r) {
  std::ostringstream out;
  out << "step contacts detection_ns box_tests triangle_tests object_z segments\n";
  out << std::fixed;
  for (const bridge::GraspStepRecord& s : r.steps) {
    out << s.step << ' ' << s.contacts << ' ' << s.detection_ns << ' ' << s.box_tests << ' '
        << s.triangle_tests << ' ' << std::setprecision(6) << s.object_z << ' '
        << segments_text(r, s) << '\n';
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
      << (r.held ? "yes" : "no") << "; object z " << r.object_z_initial << " -> "
      << r.object_z_gripped << " (gripped) -> " << r.object_z_final << " m (final), lowest "
      << r.hold_min_z << " m and drift " << r.hold_drift << " m in the hold\n";
  out << "# detection ns " << r.detection_ns_close << " closing, " << r.detection_ns_total
      << " total; " << r.physics_steps << " physics steps, " << std::setprecision(2) << r.sim_time
      << " s simulated, " << std::setprecision(4) << r.step_wall_ms << " ms per physics step; "
      << r.contained_calls << " containment findings; " << r.nonfinite_skips
      << " non-finite skips\n";
  std::cout << out.str();
}

void print_json(const bridge::GraspResult& r) {
  nlohmann::json steps = nlohmann::json::array();
  for (const bridge::GraspStepRecord& s : r.steps) {
    nlohmann::json segments = nlohmann::json::array();
    for (std::size_t i = 0; i < s.touching.size(); ++i) {
      if (s.touching[i]) segments.push_back(r.segments[i]);
    }
    steps.push_back({{"step", s.step},
                     {"contacts", s.contacts},
                     {"detection_ns", s.detection_ns},
                     {"box_tests", s.box_tests},
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
  const nlohmann::json doc = {{"scene", r.scene},
                              {"method", r.method},
                              {"native", r.native},
                              {"steps", steps},
                              {"first_contact", first},
                              {"gripped", r.gripped},
                              {"held", r.held},
                              {"object_z_initial", r.object_z_initial},
                              {"object_z_gripped", r.object_z_gripped},
                              {"object_z_final", r.object_z_final},
                              {"hold_min_z", r.hold_min_z},
                              {"hold_drift", r.hold_drift},
                              {"detection_ns_close", r.detection_ns_close},
                              {"detection_ns_total", r.detection_ns_total},
                              {"physics_steps", r.physics_steps},
                              {"sim_time", r.sim_time},
                              {"ms_per_physics_step", r.step_wall_ms},
                              {"max_contacts", r.max_contacts},
                              {"contained_calls", r.contained_calls},
                              {"nonfinite_skips", r.nonfinite_skips},
                              {"warnings", r.warnings}};
  std::cout << doc.dump(2) << '\n';
}

void run_grasp_command(GraspCliOptions& options, const CLI::App& app) {
  finish_method_options(options.method);
  bridge::GraspOptions grasp;
  grasp.config_path = options.config;
  grasp.native = options.native;
  grasp.max_steps = options.max_steps;
  if (app.count("--method") > 0) grasp.method = options.method.method;
  if (app.count("--cap") > 0) grasp.cap = options.method.cap;
  if (app.count("--switch") > 0) grasp.switch_passes = options.method.switch_passes;
  bridge::GraspResult result;
  try {
    result = bridge::run_grasp(options.scene, grasp);
  } catch (const bridge::GraspInputError& e) {
    throw io::InputError(e.file(), 0, e.message());
  }
  // The registry's findings (e.g. an open mesh whose containment cannot be decided), one line
  // each on stderr before the answer.
  for (const std::string& warning : result.warnings) std::cerr << "warning: " << warning << '\n';
  if (options.json) {
    print_json(result);
  } else {
    print_text(result);
  }
}

}  // namespace

Command add_grasp_command(CLI::App& parent) {
  auto options = std::make_shared<GraspCliOptions>();
  CLI::App* app = parent.add_subcommand(
      "grasp", "Run a grasp (paper section 9): per grasp step, contacts and detection time");
  app->add_option("SCENE", options->scene, "The scene: an MJCF file of mjcf/")->required();
  add_method_options(*app, options->method);
  app->add_flag("--native", options->native,
                "MuJoCo's own collision (convex hulls) instead of graspcd's callback");
  app->add_flag("--json", options->json, "Print one JSON document instead of text");
  app->add_option("--config", options->config,
                  "Pair config (JSON); default SCENE.pairs.json beside the scene");
  app->add_option("--max-steps", options->max_steps, "Most closing grasp steps")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app->footer(wrap_help(
      "The fingers close in grasp steps of 0.003 rad (5 physics steps each, computed-torque "
      "control of every joint); a finger segment stops at its first contact with the object "
      "(graspcd's detector for the registered pairs, or MuJoCo's with --native). When every "
      "finger touches (or after --max-steps), the hand squeezes, the arm lifts the wrist by 6 cm "
      "over 1 s and holds for 2 s. --method, --cap and --switch override the config's.\n"
      "Text output: a header line 'step contacts detection_ns box_tests triangle_tests object_z "
      "segments', then one line per grasp step: its number, the finger-object contacts after "
      "it, the tree query time in ns summed over its physics steps and all registered pairs "
      "(0 with --native), the box and triangle tests, the object's height in m, and the "
      "segments in contact (comma-separated, '-' for none). Then three summary lines starting "
      "with '#': the first-contact grasp step of each segment ('-' for never); gripped and held "
      "(the object rose >= 3 cm and stayed within 1 cm of its place in the hand during the "
      "2 s hold) with its heights; the detection time of the closing steps and of the whole "
      "run, the physics steps, simulated seconds and wall ms per physics step, the "
      "containment findings (served calls whose surfaces did not meet but a segment lay wholly "
      "inside the closed object: a contact the surface test cannot see), and the non-finite "
      "skips (served calls whose geom placement held NaN, inf or a number beyond 1e10: no "
      "contacts, no query).\n"
      "--json: one document with the same: scene, method, native, steps (step, contacts, "
      "detection_ns, box_tests, triangle_tests, served_calls, contained, nonfinite_skips, "
      "object_z, segments), first_contact (segment -> step or null), gripped, held, "
      "object_z_initial, object_z_gripped, object_z_final, hold_min_z, hold_drift, "
      "detection_ns_close, detection_ns_total, physics_steps, sim_time, ms_per_physics_step, "
      "max_contacts, contained_calls, nonfinite_skips, warnings.\n"
      "Warnings: the pair registry's findings that do not stop the grasp (a served geom with a "
      "margin, an open mesh inside which containment is not checked), one line 'warning: "
      "CONFIG: message' each on stderr, and in the JSON's warnings.\n"
      "Errors: a missing or unreadable scene or config, a bad MJCF (MuJoCo's message on one "
      "line, e.g. a mesh file it cannot find), a config that is bad or whose pattern matches no "
      "geom, print one line 'FILE: message' on stderr and exit with code 2. A simulation that "
      "goes non-finite (MuJoCo finds NaN or a number beyond 1e10 in qpos, qvel, qacc or ctrl and "
      "resets) stops the grasp with one line 'graspcd: error: SCENE: the simulation went "
      "non-finite ...' and exit code 2.\n"
      "Example:\n"
      "  graspcd grasp mjcf/example1.xml --method perceptron"));
  return Command{app, [options, app] { run_grasp_command(*options, *app); }};
}

}  // namespace graspcd::cli
