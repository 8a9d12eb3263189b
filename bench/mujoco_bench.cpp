// mj_step on the triangle hand (mjcf/hand_triangles.xml) with the fingers closed a little, so
// that they touch the cup:
//   (a) Plain              MuJoCo alone, graspcd not installed;
//   (b) InstalledNoRegistry   graspcd's function in the 21 entries, no registry attached: every
//                             call delegated to MuJoCo's original;
//       InstalledOtherModel   the same with a registry of another model (hand_boxes) attached, so
//                             each call scans the attached models before delegating;
//   (c) Served             the scene's pairs.json attached: finger-object pairs by graspcd.
// (b)/(a) is graspcd's overhead on the pairs it does not serve. NoopDirect and
// NoopDelegated measure that overhead per call without MuJoCo's work; start-up prints the calls
// per step, so (b) - (a) can be predicted from them.
//
// Every iteration restores the same state (qpos, qvel, act, ctrl, warm start, time) and runs one
// mj_step, so all variants step the same configuration. The closing angle is the first multiple
// of 0.01 rad at which the served pairs report finger-cup contact (mj_forward, graspcd on),
// plus 0.01 rad; it is found once, before the benchmarks.
//
// Run: build/bench/graspcd_mujoco_bench --benchmark_repetitions=5
#include <benchmark/benchmark.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "graspcd/grasp/grasp.h"
#include "graspcd/mujoco/collision.h"
#include "graspcd/mujoco/mujoco_ptr.h"
#include "graspcd/mujoco/registry.h"

namespace {

using graspcd::mujoco::DataPtr;
using graspcd::mujoco::ModelPtr;
using graspcd::mujoco::Registry;

const std::string kMjcf = GRASPCD_MJCF_DIR;

ModelPtr load(const std::string& name) {
  char error[1024] = "";
  ModelPtr m(mj_loadXML((kMjcf + "/" + name).c_str(), nullptr, error, sizeof(error)));
  if (!m) throw std::runtime_error(kMjcf + "/" + name + ": " + error);
  return m;
}

long& call_count() {
  static long n = 0;
  return n;
}
int counting_collision(const mjModel* m, const mjData* d, mjContact* con, int g1, int g2,
                       mjtNum margin) {
  ++call_count();
  return graspcd::mujoco::collide_geoms(m, d, con, g1, g2, margin);
}

// The triangle hand, its closed state, and a model of another scene for variant (b).
struct Bench {
  ModelPtr model;
  ModelPtr other;
  std::string config_path = kMjcf + "/hand_triangles.pairs.json";
  std::vector<mjtNum> qpos;
  double angle = 0;
  int finger_contacts = 0;  // finger-object contacts served by graspcd at `angle`
  int native_finger_contacts = 0;

  static Bench& get() {
    static Bench b;
    return b;
  }

  // Finger-object contacts at the current state of d.
  int finger_object_contacts(const mjData* d) const {
    const mjModel* m = model.get();
    std::set<int> fingers;
    for (const std::string& s : graspcd::grasp::finger_segment_names()) {
      fingers.insert(mj_name2id(m, mjOBJ_GEOM, s.c_str()));
    }
    int n = 0;
    for (int i = 0; i < d->ncon; ++i) {
      const mjContact& c = d->contact[i];
      n += fingers.count(c.geom1) != fingers.count(c.geom2) && m->geom_bodyid[c.geom1] != 0 &&
           m->geom_bodyid[c.geom2] != 0;
    }
    return n;
  }

  void set_fingers(mjData* d, double a) const {
    const mjModel* m = model.get();
    mj_resetData(m, d);
    for (const std::string& s : graspcd::grasp::finger_segment_names()) {
      d->qpos[m->jnt_qposadr[mj_name2id(m, mjOBJ_JOINT, s.c_str())]] = a;
    }
  }

 private:
  Bench() : model(load("hand_triangles.xml")), other(load("hand_boxes.xml")) {
    const mjModel* m = model.get();
    DataPtr d(mj_makeData(m));
    {
      graspcd::mujoco::ScopedInstall install;
      Registry registry(m, graspcd::mujoco::load_registry_config(config_path), config_path);
      const graspcd::mujoco::Attachment attached = graspcd::mujoco::attach(registry);
      for (int k = 0; k <= 160 && finger_contacts == 0; ++k) {
        angle = 0.01 * k + 0.01;
        set_fingers(d.get(), 0.01 * k);
        mj_forward(m, d.get());
        if (finger_object_contacts(d.get()) == 0) continue;
        set_fingers(d.get(), angle);
        mj_forward(m, d.get());
        finger_contacts = finger_object_contacts(d.get());
      }
    }
    if (finger_contacts == 0) throw std::runtime_error("the fingers never touch the cup");
    qpos.assign(d->qpos, d->qpos + m->nq);
    mj_forward(m, d.get());
    native_finger_contacts = finger_object_contacts(d.get());
    std::printf("closing angle %.2f rad: %d finger-object contacts served, %d natively\n", angle,
                finger_contacts, native_finger_contacts);
    // Calls into graspcd's function per mj_step at this state (none served).
    {
      graspcd::mujoco::ScopedInstall install;
      std::vector<mjfCollision*> ours;
      for (int t1 = 0; t1 < mjNGEOMTYPES; ++t1) {
        for (int t2 = 0; t2 < mjNGEOMTYPES; ++t2) {
          if (mjCOLLISIONFUNC[t1][t2] == &graspcd::mujoco::collide_geoms) {
            ours.push_back(&mjCOLLISIONFUNC[t1][t2]);
          }
        }
      }
      for (mjfCollision* e : ours) *e = &counting_collision;
      set_fingers(d.get(), angle);
      call_count() = 0;
      mj_step(m, d.get());
      for (mjfCollision* e : ours) *e = &graspcd::mujoco::collide_geoms;
      std::printf("calls into graspcd's function per mj_step (installed, nothing served): %ld\n",
                  call_count());
    }
  }
};

// Steps from the same closed state every iteration.
void step_loop(benchmark::State& state, const Registry* registry) {
  Bench& b = Bench::get();
  const mjModel* m = b.model.get();
  DataPtr data(mj_makeData(m));
  mjData* d = data.get();
  b.set_fingers(d, b.angle);
  mj_forward(m, d);
  const std::vector<mjtNum> warm(d->qacc_warmstart, d->qacc_warmstart + m->nv);
  long contacts = 0, steps = 0;
  for (auto _ : state) {
    mju_copy(d->qpos, b.qpos.data(), m->nq);
    mju_zero(d->qvel, m->nv);
    mju_zero(d->act, m->na);
    mju_zero(d->ctrl, m->nu);
    mju_copy(d->qacc_warmstart, warm.data(), m->nv);
    d->time = 0;
    mj_step(m, d);
    contacts += d->ncon;
    ++steps;
  }
  state.counters["contacts"] =
      benchmark::Counter(static_cast<double>(contacts), benchmark::Counter::kAvgIterations);
  if (registry) {
    const auto per_step = [&](double x) {
      return benchmark::Counter(x / static_cast<double>(steps));
    };
    const graspcd::mujoco::BridgeStats& st = registry->stats();
    state.counters["served_calls"] = per_step(static_cast<double>(st.calls));
    state.counters["detect_us"] = per_step(static_cast<double>(st.detection_ns) / 1e3);
    state.counters["contact_us"] = per_step(static_cast<double>(st.contact_ns) / 1e3);
  }
}

void BM_StepPlain(benchmark::State& state) { step_loop(state, nullptr); }

void BM_StepInstalledNoRegistry(benchmark::State& state) {
  graspcd::mujoco::ScopedInstall install;
  step_loop(state, nullptr);
}

void BM_StepInstalledOtherModel(benchmark::State& state) {
  Bench& b = Bench::get();
  const std::string other_config = kMjcf + "/hand_boxes.pairs.json";
  graspcd::mujoco::ScopedInstall install;
  Registry other(b.other.get(), graspcd::mujoco::load_registry_config(other_config), other_config);
  const graspcd::mujoco::Attachment attached = graspcd::mujoco::attach(other);
  step_loop(state, &other);
}

// With exact contacts every step ("contact_reuse" 0): this loop restores one state and steps it
// again, so the default's reused contacts would answer every call after the first (a cache across
// steps made to look free); BM_WholeGrasp times the default on consecutive steps.
void BM_StepServed(benchmark::State& state) {
  Bench& b = Bench::get();
  graspcd::mujoco::ScopedInstall install;
  graspcd::mujoco::RegistryConfig config = graspcd::mujoco::load_registry_config(b.config_path);
  config.contact_reuse = 0.0;
  Registry registry(b.model.get(), config, b.config_path);
  const graspcd::mujoco::Attachment attached = graspcd::mujoco::attach(registry);
  step_loop(state, &registry);
}

// graspcd's cost per delegated call, without MuJoCo's work: the mesh-mesh original replaced by
// a function that does nothing, called directly (NoopDirect) and through graspcd's function
// with no registry for the model (NoopDelegated). Their difference times the delegated calls
// per step (printed at start-up) is the expected (b) - (a).
int noop_collision(const mjModel*, const mjData*, mjContact*, int, int, mjtNum) { return 0; }

std::pair<int, int> finger_and_cup(const mjModel* m) {
  return {mj_name2id(m, mjOBJ_GEOM, "finger1_C"), mj_name2id(m, mjOBJ_GEOM, "object")};
}

void BM_NoopDirect(benchmark::State& state) {
  Bench& b = Bench::get();
  const mjModel* m = b.model.get();
  DataPtr d(mj_makeData(m));
  mjContact con[mjMAXCONPAIR];
  const auto [g1, g2] = finger_and_cup(m);
  mjfCollision volatile f = &noop_collision;
  for (auto _ : state) benchmark::DoNotOptimize(f(m, d.get(), con, g1, g2, 0));
}

void BM_NoopDelegated(benchmark::State& state) {
  Bench& b = Bench::get();
  const mjModel* m = b.model.get();
  DataPtr d(mj_makeData(m));
  mjContact con[mjMAXCONPAIR];
  const auto [g1, g2] = finger_and_cup(m);
  const mjfCollision saved = mjCOLLISIONFUNC[mjGEOM_MESH][mjGEOM_MESH];
  mjCOLLISIONFUNC[mjGEOM_MESH][mjGEOM_MESH] = &noop_collision;
  {
    graspcd::mujoco::ScopedInstall install;
    mjfCollision volatile f = mjCOLLISIONFUNC[mjGEOM_MESH][mjGEOM_MESH];  // graspcd's
    for (auto _ : state) benchmark::DoNotOptimize(f(m, d.get(), con, g1, g2, 0));
  }
  mjCOLLISIONFUNC[mjGEOM_MESH][mjGEOM_MESH] = saved;
}

// Whole grasps, as users run them: the scene's grasp (close, squeeze, settle, lift,
// hold; graspcd/grasp/grasp.h) from its start, every physics step in sequence, served or native.
// The time is the grasp driver's wall clock of its physics steps alone (mj_step1, control,
// mj_step2; GraspResult::step_wall_ms), so loading the model and building the trees are not in
// it, and any state carried from step to step pays its way. One iteration is one whole grasp;
// the reported time is per physics step. Counters: physics steps, most finger-object contacts
// in one step, and whether the object was held. Variants: "native" (MuJoCo's own collision),
// "native-multiccd" (the same with MuJoCo's multi-point convex collision, mjENBL_MULTICCD: up to 5
// contacts per convex pair instead of 1; grasp --multiccd),
// "served" (graspcd, the config as shipped: each tree query restarted from its front, a touching
// pair's contacts refreshed, not queried, while it moves less than the default "contact_reuse",
// 20 um; registry.h), "served-exact" (the same with "contact_reuse" 0: exact contacts every step,
// grasp --exact) and "served-roots" (exact, with "front_list" off: every query from the roots).

void whole_grasp(benchmark::State& state, const std::string& scene, const std::string& variant) {
  graspcd::grasp::GraspOptions options;
  options.native = variant == "native" || variant == "native-multiccd";
  if (variant == "native-multiccd") options.multiccd = true;
  if (variant == "served-exact" || variant == "served-roots") options.contact_reuse = 0.0;
  if (variant == "served-roots") options.front_list = false;
  long steps = 0;
  graspcd::grasp::GraspResult r;
  for (auto _ : state) {
    r = graspcd::grasp::run_grasp(kMjcf + "/" + scene, options);
    state.SetIterationTime(r.step_wall_ms / 1e3);  // seconds per physics step
    steps = r.physics_steps;
  }
  state.counters["physics_steps"] = static_cast<double>(steps);
  state.counters["max_contacts"] = r.max_contacts;
  state.counters["held"] = r.held ? 1 : 0;
  state.counters["mean_contacts"] = r.mean_contacts;
  state.counters["reused_calls"] = static_cast<double>(r.reused_calls);
}

// The grasps of examples 1-3, the triangle hand and a real Robotiq scene (whose meshes come from
// ../shared/models).
const char* const kGraspScenes[] = {"example1.xml", "example2.xml", "example3.xml",
                                    "hand_triangles.xml", "real_robotiq_cup.xml"};

// One benchmark per repetition ("BM_WholeGrasp/SCENE/VARIANT/rep:K", each run once), registered
// repetition by repetition and scene by scene, so that a scene's native and served grasps of one
// repetition run one after the other and a slow moment of the machine falls on both, not on all
// repetitions of one variant (Google Benchmark runs one benchmark's repetitions back to back).
// perf_summary.py folds "/rep:K" back into one benchmark's repetitions.
void register_whole_grasps(int repetitions) {
  for (int k = 0; k < repetitions; ++k) {
    for (const char* scene : kGraspScenes) {
      const std::string name = std::string(scene).substr(0, std::string(scene).size() - 4);
      for (const char* variant :
           {"native", "native-multiccd", "served", "served-exact", "served-roots"}) {
        benchmark::RegisterBenchmark(
            ("BM_WholeGrasp/" + name + "/" + variant + "/rep:" + std::to_string(k)).c_str(),
            [scene, variant](benchmark::State& st) { whole_grasp(st, scene, variant); })
            ->UseManualTime()
            ->Iterations(1)
            ->Repetitions(1)
            ->Unit(benchmark::kMicrosecond);
      }
    }
  }
}

// --benchmark_repetitions=N of the command line (1 when absent): the whole grasps' repetitions.
int requested_repetitions(int argc, char** argv) {
  const std::string key = "--benchmark_repetitions=";
  int n = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind(key, 0) == 0) n = std::max(1, std::atoi(arg.c_str() + key.size()));
  }
  return n;
}

BENCHMARK(BM_StepPlain)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_StepInstalledNoRegistry)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_StepInstalledOtherModel)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_StepServed)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_NoopDirect);
BENCHMARK(BM_NoopDelegated);

}  // namespace

int main(int argc, char** argv) {
  register_whole_grasps(requested_repetitions(argc, argv));
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
