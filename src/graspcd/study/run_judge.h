// `graspcd judge SCENE RECORD`: a grasp that any simulator ran, written as a run record
// (docs/run-record.md, grasp/run_record.h), judged with the library code of `graspcd grasp`: the
// record's states through the motion watch (grasp/motion_watch.h) and the one verdict function
// (grasp/verdicts.h), the start rule on the start state and on the simulator's own contacts, the
// simulator's contacts against CGAL (contact_judge.h), the six directions.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "graspcd/grasp/grasp_result.h"
#include "graspcd/grasp/run_record.h"
#include "graspcd/study/contact_judge.h"

namespace graspcd::study {

struct JudgedRun {
  std::string scene, record;
  grasp::RunHeader header;
  grasp::RunEnd end;
  long states = 0;  // state lines read, the start included
  // Whether the run is judged: false for a record that ended "cannot start" or "nonfinite", and
  // for a start the start rule refuses (its message in `message`); outcome "cannot start".
  bool judged = false;
  std::string message;
  // The verdicts (judged) and outcome (always).
  grasp::GraspResult result;
  // Where the record carries contacts: their phantom and missed counts on the closing steps.
  std::optional<ContactJudgeSummary> contacts;
};

// Judges `record` on `scene`. Throws io::InputError naming the record and its line for a
// malformed record or one that does not fit the scene, naming the scene (or its pair config) for
// a scene that does not load (docs/run-record.md, "Refusals").
JudgedRun judge_run(const std::string& scene, const std::string& record);

// The document of `graspcd judge --json` (without its envelope): the record's header, how it
// ended, the outcome, and when judged the verdict fields of `grasp --json` (grasp_output.h's
// verdict_json) and "judge" with the contact counts (contact_judge_json).
nlohmann::json judged_json(const JudgedRun& run);

// The text of `graspcd judge`: what was judged, the verdict's lines (grasp_output.h's
// verdict_text), the outcome, the contact counts.
std::string judged_text(const JudgedRun& run);

}  // namespace graspcd::study
