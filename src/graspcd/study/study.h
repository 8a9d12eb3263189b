// `graspcd study`: the reproduction study of paper sections 9-11 and its data.
//
// 1. Records the grasps once: the three triangle-hand examples (mjcf/example{1,2,3}.xml) with the
//    bridge (SAT), and the parallelepiped hand (mjcf/hand_boxes.xml) with the bridge's exact
//    box-box path (SAT decides, MuJoCo's box-box routine makes the contacts).
// 2. Table 1: every method replays every example's grasp steps `repeats` times (all-contacts mode,
//    exact triangle test, the trees the bridge builds); total detection time per method (median,
//    min, max), work counters, and the hash of its answers beside CGAL's.
// 3. Figures 13-15: SAT, the perceptron (cap 10,000, the paper's box hand) and Neuro-SAT (switch
//    300) replay the box hand's segments B and C against the object's boxes: time and perceptron
//    passes per grasp step, the cumulative time saved against SAT, and Novikoff's bound on the
//    perceptron's updates from the exact gap of each box pair.
// 4. The sweep: knobs against error (CGAL ground truth): missed and false contacts, first-contact
//    step error, contact position error; split into shards (--shard i/n) that merge() joins.
// Writes JSON (the data) and CSV (the tables) into `out_dir`; report/make_report.py turns them
// into report/out/REPORT.md and its figures.
#pragma once

#include <functional>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

namespace graspcd::study {

class MeshScene;  // recording.h
class Querier;    // replay.h

// A replay method from outside the study's own detectors: a peer library (FCL, in the graspcd
// executable: graspcd/peer/fcl_querier.h). It is one more row of Table 1, after the detector
// methods, replayed and checked against CGAL like them. The study library links no peer; the
// caller hands these in.
struct PeerMethod {
  std::string name;                                                // its row name, "fcl-obb"
  std::function<std::unique_ptr<Querier>(const MeshScene&)> make;  // its querier on a scene
};

struct Shard {
  int index = 0;  // 0 .. count-1
  int count = 1;
};

struct StudyOptions {
  std::string out_dir = "report/out";
  std::string mjcf_dir;  // the scenes (default: graspcd::mjcf_dir())
  bool quick = false;    // example 1, fewer methods and sweep points: the smoke test
  int repeats = 5;       // timed replays per method (medians of these)
  int max_steps = 400;   // closing grasp steps at most
  // Replays run this many at a time, one thread each (0: one per core). Each replay's clock
  // measures its own thread's queries; the box hand of Figures 13-15 always runs alone.
  int jobs = 0;
  bool table = true;  // Table 1 and Figures 13-15
  bool sweep = true;  // the error sweep
  // The sweep on all three examples with every knob value (a cluster job, see --shard); by
  // default it runs on example 1 with the standard values.
  bool full_sweep = false;
  std::optional<Shard> shard;     // only this shard of the sweep (implies table = false)
  std::vector<PeerMethod> peers;  // Table 1's peer rows, in this order after the detectors
};

// Runs the study; progress lines go to `log` (stderr in the command). Throws std::runtime_error
// (and grasp::GraspInputError for a bad scene) with a one-line message.
void run_study(const StudyOptions& options, const std::function<void(const std::string&)>& log);

// Joins sweep shard files (each written by a --shard run) into OUT/sweep.json and OUT/sweep.csv.
// Checks that the shards agree on the recordings (pose hashes) and the configuration list, and
// that every configuration appears exactly once. Throws std::runtime_error naming the file.
void merge_shards(const std::vector<std::string>& files, const std::string& out_dir,
                  const std::function<void(const std::string&)>& log);

// Reads a shard file written by a --shard run (`kind`: "a sweep shard", "an object-set shard"): a
// JSON object holding every key of `keys`. Throws std::runtime_error naming the file: "FILE:
// cannot open the shard file", "FILE: not KIND (the parser's message)", "FILE: not KIND (no A, B
// or C)".
nlohmann::json read_shard_file(const std::string& file, const std::string& kind,
                               const std::vector<std::string>& keys);

// Parses "i/n" (0 <= i < n); throws std::invalid_argument otherwise.
Shard parse_shard(const std::string& text);

}  // namespace graspcd::study
