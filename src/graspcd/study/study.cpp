#include "graspcd/study/study.h"

#include <algorithm>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <thread>

#include "graspcd/core/clock.h"
#include "graspcd/io/output_files.h"
#include "graspcd/study/box_hand.h"
#include "graspcd/study/experiment.h"
#include "graspcd/study/recording.h"
#include "graspcd/study/replay.h"
#include "graspcd/study/sweep.h"
#include "graspcd/study/table1.h"
#include "graspcd/study/trajectory.h"
#include "graspcd/version/data_dirs.h"
#include "graspcd/version/envelope.h"
#include "graspcd/version/machine.h"

namespace graspcd::study {

namespace {

using json = nlohmann::json;

// The examples of the study, in order.
std::vector<Example> examples(const StudyOptions& o) {
  std::vector<Example> v;
  // Example 1 alone when nothing needs the others (--quick, or a default sweep without tables).
  const int n = o.quick || (!o.table && !o.full_sweep) ? 1 : 3;
  for (int i = 1; i <= n; ++i) {
    const std::string name = "example" + std::to_string(i);
    v.push_back({name, (std::filesystem::path(o.mjcf_dir) / (name + ".xml")).string()});
  }
  return v;
}

json recording_json(const Recording& r, const std::vector<int>* truth_first) {
  json j = {{"name", r.name},
            {"scene", r.scene},
            {"recorded_with", r.native ? "native" : "graspcd, " + r.grasp.method},
            {"grasp_steps", r.steps()},
            {"gripped", r.grasp.gripped},
            {"held", r.grasp.held},
            {"object_rise_m", r.grasp.object_z_final - r.grasp.object_z_initial},
            {"first_contact", r.grasp.first_contact},
            {"step_wall_ms", r.grasp.step_wall_ms},
            {"pose_hash", hex64(r.pose_hash)}};
  if (truth_first) j["truth_first_contact"] = *truth_first;
  return j;
}

// The viewer's and the figures' data (trajectory.h): each example with the per-step detection
// times of Table 1's replays, and the box hand.
void write_trajectories(const std::filesystem::path& dir, const std::filesystem::path& shown,
                        const std::vector<Example>& ex, const std::vector<Recording>& recs,
                        const std::vector<std::unique_ptr<MeshScene>>& scenes,
                        const ReplayCache& cache, const Recording& box, const Log& log) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error(dir.string() + ": cannot create the folder: " + ec.message());
  for (std::size_t e = 0; e < ex.size(); ++e) {
    StepTimes times;
    for (const auto& [method, stats] : cache)
      times.emplace_back(method, step_medians(stats[e].step_ns));
    write_trajectory((dir / (ex[e].name + ".json")).string(), recs[e], scenes[e].get(), times);
  }
  write_trajectory((dir / "hand_boxes.json").string(), box, nullptr, {});
  log("wrote " + std::to_string(ex.size() + 1) + " trajectories into " + shown.string());
}

// The examples' grasps, recorded once served by graspcd (SAT), each with its scene and CGAL's
// answers at every recorded grasp step.
struct Grasps {
  std::vector<Recording> recs;
  std::vector<std::unique_ptr<MeshScene>> scenes;
  std::vector<Answers> truths;
};

Grasps record_examples(const StudyOptions& o, const std::vector<Example>& ex, const Log& log) {
  Grasps g;
  for (const Example& e : ex) {
    const Clock::time_point t = Clock::now();
    g.recs.push_back(record_grasp(e.name, e.scene, false, o.max_steps));
    const Recording& r = g.recs.back();
    log("recorded " + e.name + " with graspcd (sat): " + std::to_string(r.steps()) +
        " grasp steps, " + (r.grasp.held ? "held" : "NOT held") + ", rise " +
        fmt(100 * (r.grasp.object_z_final - r.grasp.object_z_initial), 1) + " cm (" +
        fmt(seconds_since(t), 1) + " s)");
  }
  for (std::size_t e = 0; e < ex.size(); ++e) {
    const Clock::time_point t = Clock::now();
    g.scenes.push_back(std::make_unique<MeshScene>(ex[e].scene));
    g.truths.push_back(exact_answers(*g.scenes.back(), g.recs[e]));
    log("CGAL ground truth for " + ex[e].name + ": " + std::to_string(g.recs[e].steps()) +
        " steps x " + std::to_string(g.scenes.back()->pairs().size()) + " pairs (" +
        fmt(seconds_since(t), 1) + " s)");
  }
  return g;
}

json recordings_json(const std::vector<Example>& ex, const Grasps& g) {
  json recordings = json::array();
  for (std::size_t e = 0; e < ex.size(); ++e) {
    const std::vector<int> truth_first =
        first_contact_steps(*g.scenes[e], g.truths[e], g.recs[e].steps());
    json r = recording_json(g.recs[e], &truth_first);
    r["pairs"] = g.scenes[e]->pairs().size();
    r["faces"] = g.scenes[e]->face_count();
    r["truth_pairs_hash"] = hex64(g.truths[e].pairs_hash);
    recordings.push_back(r);
  }
  return recordings;
}

// Table 1, the box hand of Figures 13-15 and the trajectories: study.json, table1.csv,
// box_hand.csv and trajectories/ in `out` (named `shown` in the log). Fills `cache` with Table 1's
// replays.
void write_tables(const StudyOptions& o, const std::vector<Example>& ex, const Grasps& g,
                  const std::filesystem::path& out, const std::filesystem::path& shown,
                  const Clock::time_point start, ReplayCache& cache, const Log& log) {
  json study = {{"schema", kSchema},
                {"created", now_utc()},
                {"quick", o.quick},
                {"repeats", o.repeats},
                {"perceptron_repeats", std::min(o.repeats, o.perceptron_repeats)},
                {"machine", machine_info()},
                {"build", build_info()}};
  study["recordings"] = recordings_json(ex, g);
  std::vector<std::vector<Pose>> poses;
  for (std::size_t e = 0; e < ex.size(); ++e)
    poses.push_back(recorded_poses(*g.scenes[e], g.recs[e]));
  study["table1"] = run_table(o, ex, g.recs, g.truths, g.scenes, poses, cache, log);
  write_file(out / "table1.csv", table_csv(study["table1"]));

  const std::string box_scene = (std::filesystem::path(o.mjcf_dir) / "hand_boxes.xml").string();
  const Clock::time_point t = Clock::now();
  const Recording box = record_grasp("hand_boxes", box_scene, false, o.max_steps);
  log("recorded hand_boxes with graspcd (sat, exact box-box): " + std::to_string(box.steps()) +
      " grasp steps (" + fmt(seconds_since(t), 1) + " s)");
  study["box_hand"] = run_box_hand(o, box, log);
  study["box_hand"]["recording"] = recording_json(box, nullptr);
  write_file(out / "box_hand.csv", box_csv(study["box_hand"]));
  write_trajectories(out / "trajectories", shown / "trajectories", ex, g.recs, g.scenes, cache, box,
                     log);
  study["seconds"] = seconds_since(start);
  add_envelope(study);
  write_file(out / "study.json", study.dump(1) + "\n");
  log("wrote " + (shown / "study.json").string() + ", table1.csv, box_hand.csv");
}

// The sweep (or its shard) into sweep.json and sweep.csv (sweep.shard-i-of-n.* for a shard) in
// `out` (named `shown` in the log).
void write_sweep(const StudyOptions& o, const std::vector<Example>& ex, const Grasps& g,
                 const std::filesystem::path& out, const std::filesystem::path& shown,
                 const ReplayCache& cache, const Log& log) {
  json sweep = run_sweep(o, ex, g.recs, g.truths, cache, log);
  add_envelope(sweep);
  const std::string base = o.shard ? "sweep.shard-" + std::to_string(o.shard->index) + "-of-" +
                                         std::to_string(o.shard->count)
                                   : std::string("sweep");
  write_file(out / (base + ".json"), sweep.dump(1) + "\n");
  write_file(out / (base + ".csv"), sweep_csv(sweep));
  log("wrote " + (shown / (base + ".json")).string() + " and .csv");
}

}  // namespace

void run_study(const StudyOptions& options, const Log& log) {
  StudyOptions o = options;
  if (o.mjcf_dir.empty()) o.mjcf_dir = graspcd::mjcf_dir();
  if (o.repeats < 1) throw std::runtime_error("--repeats must be >= 1");
  if (o.perceptron_repeats < 1) throw std::runtime_error("--perceptron-repeats must be >= 1");
  if (o.jobs < 1) o.jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (o.shard) o.table = false;
  const Clock::time_point start = Clock::now();
  // The study is written whole or not at all: into a private folder in OUT (removed on errors and
  // on INT, TERM and HUP), whose files are moved into OUT together at the end.
  const std::filesystem::path out(o.out_dir);
  std::optional<io::RemoveIfEmpty> created;
  if (io::prepare_output_folder(o.out_dir)) created.emplace(out);
  const io::CleanupGuard work = io::make_private_folder(out, ".graspcd-study", o.out_dir);

  const std::vector<Example> ex = examples(o);
  const Grasps g = record_examples(o, ex, log);
  ReplayCache cache;
  if (o.table) write_tables(o, ex, g, work.path(), out, start, cache, log);
  if (o.sweep) write_sweep(o, ex, g, work.path(), out, cache, log);
  io::move_entries(work.path(), out, o.out_dir);
  log("done in " + fmt(seconds_since(start), 1) + " s");
}

}  // namespace graspcd::study
