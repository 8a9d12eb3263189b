// graspcd judge SCENE RECORD [--json]: a grasp run by any simulator, written as a run record
// (docs/run-record.md), judged with the library code of graspcd grasp (study/run_judge.h).

#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "command.h"
#include "graspcd/study/run_judge.h"
#include "graspcd/version/envelope.h"

namespace graspcd::cli {

namespace {

const char* const kJudgeHelp =
    "RECORD is a run record (docs/run-record.md): a JSON header, the start state, one JSON line "
    "per physics step (time, phase, qpos, qvel, optionally the simulator's contacts) and an end "
    "line, written by graspcd grasp --write-run or by another simulator (a MuJoCo 3.x runner, "
    "any engine). SCENE is the scene the run was made from, as MuJoCo 2.2 compiles it: its nq, "
    "nv, bodies and geom ids must be the record's. The judge sets each recorded state, computes "
    "its kinematics and judges the motion with the code graspcd grasp judges its own run with: "
    "the verdicts (gripped, held, the reason or what carried the object, notes, tilt, speed, "
    "kinetic energy, ejected, dropped), the race's outcome (held, held tilted, dropped, "
    "ejected, cannot start) and the true meshes' penetration (hand and support). Touch comes "
    "from the true meshes (within 1 mm plus the record's inflation), never from the record's "
    "contacts, so graspcd's own record judges to the verdicts of its run. The start rule "
    "(0.5 mm) is applied to the start state on the true meshes and, when the record has "
    "contacts, to the simulator's contacts of its first step (0.5 mm plus the inflation): "
    "either refusal is 'cannot start' with its message, as is a record that ended 'cannot "
    "start' or 'nonfinite'. With contacts, each closing grasp step's last physics step is "
    "judged against CGAL as grasp --judge does (phantom: more than 1 mm, plus the inflation, "
    "from a true surface; missed: true surfaces that meet without a contact). With the "
    "six-direction test in the record, '# six directions: held in N of 6 directions; lost "
    "...'.\n"
    "Text: '# judged RECORD on SCENE: SIMULATOR, CONFIGURATION; N states, ended STATUS', the "
    "verdict line of graspcd grasp, '# outcome: OUTCOME', and with contacts '# judged by CGAL "
    "over S closing steps: C hand-object contacts, P phantom, M missed'. --json: scene, "
    "record, simulator, configuration, timestep, inflation, noslip_iterations, multiccd, "
    "states, end {status, closing, message}, outcome, message (why it cannot start, or null), "
    "the verdict fields of graspcd grasp --json when judged, and judge (the contact counts, or "
    "null).\n"
    "Errors: a malformed record, or one that does not fit SCENE (bad JSON, a missing key, a "
    "qpos or qvel of another length, a body the scene does not have, a geom id out of range "
    "or not of its body, time going backwards within a phase, a phase out of order, a "
    "non-finite number, no end line, six_directions parameters other than the judge's) is one "
    "line 'RECORD:LINE: what', exit code 2; a scene that does not load, one line naming it.\n"
    "Examples:\n"
    "  graspcd grasp mjcf/real_robotiq_mug.xml --write-run mug.jsonl\n"
    "  graspcd judge mjcf/real_robotiq_mug.xml mug.jsonl --json";

struct JudgeCliOptions {
  std::string scene;
  std::string record;
  bool json = false;
};

void run_judge_command(const JudgeCliOptions& o) {
  const study::JudgedRun run = study::judge_run(o.scene, o.record);
  if (o.json) {
    nlohmann::json doc = study::judged_json(run);
    add_envelope(doc);
    std::cout << doc.dump(2) << '\n';
  } else {
    std::cout << study::judged_text(run);
  }
}

}  // namespace

Command add_judge_command(CLI::App& parent) {
  auto o = std::make_shared<JudgeCliOptions>();
  CLI::App* app = parent.add_subcommand(
      "judge", "Judge a grasp any simulator ran (a run record) with graspcd grasp's verdicts");
  app->add_option("SCENE", o->scene, "The scene the run was made from (MJCF)")->required();
  app->add_option("RECORD", o->record, "The run record (JSON Lines, docs/run-record.md)")
      ->required();
  app->add_flag("--json", o->json, "Print one JSON document instead of text");
  app->footer(wrap_help(kJudgeHelp));
  return Command{app, [o] { run_judge_command(*o); }, nullptr};
}

}  // namespace graspcd::cli
