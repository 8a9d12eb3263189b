#include "graspcd/grasp/grasp.h"

#include <filesystem>
#include <memory>
#include <string>

#include "graspcd/grasp/decomposed_pieces.h"
#include "graspcd/grasp/drive_config.h"
#include "graspcd/grasp/driven_run.h"
#include "graspcd/grasp/grasp_run.h"
#include "graspcd/grasp/hand_run.h"
#include "graspcd/grasp/run_record.h"
#include "graspcd/grasp/start_check.h"
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

// Paper section 9 (the grasp) with the computed-torque law of section 7, eq. (12)-(16); the
// phases are described in grasp.h.
GraspResult run_grasp(const std::string& scene_path, const GraspOptions& options) {
  // MuJoCo's errors name the scene (mujoco_messages.h).
  const mujoco::ScopedMujocoErrors mujoco_errors(scene_path, options.names);
  const auto model = mujoco::load_model(scene_path, options.names);
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
  result.multiccd = (m->opt.enableflags & mjENBL_MULTICCD) != 0;

  // A hand driven through its own actuators (the config's "grasp" section), or ours.
  std::unique_ptr<HandRun> run;
  if (drive) {
    run = std::make_unique<DrivenRun>(m, d, registry.get(), *drive, scene_path,
                                      options.names.file(config_path));
  } else {
    run = std::make_unique<GraspRun>(m, d, registry.get(), options, scene_path);
  }
  // The run record (GraspOptions::write_run), written whole or not at all; a refused start and a
  // simulation gone non-finite end it with their message.
  std::unique_ptr<RunRecordWriter> record;
  if (!options.write_run.empty()) {
    const std::string scene = decomposed ? options.names.scene : scene_path;
    record = std::make_unique<RunRecordWriter>(
        options.write_run, record_header(m, *run, options, scene, decomposed),
        decomposed ? record_geom_ids(m) : std::vector<int>{});
    run->set_record(record.get());
  }
  // The start state: the scene's first keyframe when it has one (a hand shaped before the grasp,
  // e.g. a gripper half closed with a pad through a mug's handle), else the model's qpos0.
  if (m->nkey > 0) mj_resetDataKeyframe(m, d, 0);
  mj_forward(m, d);
  try {
    throw_if_bad_start(m, d, run->object(), scene_path, options, truth.get());
  } catch (const io::InputError& e) {
    if (record) record->end({"", "cannot start", e.what()});
    throw;
  }
  if (truth) run->set_truth(truth.get());
  run->set_mutable_model(model.get());
  if (registry) registry->reset_stats();
  try {
    run->run(options, result);
  } catch (const std::runtime_error& e) {
    if (record) record->end({"", "nonfinite", e.what()});
    throw;
  }
  if (record) record->end({result.closing, "ok", ""});
  if (options.true_penetration) {
    result.support_warning = support_warning(
        result, support_cause(m, registry.get(), run->object(), run->support_body()));
    if (!result.support_warning.empty()) {
      graspcd::warnings().add("support_penetration",
                              options.names.file(scene_path) + ": " + result.support_warning);
    }
  }
  attached.release();
  registry.reset();  // before the model goes
  return result;
}

}  // namespace graspcd::grasp
