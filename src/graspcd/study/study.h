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
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "graspcd/study/study_options.h"

namespace graspcd::study {

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
