// `graspcd study`: the reproduction study of paper sections 9-11 and its data.
//
// 1. Records the grasps once (recording.h): the three triangle-hand examples
//    (mjcf/example{1,2,3}.xml) served by graspcd with SAT, and the parallelepiped hand
//    (mjcf/hand_boxes.xml) through graspcd's exact box-box path.
// 2. Table 1 (table1.h), 3. Figures 13-15 (box_hand.h), 4. the error sweep and its shards
//    (sweep.h), each replaying the recordings against CGAL's answers.
// Writes JSON (the data) and CSV (the tables) into `out_dir`, from which the report is drawn:
// whole or not at all (a private folder OUT/.graspcd-study-XXXXXX, removed on errors and on INT,
// TERM and HUP, its files moved into OUT together at the end; io/output_files.h), so an
// interrupted study leaves OUT as it was.
#pragma once

#include <functional>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "graspcd/study/study_options.h"

namespace graspcd::study {

// Runs the study; progress lines go to `log` (stderr in the command). Throws std::runtime_error
// (and io::InputError for a bad scene) with a one-line message.
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
