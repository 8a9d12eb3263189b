// graspcd study [--quick] [--out DIR] [--repeats N] [--shard i/n] [--no-table] [--no-sweep]
// [--merge FILE...]: the reproduction study (src/graspcd/study/study.h), its data into DIR.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "command.h"
#include "graspcd/peer/fcl_querier.h"
#include "graspcd/study/study.h"
#include "progress.h"

namespace graspcd::cli {

namespace {

struct StudyCliOptions {
  study::StudyOptions study;
  std::string shard;
  bool no_table = false;
  bool no_sweep = false;
  std::vector<std::string> merge;
  std::size_t repeats_given = 0;
};

void run_study_command(StudyCliOptions& o, const CLI::App& app) {
  o.repeats_given = app.count("--repeats");
  Progress progress("study");
  const auto log = [&progress](const std::string& line) { progress.update(line); };
  if (!o.merge.empty()) {
    study::merge_shards(o.merge, o.study.out_dir, log);
    progress.done("merged " + std::to_string(o.merge.size()) + " shards into " + o.study.out_dir);
    return;
  }
  if (!o.shard.empty()) {
    try {
      o.study.shard = study::parse_shard(o.shard);
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
  }
  // --quick is a smoke test: 3 repeats unless --repeats says otherwise.
  if (o.study.quick && o.repeats_given == 0) o.study.repeats = 3;
  o.study.table = !o.no_table;
  o.study.sweep = !o.no_sweep;
  if (!o.study.table && !o.study.sweep) throw UsageError("--no-table and --no-sweep leave nothing");
  // FCL's OBB and RSS trees are Table 1's peer rows.
  o.study.peers = peer::fcl_table_methods();
  study::run_study(o.study, log);
  progress.done("wrote " + o.study.out_dir);
}

}  // namespace

Command add_study_command(CLI::App& parent) {
  auto o = std::make_shared<StudyCliOptions>();
  CLI::App* app = parent.add_subcommand(
      "study", "The reproduction study: Table 1, Figures 13-15 and the run-time/error sweep");
  app->add_flag("--quick", o->study.quick,
                "Smoke test (< 1 min): example 1, 3 repeats, no perceptron at cap 1,500 in "
                "Table 1, a short sweep");
  app->add_flag("--full-sweep", o->study.full_sweep,
                "The sweep on all three examples with every knob value (hours: use --shard)");
  app->add_option("--out", o->study.out_dir, "Output folder (JSON and CSV)")->capture_default_str();
  app->add_option("--repeats", o->study.repeats, "Timed replays per method (medians of these)")
      ->transform(positive_integer())
      ->capture_default_str();
  app->add_option("--perceptron-repeats", o->study.perceptron_repeats,
                  "Timed replays of Table 1's perceptron, perceptron-warm and perceptron-scaled "
                  "(at most --repeats; they are most of the study's time)")
      ->transform(positive_integer())
      ->capture_default_str();
  app->add_option("--jobs", o->study.jobs, "Replays run at once, one thread each (0: one per core)")
      ->transform(non_negative_integer())
      ->capture_default_str();
  app->add_option("--max-steps", o->study.max_steps, "Most closing grasp steps per grasp")
      ->transform(positive_integer())
      ->capture_default_str();
  app->add_option("--mjcf", o->study.mjcf_dir,
                  "Folder of the scenes (default: the template scenes, PREFIX/share/graspcd/mjcf)");
  app->add_option("--shard", o->shard,
                  "Run only shard i of n of the sweep (i from 0 to n-1), no tables");
  app->add_flag("--no-table", o->no_table, "Skip Table 1 and Figures 13-15");
  app->add_flag("--no-sweep", o->no_sweep, "Skip the run-time/error sweep");
  app->add_option("--merge", o->merge,
                  "Join sweep shard files (from --shard runs) into OUT/sweep.json and .csv")
      ->expected(1, -1);
  app->footer(wrap_help(
      "Records each grasp once (the triangle-hand examples 1-3 with graspcd's contacts and SAT; "
      "the box hand with graspcd's exact box-box path), then replays the recorded poses of "
      "every "
      "closing grasp step for every method, --repeats times (the perceptron methods that run to "
      "their cap --perceptron-repeats times), and reports medians with min-max. "
      "Every replay keeps its answers: their hash beside CGAL's proves that a timing run also "
      "agreed with the exact ground truth.\n"
      "Writes into --out: study.json (machine, build, recordings, Table 1, the box hand of "
      "Figures 13-15), table1.csv, box_hand.csv, sweep.json and sweep.csv (each sweep point: "
      "time, missed and false contacts, first-contact step error, contact position error, "
      "against CGAL), and with the tables trajectories/<grasp>.json per grasp (poses, contacts, "
      "per-step times of every Table 1 method, OBB levels: graspcd trajectory --help), which the "
      "viewer and the pictures are drawn from. Then run /usr/bin/python3 report/make_report.py OUT "
      "to draw the figures and write OUT/REPORT.md; ./run study does both and bundles the "
      "viewer OUT/viewer/index.html.\n"
      "The default sweep replays example 1 (perceptron caps 10-1500, Neuro-SAT switches "
      "10-3000, leaf sizes 1-16, float nodes, Moller variants, first-contact mode); its points "
      "equal to a Table 1 method reuse Table 1's replays. --full-sweep adds caps 30, 1000 and "
      "3000 and switch 30, on all three examples.\n"
      "Progress goes to stderr. The default run takes about 4 minutes of CPU time (user+sys; "
      "about 2 minutes on 2 idle cores), --quick under a minute.\n"
      "Scale-out: --shard i/n runs every n-th sweep point from i (no tables) into "
      "sweep.shard-i-of-n.json; --merge FILE... joins the shards (they must come from the same "
      "build, recordings and options) into sweep.json. cluster/sweep.sbatch runs the shards "
      "as a Slurm array job.\n"
      "Examples:\n"
      "  graspcd study --quick --out /tmp/q\n"
      "  graspcd study --no-table --shard 0/2 --out /tmp/s\n"
      "  graspcd study --merge /tmp/s/sweep.shard-0-of-2.json /tmp/s/sweep.shard-1-of-2.json "
      "--out /tmp/s"));
  return Command{app, [o, app] { run_study_command(*o, *app); }};
}

}  // namespace graspcd::cli
