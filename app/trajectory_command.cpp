// graspcd trajectory SCENE.xml --out FILE [--methods M,...] [--repeats N] [--max-steps N]: one
// grasp as a trajectory file for the viewer and the figures (src/graspcd/study/trajectory.h).
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "command.h"
#include "graspcd/grasp/grasp.h"
#include "graspcd/io/text_input.h"
#include "graspcd/mujoco/mujoco_messages.h"
#include "graspcd/study/trajectory.h"

namespace graspcd::cli {

namespace {

struct TrajectoryCliOptions {
  std::string scene;
  std::string out;
  std::vector<std::string> methods = {"sat", "sat-cached", "neurosat"};
  study::TrajectoryOptions options;
};

void run_trajectory_command(TrajectoryCliOptions& o) {
  o.options.methods.clear();
  for (const std::string& name : o.methods) {
    const auto m = parse_method(name);
    if (!m) throw UsageError("--methods: unknown method '" + name + "'");
    o.options.methods.push_back(*m);
  }
  try {
    study::export_grasp(o.scene, o.out, o.options);
  } catch (const grasp::GraspInputError& e) {
    throw io::InputError(e.file(), e.line(), e.message());
  } catch (const mujoco::MujocoError& e) {
    throw io::InputError(o.scene, 0, e.what());
  }
  std::cerr << "[trajectory] wrote " << o.out << std::endl;
}

}  // namespace

Command add_trajectory_command(CLI::App& parent) {
  auto o = std::make_shared<TrajectoryCliOptions>();
  CLI::App* app = parent.add_subcommand(
      "trajectory", "One grasp as a trajectory file for the viewer (report/viewer-src)");
  app->add_option("scene", o->scene, "The MJCF scene (with its SCENE.pairs.json)")->required();
  app->add_option("--out", o->out, "The trajectory file to write (JSON)")->required();
  app->add_option("--methods", o->methods, "Methods timed per grasp step")
      ->delimiter(',')
      ->capture_default_str();
  app->add_option("--repeats", o->options.repeats, "Timed replays per method (per-step medians)")
      ->check(positive_number())
      ->capture_default_str();
  app->add_option("--max-steps", o->options.max_steps, "Most closing grasp steps")
      ->check(positive_number())
      ->capture_default_str();
  app->footer(wrap_help(
      "Records the grasp of paper section 9 with graspcd's bridge (SAT), replays the recorded "
      "poses with each of --methods (all contacts, as Table 1) and writes one JSON file: the "
      "meshes once in their geom frames, per closing grasp step every geom's pose, our contacts "
      "and MuJoCo's native convex-hull contacts at the same joint positions, the detection time "
      "of each step per method, and the OBB trees' boxes at depths 0-3. graspcd study writes one "
      "per example into OUT/trajectories/; report/viewer-src/build.mjs bundles such files into "
      "one HTML page, report/draw_figures.py draws the report's pictures from them.\n"
      "Examples:\n"
      "  graspcd trajectory mjcf/example1.xml --out /tmp/example1.json\n"
      "  graspcd trajectory mjcf/example3.xml --methods sat,neurosat --repeats 3 --out e3.json"));
  return Command{app, [o] { run_trajectory_command(*o); }};
}

}  // namespace graspcd::cli
