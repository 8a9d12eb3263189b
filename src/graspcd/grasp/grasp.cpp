#include "graspcd/grasp/grasp.h"

#include <algorithm>
#include <filesystem>
#include <memory>
#include <string>

#include "graspcd/grasp/decomposed_pieces.h"
#include "graspcd/grasp/drive_config.h"
#include "graspcd/grasp/driven_run.h"
#include "graspcd/grasp/grasp_run.h"
#include "graspcd/grasp/hand_run.h"
#include "graspcd/grasp/start_check.h"
#include "graspcd/mujoco/collision.h"
#include "graspcd/mujoco/mujoco_messages.h"
#include "graspcd/mujoco/mujoco_ptr.h"
#include "graspcd/mujoco/registry.h"

namespace graspcd::grasp {

namespace {

// The start rule (grasp.h, start_check.h) as bad input naming the scene: the scene itself, its
// object's true meshes (for a decomposed scene, the model with the object as it was) checked by
// check_start_state; then, under native collision, the geometry MuJoCo collides (the hulls of
// the meshes, or of the pieces) by check_hull_start.
// `truth`: the model with the true object (true_object_model) for a decomposed scene, else null.
void throw_if_bad_start(const mjModel* m, const mjData* d, int object, const std::string& scene,
                        const GraspOptions& options, const mjModel* truth) {
  const bool decomposed = truth != nullptr;
  const mujoco::SceneNames& names = options.names;
  const std::string problem = check_start_state(decomposed ? truth : m, d, object, names);
  if (!problem.empty()) {
    throw names.refusal(scene, 0, "the start state is not valid: " + problem);
  }
  if (!options.native) return;
  const std::string hull = check_hull_start(m, d, object);
  if (!hull.empty()) {
    throw names.refusal(scene, 0,
                        std::string("cannot start with ") +
                            (decomposed ? "--decomposed" : "--native") + ": " + hull +
                            " (a limit of the " + (decomposed ? "pieces" : "hull") +
                            ", not of the scene; graspcd's contacts start this scene)");
  }
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

}  // namespace

// Paper section 9 (the grasp) with the computed-torque law of section 7, eq. (12)-(16); the
// phases are described in grasp.h.
GraspResult run_grasp(const std::string& scene_path, const GraspOptions& given) {
  // MuJoCo's errors name the scene (mujoco_messages.h).
  const mujoco::ScopedMujocoErrors mujoco_errors(scene_path, given.names);
  const auto model = mujoco::load_model(scene_path, given.names);
  // A finer step, the drive the same in time: K times the physics steps per grasp step; the
  // squeeze, lift and hold count their steps from the time step (hand_run.h).
  GraspOptions options = given;
  const int divisor = std::max(1, given.timestep_divisor);
  model->opt.timestep /= divisor;
  options.physics_steps_per_grasp_step = given.physics_steps_per_grasp_step * divisor;
  if (options.noslip_iterations) model->opt.noslip_iterations = *options.noslip_iterations;
  if (options.multiccd) {
    if (*options.multiccd) {
      model->opt.enableflags |= mjENBL_MULTICCD;
    } else {
      model->opt.enableflags &= ~static_cast<int>(mjENBL_MULTICCD);
    }
  }
  const mjModel* m = model.get();
  // A decomposed scene's true object (its start and its penetration are the true meshes').
  bool decomposed = false;
  for (int g = 0; g < m->ngeom && !decomposed; ++g) decomposed = is_piece(m, g);
  const mujoco::ModelPtr truth = decomposed ? true_object_model(m) : nullptr;

  const std::string config_path =
      options.config_path.empty() ? mujoco::pair_config_path(scene_path) : options.config_path;
  std::unique_ptr<mujoco::ScopedInstall> install_guard;
  GraspConfig loaded = load_grasp_config(m, config_path, options);
  std::unique_ptr<mujoco::Registry>& registry = loaded.registry;
  const mujoco::RegistryConfig& config = loaded.registry_config;
  const std::optional<DriveConfig>& drive = loaded.drive;
  // Declared after the registry, so that it detaches before the registry goes, on a throw too.
  mujoco::Attachment attached;
  if (registry) {
    install_guard = std::make_unique<mujoco::ScopedInstall>();
    attached = mujoco::attach(*registry);
  }
  GraspResult result;
  if (registry) result.warnings = registry->warnings();

  mujoco::DataPtr data(mj_makeData(m));
  mjData* d = data.get();
  result.scene = scene_path;
  result.native = options.native;
  result.method = options.native ? "native" : method_name(config.method);
  result.noslip_iterations = m->opt.noslip_iterations;
  result.timestep = m->opt.timestep;
  result.physics_steps_per_grasp_step = options.physics_steps_per_grasp_step;
  result.multiccd = (m->opt.enableflags & mjENBL_MULTICCD) != 0;

  // A hand driven through its own actuators (the config's "grasp" section), or ours.
  std::unique_ptr<HandRun> run;
  if (drive) {
    run = std::make_unique<DrivenRun>(m, d, registry.get(), *drive, scene_path,
                                      options.names.file(config_path));
  } else {
    run = std::make_unique<GraspRun>(m, d, registry.get(), options, scene_path);
  }
  // The start state: the scene's first keyframe when it has one (a hand shaped before the grasp,
  // e.g. a gripper half closed with a pad through a mug's handle), else the model's qpos0.
  if (m->nkey > 0) mj_resetDataKeyframe(m, d, 0);
  mj_forward(m, d);
  throw_if_bad_start(m, d, run->object(), scene_path, options, truth.get());
  if (truth) run->set_truth(truth.get());
  if (registry) registry->reset_stats();
  run->run(options, result);
  attached.release();
  registry.reset();  // before the model goes
  return result;
}

}  // namespace graspcd::grasp
