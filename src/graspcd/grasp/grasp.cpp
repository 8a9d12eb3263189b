#include "graspcd/grasp/grasp.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "graspcd/grasp/decomposed_pieces.h"
#include "graspcd/grasp/drive_config.h"
#include "graspcd/grasp/driven_run.h"
#include "graspcd/grasp/grasp_run.h"
#include "graspcd/grasp/hand_run.h"
#include "graspcd/grasp/run_record.h"
#include "graspcd/grasp/start_check.h"
#include "graspcd/grasp/surface_cache.h"
#include "graspcd/grasp/true_surfaces.h"
#include "graspcd/grasp/verdicts.h"
#include "graspcd/io/warnings.h"
#include "graspcd/mujoco/collision.h"
#include "graspcd/mujoco/mujoco_messages.h"
#include "graspcd/mujoco/mujoco_ptr.h"
#include "graspcd/mujoco/registry.h"
#include "graspcd/version.h"

namespace graspcd::grasp {

namespace {

// The start rule (grasp.h, start_check.h) as bad input naming the scene: the scene itself, its
// object's true meshes (for a decomposed scene, the model with the object as it was) checked by
// check_start_state; then, under native collision, the geometry MuJoCo collides (the hulls of
// the meshes, or of the pieces) by check_hull_start. The refusal, or none when the start is valid.
// `truth`: the model with the true object (true_object_model) for a decomposed scene, else null.
// `open`: the open meshes reported elsewhere (the hand's, the served ones). `surfaces`: the geoms'
// surfaces (the same geometry in `m` and `truth`).
GraspScene::Refusal start_refusal(const mjModel* m, const mjData* d, int object,
                                  const std::string& scene, const GraspOptions& options,
                                  const mjModel* truth, const OpenMeshes& open,
                                  SurfaceCache* surfaces) {
  const bool decomposed = truth != nullptr;
  const mujoco::SceneNames& names = options.names;
  const std::string problem =
      check_start_state(decomposed ? truth : m, d, object, names, open, surfaces);
  if (!problem.empty()) {
    return {names.refusal(scene, 0, "the start state is not valid: " + problem + names.start_note),
            false,
            {}};
  }
  if (!options.native) return {};
  const std::string hull = check_hull_start(m, d, object, names, surfaces);
  if (!hull.empty()) {
    return {names.refusal(scene, 0,
                          std::string("cannot start with ") +
                              (decomposed ? "--decomposed" : "--native") + ": " + hull +
                              " (a limit of the " + (decomposed ? "pieces" : "hull") +
                              ", not of the scene; graspcd's contacts start this scene)"),
            true,
            {}};
  }
  return {};
}

// The pair config of a grasp: its "grasp" section (drive_config.h) when it has one and, unless
// the collision is native, the registry built on it with the options' overrides. Errors name the
// config.
struct GraspConfig {
  mujoco::RegistryConfig registry_config;
  std::unique_ptr<mujoco::Registry> registry;
  std::optional<DriveConfig> drive;
};

GraspConfig load_grasp_config(const mjModel* m, const std::string& config_path,
                              const GraspOptions& options) {
  GraspConfig out;
  // How to drive the hand (the config's "grasp" section, drive_config.h); with native collision
  // that is all the config says.
  std::error_code exists_ec;
  if (std::filesystem::is_regular_file(config_path, exists_ec)) {
    if (options.native) {
      out.registry_config = mujoco::load_registry_config(config_path, options.names);
    }
    out.drive = load_drive_config(config_path, options.names);
  }
  if (options.native) return out;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(config_path, ec)) {
    throw options.names.refusal(config_path, 0, "cannot open the pair config");
  }
  mujoco::RegistryConfig& config = out.registry_config;
  config = mujoco::load_registry_config(config_path, options.names);
  if (options.method) config.method = *options.method;
  if (options.cap) config.detector.cap = *options.cap;
  if (options.switch_passes) config.detector.switch_passes = *options.switch_passes;
  if (options.front_list) config.front_list = *options.front_list;
  if (options.contact_reuse) config.contact_reuse = *options.contact_reuse;
  if (options.reduction) config.manifold.reduction = *options.reduction;
  if (options.max_contacts) config.manifold.max_per_pair = *options.max_contacts;
  out.registry = std::make_unique<mujoco::Registry>(m, config, config_path, options.names);
  return out;
}

// The run record's geom id of each geom of a decomposed scene's model (decomposed_scene.h): the
// scene as given has no pieces, and each piece follows the geom it replaces in its body.
std::vector<int> record_geom_ids(const mjModel* m) {
  std::vector<int> ids(static_cast<std::size_t>(m->ngeom));
  int pieces = 0;
  int original = -1;
  for (int g = 0; g < m->ngeom; ++g) {
    if (is_piece(m, g)) {
      ++pieces;
      ids[static_cast<std::size_t>(g)] = original;
    } else {
      original = g - pieces;
      ids[static_cast<std::size_t>(g)] = original;
    }
  }
  return ids;
}

// The run record's header of a grasp of `m` by `run` (run_record.h).
RunHeader record_header(const mjModel* m, const HandRun& run, const GraspOptions& options,
                        const std::string& scene, bool decomposed) {
  RunHeader h;
  h.scene = scene;
  h.simulator =
      std::string("MuJoCo ") + GRASPCD_MUJOCO_VERSION + " with graspcd " + GRASPCD_VERSION;
  const bool multiccd = (m->opt.enableflags & mjENBL_MULTICCD) != 0;
  const bool exact = options.contact_reuse && *options.contact_reuse == 0;
  h.configuration = !options.configuration.empty() ? options.configuration
                    : decomposed                   ? "decomposed"
                    : options.native               ? "native hull"
                    : exact                        ? "graspcd exact"
                                                   : "graspcd";
  if (options.configuration.empty() && multiccd) h.configuration += " multiccd";
  h.timestep = m->opt.timestep;
  h.nq = m->nq;
  h.nv = m->nv;
  const auto name = [m](int body) {
    const char* n = mj_id2name(m, mjOBJ_BODY, body);
    return std::string(body == 0 || n == nullptr ? "world" : n);
  };
  h.object = name(run.object());
  h.hand = name(run.hand());
  h.support = name(run.support_body());
  h.contacts = true;
  h.noslip_iterations = m->opt.noslip_iterations;
  h.multiccd = multiccd;
  h.max_steps = options.max_steps;
  h.six_directions = options.six_directions;
  return h;
}

// How the run collided the object with its support, for the support's warning (verdicts.h):
// served by graspcd, or MuJoCo's own collision of the pair and how many contacts it makes.
std::string support_cause(const mjModel* m, const mujoco::Registry* registry, int object,
                          int support) {
  const int root = m->body_rootid[object];
  const int support_root = support > 0 ? m->body_rootid[support] : 0;
  for (int o = 0; o < m->ngeom; ++o) {
    if (m->body_rootid[m->geom_bodyid[o]] != root) continue;
    for (int g = 0; g < m->ngeom; ++g) {
      const int body = m->geom_bodyid[g];
      const bool of_support = support > 0 ? m->body_rootid[body] == support_root : body == 0;
      if (!of_support || !may_collide(m, o, g)) continue;
      if (registry != nullptr && registry->find_pair(o, g) >= 0) {
        return "graspcd serves the object's contacts with " + geom_label(m, g) +
               " (its pair config)";
      }
      const bool multiccd = (m->opt.enableflags & mjENBL_MULTICCD) != 0;
      if (m->geom_type[g] == mjGEOM_PLANE) {
        return "MuJoCo collides the object with " + geom_label(m, g) +
               " itself (a plane against the object's convex hull)";
      }
      return "MuJoCo collides the object with " + geom_label(m, g) +
             " itself, convex hull against convex hull, " +
             (multiccd ? "up to 5 contacts per step (multiccd)"
                       : "one contact per step (multiccd off: grasp --multiccd gives up to 5, "
                         "a served pair in the pair config the true meshes)");
    }
  }
  return "the object's contact with its support";
}

}  // namespace

// What a scene keeps from one grasp to the next. Declared in the order it is built: destroyed
// the other way round, the attachment before the registry, the registry before the model.
struct GraspScene::Loaded {
  Loaded(const std::string& scene_path, const GraspOptions& options)
      : errors(scene_path, options.names) {}
  // MuJoCo's errors name the scene (mujoco_messages.h) while the scene lives.
  mujoco::ScopedMujocoErrors errors;
  mujoco::ModelPtr model;
  mujoco::ModelPtr truth;  // a decomposed scene's true object, else null
  std::unique_ptr<SurfaceCache> surfaces;
  std::unique_ptr<mujoco::ScopedInstall> install_guard;
  GraspConfig config;
  std::string config_path;
  // Declared after the registry, so that it detaches before the registry goes, on a throw too.
  mujoco::Attachment attached;
  mujoco::DataPtr data;
  bool fresh = true;  // data as mj_makeData left it: no reset needed before the first grasp
};

GraspScene::GraspScene(const std::string& scene_path, const GraspOptions& options)
    : options_(options),
      scene_path_(scene_path),
      loaded_(std::make_unique<Loaded>(scene_path, options)) {
  Loaded& l = *loaded_;
  CostTimer compile(&setup_cost_, CostPart::kCompile);
  l.model = mujoco::load_model(scene_path, options.names);
  mjModel* m = l.model.get();
  // A finer step, the drive the same in time: K times the physics steps per grasp step; the
  // squeeze, lift and hold count their steps from the time step (hand_run.h).
  const int divisor = std::max(1, options.timestep_divisor);
  m->opt.timestep /= divisor;
  options_.physics_steps_per_grasp_step = options.physics_steps_per_grasp_step * divisor;
  if (options.noslip_iterations) m->opt.noslip_iterations = *options.noslip_iterations;
  if (options.multiccd) {
    if (*options.multiccd) {
      m->opt.enableflags |= mjENBL_MULTICCD;
    } else {
      m->opt.enableflags &= ~static_cast<int>(mjENBL_MULTICCD);
    }
  }
  // A decomposed scene's true object (its start and its penetration are the true meshes').
  bool decomposed = false;
  for (int g = 0; g < m->ngeom && !decomposed; ++g) decomposed = is_piece(m, g);
  if (decomposed) l.truth = true_object_model(m);
  compile.stop();

  const CostTimer trees(&setup_cost_, CostPart::kTrees);
  l.surfaces = std::make_unique<SurfaceCache>(m);
  l.config_path =
      options.config_path.empty() ? mujoco::pair_config_path(scene_path) : options.config_path;
  l.config = load_grasp_config(m, l.config_path, options);
  if (l.config.registry) {
    l.install_guard = std::make_unique<mujoco::ScopedInstall>();
    l.attached = mujoco::attach(*l.config.registry);
  }
  l.data.reset(mj_makeData(m));
}

GraspScene::~GraspScene() = default;

mjModel* GraspScene::model() { return loaded_->model.get(); }

void GraspScene::place_free_body(int body, const std::array<double, 3>& pos,
                                 const std::array<double, 4>& quat) {
  mjModel* m = loaded_->model.get();
  const int joint = m->body_jntadr[body];
  if (m->nkey > 0 || m->body_jntnum[body] != 1 || m->jnt_type[joint] != mjJNT_FREE) {
    throw std::invalid_argument(
        "place_free_body: the body must have one free joint and the scene no keyframe");
  }
  const CostTimer timer(&setup_cost_, CostPart::kPlacement);
  // The compiler's normalisation (user_util.cc, mjuu_normvec): each component over the norm.
  std::array<double, 4> q = quat;
  const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (!(norm >= mjMINVAL)) throw std::invalid_argument("place_free_body: a zero quaternion");
  for (double& x : q) x /= norm;
  const int adr = m->jnt_qposadr[joint];
  for (mjModel* model : {m, loaded_->truth.get()}) {
    if (model == nullptr) continue;
    for (int k = 0; k < 3; ++k) {
      model->body_pos[3 * body + k] = pos[static_cast<std::size_t>(k)];
      model->qpos0[adr + k] = model->qpos_spring[adr + k] = pos[static_cast<std::size_t>(k)];
    }
    for (int k = 0; k < 4; ++k) {
      model->body_quat[4 * body + k] = q[static_cast<std::size_t>(k)];
      model->qpos0[adr + 3 + k] = model->qpos_spring[adr + 3 + k] = q[static_cast<std::size_t>(k)];
    }
  }
  // What the compiler computes from qpos0 (the constants that depend on the configuration), on
  // the scene's data, which the next grasp resets.
  mj_setConst(m, loaded_->data.get());
  loaded_->fresh = false;
}

GraspResult GraspScene::grasp() {
  Refusal refusal;
  std::optional<GraspResult> result = grasp_if_valid(&refusal);
  if (!result) throw *refusal.error;
  return std::move(*result);
}

// Paper section 9 (the grasp) with the computed-torque law of section 7, eq. (12)-(16); the
// phases are described in grasp.h.
std::optional<GraspResult> GraspScene::grasp_if_valid(Refusal* refusal) {
  Loaded& l = *loaded_;
  const GraspOptions& options = options_;
  const mjModel* m = l.model.get();
  mjData* d = l.data.get();
  mujoco::Registry* registry = l.config.registry.get();
  GraspResult result;
  result.cost = setup_cost_;  // the scene's own parts go with its first grasp
  setup_cost_ = GraspCost{};
  if (registry) result.warnings = registry->warnings();
  result.scene = scene_path_;
  result.native = options.native;
  result.method = options.native ? "native" : method_name(l.config.registry_config.method);
  result.noslip_iterations = m->opt.noslip_iterations;
  result.timestep = m->opt.timestep;
  result.physics_steps_per_grasp_step = options.physics_steps_per_grasp_step;
  result.multiccd = (m->opt.enableflags & mjENBL_MULTICCD) != 0;

  // A hand driven through its own actuators (the config's "grasp" section), or ours.
  std::unique_ptr<HandRun> run;
  if (l.config.drive) {
    run = std::make_unique<DrivenRun>(m, d, registry, *l.config.drive, scene_path_,
                                      options.names.file(l.config_path));
  } else {
    run = std::make_unique<GraspRun>(m, d, registry, options, scene_path_);
  }
  // A grasp after the first starts from a state as mj_makeData makes it, and the served pairs
  // forget what they carried over from the last one.
  if (!l.fresh) {
    const CostTimer timer(&result.cost, CostPart::kPlacement);
    mj_resetData(m, d);
    if (registry) registry->forget_fronts(d);
  }
  l.fresh = false;
  const bool decomposed = l.truth != nullptr;
  // The run record (GraspOptions::write_run), written whole or not at all; a refused start and a
  // simulation gone non-finite end it with their message.
  std::unique_ptr<RunRecordWriter> record;
  if (!options.write_run.empty()) {
    const std::string scene = decomposed ? options.names.scene : scene_path_;
    record = std::make_unique<RunRecordWriter>(
        options.write_run, record_header(m, *run, options, scene, decomposed),
        decomposed ? record_geom_ids(m) : std::vector<int>{});
    run->set_record(record.get());
  }
  // The start state: the scene's first keyframe when it has one (a hand shaped before the grasp,
  // e.g. a gripper half closed with a pad through a mug's handle), else the model's qpos0. The
  // keyframe's time starts MuJoCo's clock, on which the events are reported: before 0 it is
  // refused (grasp.h).
  if (m->nkey > 0) {
    if (m->key_time[0] < 0) {
      const char* name = m->names + m->name_keyadr[0];
      std::ostringstream message;
      message << "the first keyframe" << (*name ? std::string(" '") + name + "'" : "")
              << ", where the grasp starts, has time=\"" << m->key_time[0]
              << "\": the grasp's clock starts at the keyframe's time and cannot start before 0 "
                 "(give time=\"0\" or leave it out)";
      throw options.names.refusal(scene_path_, 0, message.str());
    }
    mj_resetDataKeyframe(m, d, 0);
  }
  CostTimer start_check(&result.cost, CostPart::kStartCheck);
  mj_forward(m, d);
  OpenMeshes open;
  if (l.config.drive) open.hand_body = mj_name2id(m, mjOBJ_BODY, l.config.drive->hand.c_str());
  if (registry) {
    open.served = [registry](int g) { return registry->geom_tree(g) != nullptr; };
  }
  *refusal = start_refusal(m, d, run->object(), scene_path_, options, l.truth.get(), open,
                           l.surfaces.get());
  start_check.stop();
  if (refusal->error) {
    if (record) record->end({"", "cannot start", refusal->error->what()});
    refusal->cost = result.cost;
    return std::nullopt;
  }
  if (l.truth) run->set_truth(l.truth.get());
  run->set_surfaces(l.surfaces.get());
  run->set_mutable_model(l.model.get());
  if (registry) registry->reset_stats();
  try {
    run->run(options, result);
  } catch (const std::runtime_error& e) {
    if (record) record->end({"", "nonfinite", e.what()});
    throw;
  }
  if (record) record->end({result.closing, "ok", ""});
  if (options.true_penetration) {
    result.support_warning =
        support_warning(result, support_cause(m, registry, run->object(), run->support_body()));
    if (!result.support_warning.empty()) {
      graspcd::warnings().add("support_penetration",
                              options.names.file(scene_path_) + ": " + result.support_warning);
    }
  }
  return result;
}

GraspResult run_grasp(const std::string& scene_path, const GraspOptions& options) {
  GraspScene scene(scene_path, options);
  return scene.grasp();
}

}  // namespace graspcd::grasp
