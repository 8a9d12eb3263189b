// The sweep: knobs against error, with CGAL as ground truth. Each point (a separator, a perceptron
// cap, a Neuro-SAT switch, a leaf size, float tree nodes, a Moller variant, first-contact mode)
// replays the recorded grasps; the answers give missed and false contacts, the first-contact step
// error and the contact position error. Split into shards (--shard i/n): shard i runs every n-th
// point from i, and merge_shards (study.h) joins them.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "graspcd/study/experiment.h"
#include "graspcd/study/recording.h"
#include "graspcd/study/replay.h"
#include "graspcd/study/study_options.h"

namespace graspcd::study {

// The sweep's points of `o.shard` (all of them without one) on example 1, or on every example of
// `all_examples` with `o.full_sweep`. Points equal to a Table 1 method reuse its replays in
// `cache`; the others are replayed `o.repeats` times, `o.jobs` at a time.
nlohmann::json run_sweep(const StudyOptions& o, const std::vector<Example>& all_examples,
                         const std::vector<Recording>& recs, const std::vector<Answers>& truths,
                         const ReplayCache& cache, const Log& log);

// sweep.csv: one row per sweep point.
std::string sweep_csv(const nlohmann::json& sweep);

}  // namespace graspcd::study
