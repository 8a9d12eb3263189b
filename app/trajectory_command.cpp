// graspcd trajectory SCENE.xml --out FILE [--methods M,...] [--repeats N] [--max-steps N]: one
// grasp as a trajectory file for the viewer and the figures (src/graspcd/study/trajectory.h).
#include <chrono>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "command.h"
#include "graspcd/io/output_files.h"
#include "graspcd/study/trajectory.h"
#include "progress.h"

namespace graspcd::cli {

namespace {

struct TrajectoryCliOptions {
  std::string scene;
  std::string out;
  std::vector<std::string> methods = {"sat", "sat-cached", "neurosat"};
  bool force = false;  // --force: replace an existing --out that is no trajectory
  study::TrajectoryOptions options;
};

void run_trajectory_command(TrajectoryCliOptions& o) {
  o.options.methods.clear();
  for (const std::string& name : o.methods) {
    const auto m = parse_method(name);
    if (!m) throw UsageError("--methods: unknown method '" + name + "'");
    o.options.methods.push_back(*m);
  }
  // --out: never a file the run reads nor, without --force, a file that is no trajectory; a file
  // that cannot be written is found before the simulation; the trajectory goes to a hidden file
  // beside it, renamed over it at the end (io/output_files.h).
  study::check_trajectory_target(o.out, o.scene, o.force);
  io::AtomicFile out(o.out);
  const auto started = std::chrono::steady_clock::now();
  Progress progress("trajectory");
  progress.update(o.scene + ": recording the grasp, then replaying it with " +
                  std::to_string(o.options.methods.size()) + " method(s) ...");
  o.options.out_name = o.out;
  study::export_grasp(o.scene, out.write_path(), o.options);
  out.commit();
  std::ostringstream done;
  done << "wrote " << o.out << " in " << std::setprecision(3)
       << std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count() << " s";
  progress.done(done.str());
}

}  // namespace

Command add_trajectory_command(CLI::App& parent) {
  auto o = std::make_shared<TrajectoryCliOptions>();
  CLI::App* app = parent.add_subcommand(
      "trajectory", "One grasp as a trajectory file for the viewer (report/viewer-src)");
  app->add_option("scene", o->scene, "The MJCF scene (with its SCENE.pairs.json)")->required();
  app->add_option("--out", o->out, "The trajectory file to write (JSON)")->required();
  app->add_flag("--force", o->force,
                "Replace an existing --out that is not a trajectory graspcd wrote (never the "
                "scene, a file it includes or names, or its pair config)");
  app->add_option("--methods", o->methods, "Methods timed per grasp step")
      ->delimiter(',')
      ->capture_default_str();
  app->add_option("--repeats", o->options.repeats, "Timed replays per method (per-step medians)")
      ->transform(positive_integer())
      ->capture_default_str();
  app->add_option("--max-steps", o->options.max_steps, "Most closing grasp steps")
      ->transform(positive_integer())
      ->capture_default_str();
  app->footer(wrap_help(
      "Records the grasp of paper section 9 with graspcd's contacts (SAT), replays the recorded "
      "poses with each of --methods (all contacts, as Table 1) and writes one JSON file: the "
      "meshes once in their geom frames, per closing grasp step every geom's pose, our contacts "
      "and MuJoCo's native convex-hull contacts at the same joint positions, the detection time "
      "of each step per method, and the OBB trees' boxes at depths 0-3. graspcd study writes one "
      "per example into OUT/trajectories/; report/viewer-src/build.mjs bundles such files into "
      "one HTML page, report/draw_figures.py draws the report's pictures from them.\n"
      "The file never replaces a file the run reads (the scene, its includes, its meshes, its "
      "pair config) and, without --force, no existing file but a trajectory graspcd wrote "
      "('FILE: exists and is not a trajectory graspcd wrote', exit code 2, at once). "
      "It is written whole or not at all: a hidden file beside it (.NAME.graspcd-XXXXXX), "
      "created before the simulation (an --out that cannot be written is one line 'FILE: "
      "message', exit code 2, at once), renamed to FILE at the end, removed on an error or on "
      "INT, TERM and HUP. Progress: on a terminal, one line on stderr rewritten as the work "
      "goes; otherwise one final line '[trajectory] wrote FILE in S s'.\n"
      "Examples:\n"
      "  graspcd trajectory mjcf/example1.xml --out /tmp/example1.json\n"
      "  graspcd trajectory mjcf/example3.xml --methods sat,neurosat --repeats 3 --out e3.json"));
  return Command{app, [o] { run_trajectory_command(*o); }};
}

}  // namespace graspcd::cli
