// The output of one grasp (`graspcd grasp`; its --help says what each field means): the JSON
// document and the text, each a function of the grasp result and of what ran (an object run's
// description, a decomposed scene).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "graspcd/grasp/decomposed_scene.h"
#include "graspcd/grasp/grasp_result.h"
#include "graspcd/grasp/object_run.h"

namespace graspcd::grasp {

// The document without its envelope (version/envelope.h): scene, method, the steps, the verdicts
// and measures, the cost (cost_json); "object" with an object run, "decomposed" (with the
// decomposition's folder `decomposed_dir`) with a decomposed scene.
nlohmann::json grasp_json(const GraspResult& r, const ObjectRunDescription* object = nullptr,
                          const DecomposedScene* decomposed = nullptr,
                          const std::string& decomposed_dir = "");

// The verdicts and how the object moved (verdicts.h), the keys `graspcd grasp --json` and
// `graspcd judge --json` share: gripped, held, reason, evidence, notes, outcome, the heights,
// rise and travel, drift, tilts, speed, energy, ejected, dropped_at and drop, closing, the
// support's warning, the true penetration, the six directions when run.
nlohmann::json verdict_json(const GraspResult& r);

// The verdict's lines of the text (shared with `graspcd judge`): "# gripped ...; held ...",
// and "# six directions: ..." when they ran.
std::string verdict_text(const GraspResult& r);

// The text: "# object ..." with an object run, the per-step table (left out when `quiet`), the
// summary lines, "# decomposed: ..." with a decomposed scene. Without the cost line (cost_text).
std::string grasp_text(const GraspResult& r, const ObjectRunDescription* object = nullptr,
                       const DecomposedScene* decomposed = nullptr, bool quiet = false);

// The document's "cost" (grasp_cost.h): {"cpu_s", "wall_s", "before_first_step": {"cpu_s",
// "wall_s"}, "parts": {KEY: {"cpu_s", "wall_s"}, ...}} with every part under its key.
nlohmann::json cost_json(const GraspCost& cost);

// The text's cost line: "# cost 0.61 s CPU (0.64 s wall): scene 0.03, compile 0.12, ... s CPU;
// 0.35 s CPU before the first physics step", the parts that took time in their order.
std::string cost_text(const GraspCost& cost);

}  // namespace graspcd::grasp
