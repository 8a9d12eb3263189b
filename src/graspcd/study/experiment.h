// What the study's experiments (study.h: Table 1, the box hand, the sweep and its shards) share:
// the examples, Table 1's replays kept for the sweep and the trajectories, the JSON of timings and
// work counters, and writing a file.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "graspcd/core/tree_query.h"
#include "graspcd/study/replay.h"

namespace graspcd::study {

using Log = std::function<void(const std::string&)>;

// The version of the layout of study.json and sweep.json.
constexpr int kSchema = 1;

// An example of the study: its name ("example1") and its scene file.
struct Example {
  std::string name;
  std::string scene;
};

// Table 1's replays by method name, per example: the sweep reuses those of its default points.
using ReplayCache = std::map<std::string, std::vector<ReplayStats>>;

// `v` in fixed notation with `digits` decimals.
std::string fmt(double v, int digits = 2);

// The work counters of a replay as JSON.
nlohmann::json counters_json(const QueryCounters& c);

// Median, min, max and every repeat of a replay's total times (nanoseconds in, milliseconds out).
nlohmann::json timing_json(const std::vector<double>& ns);

// Writes `text` into `path`; throws std::runtime_error "PATH: cannot write".
void write_file(const std::filesystem::path& path, const std::string& text);

}  // namespace graspcd::study
