#include "graspcd/study/run_judge.h"

#include <cmath>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <memory>
#include <sstream>

#include "graspcd/grasp/drive_config.h"
#include "graspcd/grasp/grasp_output.h"
#include "graspcd/grasp/motion_watch.h"
#include "graspcd/grasp/start_check.h"
#include "graspcd/grasp/true_surfaces.h"
#include "graspcd/grasp/verdicts.h"
#include "graspcd/io/warnings.h"
#include "graspcd/mujoco/model_loading.h"
#include "graspcd/mujoco/mujoco_messages.h"
#include "graspcd/mujoco/mujoco_ptr.h"
#include "graspcd/mujoco/pair_config.h"

namespace graspcd::study {

namespace {

using json = nlohmann::json;

// The bodies a record of `scene` must name: its drive's (the pair config's "grasp" section), or
// the project hand's scene contract (grasp/grasp.h).
struct SceneBodies {
  std::string object = "object", hand = "palm", support = "world";
};

SceneBodies scene_bodies(const std::string& scene) {
  SceneBodies out;
  const std::string config = mujoco::pair_config_path(scene);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(config, ec)) return out;
  const std::optional<grasp::DriveConfig> drive = grasp::load_drive_config(config);
  if (!drive) return out;
  out.object = drive->object;
  out.hand = drive->hand;
  out.support = drive->support.empty() ? "world" : drive->support;
  return out;
}

void set_state(const mjModel* m, mjData* d, const grasp::RecordState& s) {
  for (int i = 0; i < m->nq; ++i) d->qpos[i] = s.qpos[static_cast<std::size_t>(i)];
  for (int i = 0; i < m->nv; ++i) d->qvel[i] = s.qvel[static_cast<std::size_t>(i)];
  d->time = s.t;
  grasp::state_kinematics(m, d);
}

std::vector<mjContact> mj_contacts(const std::vector<grasp::RecordContact>& contacts) {
  std::vector<mjContact> out(contacts.size());
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    mjContact& c = out[i];
    c = mjContact{};
    c.geom1 = contacts[i].geom1;
    c.geom2 = contacts[i].geom2;
    c.dist = contacts[i].dist;
    for (int k = 0; k < 3; ++k) {
      c.pos[k] = contacts[i].pos[static_cast<std::size_t>(k)];
      c.frame[k] = contacts[i].normal[static_cast<std::size_t>(k)];
    }
  }
  return out;
}

// The start rule on the simulator's own contacts of the first step (found at the start state):
// the deepest object contact past kStartPenetration plus the inflation, as a message; "" within.
std::string simulator_start(const mjModel* m, int object, const grasp::RunHeader& header,
                            const std::vector<grasp::RecordContact>& contacts) {
  const int root = m->body_rootid[object];
  const grasp::RecordContact* deepest = nullptr;
  for (const grasp::RecordContact& c : contacts) {
    const bool of_object = m->body_rootid[m->geom_bodyid[c.geom1]] == root ||
                           m->body_rootid[m->geom_bodyid[c.geom2]] == root;
    if (of_object && (deepest == nullptr || c.dist < deepest->dist)) deepest = &c;
  }
  const double limit = grasp::kStartPenetration + header.inflation;
  if (deepest == nullptr || -deepest->dist <= limit) return "";
  char depth[96];
  std::snprintf(depth, sizeof depth, "%.1f mm deep at the start (at most %.2f mm allowed",
                -1e3 * deepest->dist, 1e3 * limit);
  return "cannot start in " + header.configuration + ": " + header.simulator +
         "'s contact between " + grasp::geom_label(m, deepest->geom1) + " and " +
         grasp::geom_label(m, deepest->geom2) + " lies " + depth +
         (header.inflation > 0 ? ", its inflation included" : "") +
         "): its geometry cannot represent the start";
}

}  // namespace

JudgedRun judge_run(const std::string& scene, const std::string& record) {
  JudgedRun out;
  out.scene = scene;
  out.record = record;
  const mujoco::ScopedMujocoErrors mujoco_errors(scene);
  const mujoco::ModelPtr model = mujoco::load_model(scene);
  const mjModel* m = model.get();
  const SceneBodies bodies = scene_bodies(scene);
  grasp::RunRecordReader reader(record, m, bodies.object, bodies.hand, bodies.support);
  const grasp::RunHeader& header = out.header = reader.header();
  const int object = mj_name2id(m, mjOBJ_BODY, header.object.c_str());
  const int hand = mj_name2id(m, mjOBJ_BODY, header.hand.c_str());
  const int support =
      header.support == "world" ? 0 : mj_name2id(m, mjOBJ_BODY, header.support.c_str());

  // The states, with one ahead (whether a state is its phase's last, or its grasp step's) and,
  // before the first is judged, the closing's first grasp step whole: its physics steps are the
  // true penetration's sampling.
  std::deque<grasp::RecordState> ahead;
  const auto read = [&] {
    grasp::RecordState s;
    if (!reader.next(s)) return false;
    ahead.push_back(std::move(s));
    return true;
  };
  bool more = true;
  while (more) {
    more = read();
    if (more &&
        !(ahead.back().phase == grasp::RunPhase::kStart ||
          (ahead.back().phase == grasp::RunPhase::kClose && ahead.back().grasp_step == 1))) {
      break;
    }
  }
  int sample = 0;
  for (const grasp::RecordState& s : ahead) {
    sample += s.phase == grasp::RunPhase::kClose && s.grasp_step == 1 ? 1 : 0;
  }
  // The geoms' surfaces, built once for the start check, the true penetration and the touch.
  grasp::SurfaceCache surfaces(m);
  grasp::WatchOptions options;
  options.touch_tolerance = grasp::kTouchDistance + header.inflation;
  options.true_penetration = true;
  options.sample = sample > 0 ? sample : 5;
  options.surfaces = &surfaces;
  grasp::MotionWatch watch(m, m, object, hand, support, options);
  std::unique_ptr<ContactJudge> judge;
  if (header.contacts) {
    judge = std::make_unique<ContactJudge>(
        m, header.object, header.support == "world" ? "" : header.support, header.inflation);
  }

  mujoco::DataPtr current(mj_makeData(m));
  mujoco::DataPtr previous(mj_makeData(m));
  std::string refusal;
  double last_t = 0;
  while (!ahead.empty()) {
    if (more && ahead.size() < 2) more = read();
    const grasp::RecordState s = std::move(ahead.front());
    ahead.pop_front();
    const grasp::RecordState* next = ahead.empty() ? nullptr : &ahead.front();
    set_state(m, current.get(), s);
    ++out.states;
    last_t = s.t;
    if (s.phase == grasp::RunPhase::kStart) {
      const std::string problem =
          grasp::check_start_state(m, current.get(), object, {}, {}, &surfaces);
      if (!problem.empty()) refusal = "the start state is not valid: " + problem;
    } else if (out.states == 2 && header.contacts && refusal.empty()) {
      refusal = simulator_start(m, object, header, s.contacts);
    }
    const bool last = next == nullptr || next->phase != s.phase || next->direction != s.direction;
    watch.observe(current.get(), s.phase, s.t, last, s.direction);
    const bool step_end =
        s.phase == grasp::RunPhase::kClose &&
        (next == nullptr || next->phase != s.phase || next->grasp_step != s.grasp_step);
    if (judge && step_end) {
      // The step's contacts were found at the state before it.
      const std::vector<mjContact> contacts = mj_contacts(s.contacts);
      judge->judge_step(m, previous.get(), s.grasp_step, contacts.data(),
                        static_cast<int>(contacts.size()));
    }
    std::swap(current, previous);
  }
  out.end = reader.end();
  if (judge) out.contacts = judge->summary();

  grasp::GraspResult& r = out.result;
  r.scene = scene;
  if (out.end.status == "cannot start") {
    out.message = out.end.message;
  } else if (!refusal.empty()) {
    out.message = refusal;
  } else if (out.end.status == "nonfinite") {
    char text[64];
    std::snprintf(text, sizeof text, "the simulation went non-finite after t = %.3f s", last_t);
    out.message = text + (out.end.message.empty() ? "" : ": " + out.end.message);
  } else {
    out.judged = true;
  }
  if (!out.judged) {
    r.outcome = "cannot start";
    return out;
  }
  watch.fill(r);
  r.closing = out.end.closing;
  r.max_steps = header.max_steps;
  grasp::judge_grasp(r);
  r.support_warning =
      grasp::support_warning(r, "as " + header.simulator + " collides them in configuration '" +
                                    header.configuration + "'");
  if (!r.support_warning.empty()) {
    graspcd::warnings().add("support_penetration", record + ": " + r.support_warning);
  }
  return out;
}

json judged_json(const JudgedRun& run) {
  const grasp::RunHeader& h = run.header;
  json doc = {{"scene", run.scene},
              {"record", run.record},
              {"simulator", h.simulator},
              {"configuration", h.configuration},
              {"timestep", h.timestep},
              {"inflation", h.inflation},
              {"noslip_iterations", h.noslip_iterations ? json(*h.noslip_iterations) : json()},
              {"multiccd", h.multiccd ? json(*h.multiccd) : json()},
              {"states", run.states},
              {"end",
               {{"status", run.end.status},
                {"closing", run.end.closing.empty() ? json() : json(run.end.closing)},
                {"message", run.end.message.empty() ? json() : json(run.end.message)}}},
              {"outcome", run.result.outcome},
              {"message", run.message.empty() ? json() : json(run.message)}};
  if (run.judged) doc.update(grasp::verdict_json(run.result));
  doc["judge"] = run.contacts ? contact_judge_json(*run.contacts, h.inflation) : json();
  return doc;
}

std::string judged_text(const JudgedRun& run) {
  std::ostringstream out;
  out << "# judged " << run.record << " on " << run.scene << ": " << run.header.simulator << ", "
      << run.header.configuration << "; " << run.states << " states, ended " << run.end.status
      << (run.end.closing.empty() ? "" : " (closing " + run.end.closing + ")") << '\n';
  if (run.judged) {
    out << grasp::verdict_text(run.result);
  } else {
    out << "# cannot start: " << run.message << '\n';
  }
  out << "# outcome: " << run.result.outcome << '\n';
  if (run.contacts) {
    const ContactJudgeSummary& j = *run.contacts;
    out << "# judged by CGAL over " << j.steps << " closing steps: " << j.contacts
        << " hand-object contacts, " << j.phantom << " phantom, " << j.missed << " missed\n";
  }
  return out.str();
}

}  // namespace graspcd::study
