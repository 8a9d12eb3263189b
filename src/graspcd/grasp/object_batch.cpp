#include "graspcd/grasp/object_batch.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <utility>

#include "graspcd/io/output_files.h"
#include "graspcd/mujoco/pair_config.h"

namespace graspcd::grasp {

namespace {

const std::vector<std::string> kAxes = {"x", "y", "z", "-x", "-y", "-z"};

// A uniform number in [0, 1) from the generator's top 53 bits.
double uniform(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

}  // namespace

std::vector<ObjectPlacement> draw_placements(const ObjectPlacement& base,
                                             const BatchPlacementOptions& options) {
  if (options.count < 1) throw std::invalid_argument("the placements must be at least 1");
  if (!(options.max_offset >= 0) || !std::isfinite(options.max_offset)) {
    throw std::invalid_argument("the largest offset must be finite and not negative");
  }
  const std::vector<std::string>& ups = options.ups.empty() ? kAxes : options.ups;
  const std::vector<std::string> known = {"x", "y", "z", "-x", "-y", "-z", "+x", "+y", "+z"};
  for (const std::string& up : ups) {
    if (std::find(known.begin(), known.end(), up) == known.end()) {
      throw std::invalid_argument("the up axis must be x, y, z, -x, -y or -z, not '" + up + "'");
    }
  }
  std::mt19937_64 rng(options.seed);
  std::vector<ObjectPlacement> out;
  out.reserve(static_cast<std::size_t>(options.count));
  for (int k = 0; k < options.count; ++k) {
    // Four draws per placement whatever is fixed, so that a placement depends on its index only.
    const double side = uniform(rng);
    const double yaw = uniform(rng);
    const double angle = uniform(rng);
    const double radius = uniform(rng);
    ObjectPlacement p = base;
    p.pose.reset();
    p.up = ups[std::min(ups.size() - 1,
                        static_cast<std::size_t>(side * static_cast<double>(ups.size())))];
    p.yaw_degrees = options.yaw_degrees ? *options.yaw_degrees : 360 * yaw;
    const double r = options.max_offset * std::sqrt(radius);
    p.offset = {r * std::cos(2 * M_PI * angle), r * std::sin(2 * M_PI * angle)};
    out.push_back(p);
  }
  return out;
}

struct ObjectBatch::State {
  explicit State(const ObjectRunOptions& options) : run(options) {}
  ObjectRun run;
  std::unique_ptr<ObjectPlacer> placer;
  std::optional<DecomposedScene> decomposed;
  io::CleanupGuard remove_decomposed;
  std::unique_ptr<GraspScene> scene;
  int body = -1;
  GraspCost pending;  // the batch's own parts not yet given to a grasp
};

ObjectBatch::ObjectBatch(const ObjectBatchOptions& options) {
  if (options.first.fit) {
    throw std::invalid_argument("a batch keeps one scale: give --scale, not --fit");
  }
  ObjectRunOptions run = options.run;
  run.write_scene.clear();
  state_ = std::make_unique<State>(run);
  State& s = *state_;
  s.run.write(options.first);
  s.pending += s.run.cost();
  GraspOptions grasp = options.grasp;
  grasp.names = s.run.names();
  std::string scene_path = s.run.scene();
  {
    const CostTimer timer(&s.pending, CostPart::kScene);
    s.placer = std::make_unique<ObjectPlacer>(options.run.file, options.run.hand,
                                              s.run.description().scene.support_raised);
    if (!options.decomposed.empty()) {
      s.decomposed = write_decomposed_scene(scene_path, options.decomposed);
      s.remove_decomposed = io::CleanupGuard(s.decomposed->scene);
      grasp.native = true;
      if (grasp.config_path.empty()) grasp.config_path = mujoco::pair_config_path(scene_path);
      grasp.names.written_scene = s.decomposed->scene;
      grasp.names.scene_context = "with " + options.decomposed + ": " + grasp.names.scene_context;
      scene_path = s.decomposed->scene;
    }
  }
  s.scene = std::make_unique<GraspScene>(scene_path, grasp);
  s.body = mj_name2id(s.scene->model(), mjOBJ_BODY, "object");
  if (s.body < 0) throw std::runtime_error(scene_path + ": no body 'object'");
}

ObjectBatch::~ObjectBatch() = default;

BatchGrasp ObjectBatch::grasp(const ObjectPlacement& placement) {
  State& s = *state_;
  BatchGrasp out;
  out.placement = placement;
  GraspCost cost = s.pending;
  s.pending = GraspCost{};
  {
    const CostTimer timer(&cost, CostPart::kPlacement);
    out.placed = s.placer->place(placement);
  }
  s.scene->place_free_body(s.body, out.placed.pos, out.placed.quat);
  GraspScene::Refusal refusal;
  std::optional<GraspResult> result = s.scene->grasp_if_valid(&refusal);
  if (!result) {
    out.outcome = refusal.hull ? BatchOutcome::kCannotStart : BatchOutcome::kSkipped;
    out.refusal = refusal.error->what();
    out.result.cost = refusal.cost;
  } else {
    out.result = std::move(*result);
  }
  out.result.cost += cost;
  out.result.scene = s.run.description().file;
  return out;
}

const ObjectRunDescription& ObjectBatch::description() const { return state_->run.description(); }

const DecomposedScene* ObjectBatch::decomposed() const {
  return state_->decomposed ? &*state_->decomposed : nullptr;
}

}  // namespace graspcd::grasp
