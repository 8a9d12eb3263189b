// Table 1 of the paper (section 10): every method replays every example's grasp steps `repeats`
// times (all-contacts mode, exact triangle test, the trees graspcd serves with); total detection
// time per method (median, min, max), work counters, and the hash of its answers beside CGAL's.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "graspcd/study/experiment.h"
#include "graspcd/study/recording.h"
#include "graspcd/study/replay.h"
#include "graspcd/study/study_options.h"

namespace graspcd::study {

// Every (method, example) replay is a job; `o.jobs` run at once, one thread each (each replay
// alone on its core), the perceptron methods first since they take longest. The detector methods
// come first in the table, then `o.peers`. Fills `cache` with every method's replays.
nlohmann::json run_table(const StudyOptions& o, const std::vector<Example>& ex,
                         const std::vector<Recording>& recs, const std::vector<Answers>& truths,
                         const std::vector<std::unique_ptr<MeshScene>>& scenes,
                         const std::vector<std::vector<Pose>>& poses, ReplayCache& cache,
                         const Log& log);

// table1.csv: one row per (method, example).
std::string table_csv(const nlohmann::json& table);

}  // namespace graspcd::study
