// The floor of a served physics step: what a whole grasp's step would cost if graspcd's part were
// only its necessary work,
//   floor = MuJoCo's own step with the same contacts                        (a)
//         + intersecting triangle pairs x one certified triangle test       (b)
//         + kept contacts x one contact written                             (c)
// against the served step and the native one (docs/performance.md, "The floor of a served step").
//
// Per scene, the grasp (graspcd/grasp/grasp.h, the scene's config with exact contacts every step,
// "contact_reuse" 0: the floor is that of an exact query; BM_WholeGrasp times the default) runs
// once served with a recording collision function in graspcd's entries of mjCOLLISIONFUNC: every
// served call, in order, with its geoms' placements, the contacts it returned, and, for calls whose
// tree query found intersecting triangle pairs, those pairs (found again by a fresh detector on the
// same pose, whose count must equal the query's) as the posed triangles the contact routine takes.
// Then, each one whole grasp or one pass over the recording, the time per physics step of:
//   served    the grasp served (graspcd's entries as installed);
//   native    the grasp under MuJoCo's own collision (skipped, with the grasp's message, on a
//             concave scene whose start MuJoCo's convex hulls cannot represent);
//   replay    (a): the grasp served, but every served call answered by copying the recorded
//             contacts of that call. MuJoCo is deterministic, so the same contacts give the same
//             trajectory: every served call's geom placements are compared bit for bit with the
//             recording's, and the result's final measures with the served run's; a replay that
//             differs is an error (and the executable exits 1);
//   tritri    (b), first half: tri_tri_intersect (core/tritri.h, Moller 1997 with certified
//             error bounds) on every recorded intersecting pair;
//   contact   (b), second half: triangle_pair_contact (core/triangle_contact.h) on each;
//   write     (c): write_contact (mujoco/collision_served.h) of every kept contact.
// The last three run their whole recording once per iteration and report that time divided by the
// grasp's physics steps, so every benchmark's time is per physics step, and
// floor = replay + tritri + contact + write, graspcd's part = served - replay (perf_summary.py).
// Counters: physics steps, served calls, intersecting triangle pairs and kept contacts per physics
// step of the served grasp (native: its own physics steps, and its finger-object contacts per
// step), ns per test or write.
//
// Run: build/bench/graspcd_floor_bench --benchmark_repetitions=5
#include <benchmark/benchmark.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "graspcd/core/triangle_contact.h"
#include "graspcd/core/tritri.h"
#include "graspcd/grasp/grasp.h"
#include "graspcd/mujoco/collision.h"
#include "graspcd/mujoco/registry.h"

namespace {

using graspcd::Mat3;
using graspcd::Triangle;
using graspcd::TriContact;
using graspcd::Vec3;

// Every served call queried exactly ("contact_reuse" 0, grasp --exact): the floor is an exact
// query's, and every call has its intersecting pairs to record.
graspcd::grasp::GraspOptions exact_contacts() {
  graspcd::grasp::GraspOptions options;
  options.contact_reuse = 0.0;
  return options;
}
using graspcd::mujoco::Registry;
using Clock = std::chrono::steady_clock;

const std::string kMjcf = GRASPCD_MJCF_DIR;

// One served call as recorded: the geoms, their placements (geom_xpos then geom_xmat of g1, then
// of g2) and its contacts, contacts[first, first + n) of the recording.
struct Call {
  int g1 = 0;
  int g2 = 0;
  std::array<mjtNum, 24> placement{};
  std::size_t first = 0;
  int n = 0;
};

// An intersecting triangle pair as the tree path hands it to the contact routine.
struct TriCase {
  Triangle a;
  Triangle b;  // posed in geom1's frame
  Vec3 fallback = Vec3::UnitZ();
  double max_depth = 0;
  std::uint8_t sharp_a = 7;
  std::uint8_t sharp_b = 7;
};

// A kept contact in geom1's frame, with geom1's placement.
struct WriteCase {
  TriContact c;
  Mat3 R = Mat3::Identity();
  Vec3 p = Vec3::Zero();
};

struct Recording {
  std::vector<Call> calls;
  std::vector<mjContact> contacts;
  std::vector<TriCase> tri_cases;
  std::vector<WriteCase> writes;
  std::uint64_t query_tri_pairs = 0;  // the queries' own count of intersecting triangle pairs
  graspcd::grasp::GraspResult result;
};

std::array<mjtNum, 24> placement(const mjData* d, int g1, int g2) {
  std::array<mjtNum, 24> p{};
  std::copy_n(d->geom_xpos + 3 * g1, 3, p.begin());
  std::copy_n(d->geom_xmat + 9 * g1, 9, p.begin() + 3);
  std::copy_n(d->geom_xpos + 3 * g2, 3, p.begin() + 12);
  std::copy_n(d->geom_xmat + 9 * g2, 9, p.begin() + 15);
  return p;
}

// The served pair of (g1, g2) in m's attached registry, or -1 (and `registry` null).
int served_pair(const mjModel* m, int g1, int g2, Registry*& registry) {
  registry = graspcd::mujoco::find_registry(m);
  return registry ? registry->find_pair(g1, g2) : -1;
}

Recording* g_recording = nullptr;  // the recording being made or replayed
std::size_t g_cursor = 0;          // the replay's next call
long g_mismatches = 0;             // replayed calls whose geoms or placements differ

// The intersecting triangle pairs of a tree-path call, found again by a fresh detector.
void record_triangles(Registry& registry, const mjData* d, int g1, int g2, Recording& rec) {
  const graspcd::mujoco::MeshTree* t1 = registry.geom_tree(g1);
  const graspcd::mujoco::MeshTree* t2 = registry.geom_tree(g2);
  if (!t1 || !t2) return;
  const graspcd::Pose pose = graspcd::mujoco::relative_pose(d, g1, g2);
  graspcd::Detector detector(registry.config().method, registry.config().detector);
  graspcd::QueryCounters counters;
  std::vector<graspcd::TrianglePair> pairs;
  detector.collide(t1->tree, t2->tree, pose, graspcd::QueryMode::kAllContacts, counters, &pairs);
  const double tn = pose.t.norm();
  const Vec3 fallback = tn > 0 ? Vec3(pose.t / tn) : Vec3(Vec3::UnitZ());
  for (const graspcd::TrianglePair& tp : pairs) {
    rec.tri_cases.push_back({t1->face(tp.a), graspcd::apply_pose(pose, t2->face(tp.b)), fallback,
                             registry.config().max_depth, t1->sharp(tp.a), t2->sharp(tp.b)});
  }
}

int recording_collision(const mjModel* m, const mjData* d, mjContact* con, int g1, int g2,
                        mjtNum margin) {
  Registry* registry = nullptr;
  if (served_pair(m, g1, g2, registry) < 0) {
    return graspcd::mujoco::collide_geoms(m, d, con, g1, g2, margin);
  }
  Recording& rec = *g_recording;
  const std::uint64_t before = registry->stats().counters.tri_pairs;
  const int n = graspcd::mujoco::collide_geoms(m, d, con, g1, g2, margin);
  const std::uint64_t found = registry->stats().counters.tri_pairs - before;
  rec.query_tri_pairs += found;
  rec.calls.push_back({g1, g2, placement(d, g1, g2), rec.contacts.size(), n});
  const Mat3 R = graspcd::mujoco::from_row_major(d->geom_xmat + 9 * g1);
  const Vec3 p = graspcd::mujoco::geom_position(d, g1);
  for (int i = 0; i < n; ++i) {
    rec.contacts.push_back(con[i]);
    WriteCase w;
    w.R = R;
    w.p = p;
    w.c.pos = R.transpose() * (Vec3(con[i].pos[0], con[i].pos[1], con[i].pos[2]) - p);
    w.c.normal = R.transpose() * Vec3(con[i].frame[0], con[i].frame[1], con[i].frame[2]);
    w.c.depth = -con[i].dist;
    rec.writes.push_back(w);
  }
  if (found > 0) record_triangles(*registry, d, g1, g2, rec);
  return n;
}

int replay_collision(const mjModel* m, const mjData* d, mjContact* con, int g1, int g2,
                     mjtNum margin) {
  Registry* registry = nullptr;
  if (served_pair(m, g1, g2, registry) < 0) {
    return graspcd::mujoco::collide_geoms(m, d, con, g1, g2, margin);
  }
  const Recording& rec = *g_recording;
  if (g_cursor >= rec.calls.size()) {
    ++g_mismatches;
    return 0;
  }
  const Call& call = rec.calls[g_cursor++];
  const std::array<mjtNum, 24> now = placement(d, g1, g2);
  if (call.g1 != g1 || call.g2 != g2 ||
      std::memcmp(now.data(), call.placement.data(), sizeof(mjtNum) * now.size()) != 0) {
    ++g_mismatches;
  }
  std::copy_n(rec.contacts.begin() + static_cast<std::ptrdiff_t>(call.first), call.n, con);
  return call.n;
}

// graspcd's entries in mjCOLLISIONFUNC replaced by `f` while this lives (graspcd's function
// installed first, so that the grasp's own install finds the table installed and leaves it).
class EntriesReplaced {
 public:
  explicit EntriesReplaced(mjfCollision f) {
    for (int t1 = 0; t1 < mjNGEOMTYPES; ++t1) {
      for (int t2 = 0; t2 < mjNGEOMTYPES; ++t2) {
        if (mjCOLLISIONFUNC[t1][t2] == &graspcd::mujoco::collide_geoms) {
          entries_.push_back(&mjCOLLISIONFUNC[t1][t2]);
          mjCOLLISIONFUNC[t1][t2] = f;
        }
      }
    }
  }
  ~EntriesReplaced() {
    for (mjfCollision* e : entries_) *e = &graspcd::mujoco::collide_geoms;
  }
  EntriesReplaced(const EntriesReplaced&) = delete;
  EntriesReplaced& operator=(const EntriesReplaced&) = delete;

 private:
  graspcd::mujoco::ScopedInstall install_;
  std::vector<mjfCollision*> entries_;
};

// The recording of a scene's served grasp, made on first use.
const Recording& recording(const std::string& scene) {
  static std::map<std::string, Recording> made;
  auto it = made.find(scene);
  if (it != made.end()) return it->second;
  Recording& rec = made[scene];
  g_recording = &rec;
  {
    EntriesReplaced replaced(&recording_collision);
    rec.result = graspcd::grasp::run_grasp(kMjcf + "/" + scene, exact_contacts());
  }
  g_recording = nullptr;
  if (rec.tri_cases.size() != rec.query_tri_pairs) {
    throw std::runtime_error(
        scene + ": the fresh detector found " + std::to_string(rec.tri_cases.size()) +
        " intersecting triangle pairs, the served queries " + std::to_string(rec.query_tri_pairs));
  }
  return rec;
}

// The measures of two runs that must agree when their trajectories do.
bool same_outcome(const graspcd::grasp::GraspResult& x, const graspcd::grasp::GraspResult& y) {
  return x.physics_steps == y.physics_steps && x.held == y.held &&
         x.object_z_final == y.object_z_final && x.object_z_gripped == y.object_z_gripped &&
         x.hold_drift == y.hold_drift && x.max_speed == y.max_speed && x.tilt_deg == y.tilt_deg &&
         x.max_contacts == y.max_contacts && x.mean_contacts == y.mean_contacts;
}

bool g_failed = false;

void set_counters(benchmark::State& state, const Recording& rec) {
  const auto steps = static_cast<double>(rec.result.physics_steps);
  state.counters["physics_steps"] = steps;
  state.counters["served_calls"] = static_cast<double>(rec.calls.size()) / steps;
  state.counters["tri_pairs"] = static_cast<double>(rec.tri_cases.size()) / steps;
  state.counters["contacts"] = static_cast<double>(rec.writes.size()) / steps;
}

void grasp(benchmark::State& state, const std::string& scene, const std::string& variant) {
  const Recording& rec = recording(scene);
  graspcd::grasp::GraspOptions options = exact_contacts();
  options.native = variant == "native";
  graspcd::grasp::GraspResult r;
  for (auto _ : state) {
    if (variant == "replay") {
      g_recording = const_cast<Recording*>(&rec);
      g_cursor = 0;
      g_mismatches = 0;
      {
        EntriesReplaced replaced(&replay_collision);
        r = graspcd::grasp::run_grasp(kMjcf + "/" + scene, options);
      }
      g_recording = nullptr;
      if (g_mismatches != 0 || g_cursor != rec.calls.size() || !same_outcome(r, rec.result)) {
        g_failed = true;
        state.SkipWithError(
            ("the replay left the served trajectory: " + std::to_string(g_mismatches) +
             " served calls differ, " + std::to_string(g_cursor) + " of " +
             std::to_string(rec.calls.size()) + " replayed")
                .c_str());
        return;
      }
    } else {
      try {
        r = graspcd::grasp::run_grasp(kMjcf + "/" + scene, options);
      } catch (const graspcd::io::InputError& e) {
        // Natively, a concave scene whose start MuJoCo's convex hulls cannot represent
        // (grasp.h): no native grasp to compare with, which is no failure of this benchmark.
        // Served, the scene ran when it was recorded: a failure.
        if (!options.native) g_failed = true;
        state.SkipWithError(e.what());
        return;
      }
    }
    state.SetIterationTime(r.step_wall_ms / 1e3);
  }
  set_counters(state, rec);
  // The native grasp's own steps and contacts (its closing differs from the served one's).
  state.counters["physics_steps"] = static_cast<double>(r.physics_steps);
  if (options.native) {
    state.counters["contacts"] = r.mean_contacts;
    state.counters["served_calls"] = 0;
    state.counters["tri_pairs"] = 0;
  }
  if (variant == "served" && !same_outcome(r, rec.result)) {
    g_failed = true;
    state.SkipWithError("the served grasp differs from the recorded one");
  }
}

// One pass of `work` over the recording per iteration, its time divided by the physics steps.
// Never inlined: bench/callgrind_step.py counts its instructions (inclusive) per part.
template <typename Work>
[[gnu::noinline]] void pass(benchmark::State& state, const Recording& rec, std::size_t cases,
                            Work work) {
  const auto steps = static_cast<double>(rec.result.physics_steps);
  double total = 0;
  for (auto _ : state) {
    const Clock::time_point start = Clock::now();
    work();
    const double s = std::chrono::duration<double>(Clock::now() - start).count();
    total += s;
    state.SetIterationTime(s / steps);
  }
  set_counters(state, rec);
  state.counters["ns_each"] =
      cases == 0
          ? 0.0
          : total * 1e9 / (static_cast<double>(cases) * static_cast<double>(state.iterations()));
}

void tritri(benchmark::State& state, const std::string& scene) {
  const Recording& rec = recording(scene);
  long intersecting = 0;
  pass(state, rec, rec.tri_cases.size(), [&] {
    long n = 0;
    for (const TriCase& c : rec.tri_cases) n += graspcd::tri_tri_intersect(c.a, c.b);
    benchmark::DoNotOptimize(n);
    intersecting = n;
  });
  // Every recorded pair intersects (the query found it so): a pair the test now rejects is an
  // error.
  if (intersecting != static_cast<long>(rec.tri_cases.size())) {
    g_failed = true;
    state.SkipWithError("a recorded intersecting pair no longer intersects");
  }
}

void contact(benchmark::State& state, const std::string& scene) {
  const Recording& rec = recording(scene);
  pass(state, rec, rec.tri_cases.size(), [&] {
    double depth = 0;
    for (const TriCase& c : rec.tri_cases) {
      depth +=
          graspcd::triangle_pair_contact(c.a, c.b, c.max_depth, c.fallback, c.sharp_a, c.sharp_b)
              .depth;
    }
    benchmark::DoNotOptimize(depth);
  });
}

void write(benchmark::State& state, const std::string& scene) {
  const Recording& rec = recording(scene);
  std::vector<mjContact> out(mjMAXCONPAIR);
  pass(state, rec, rec.writes.size(), [&] {
    std::size_t k = 0;
    for (const WriteCase& w : rec.writes) {
      graspcd::mujoco::write_contact(w.c, w.R, w.p, out[k]);
      k = k + 1 == out.size() ? 0 : k + 1;
    }
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  });
}

// The race scenes: examples 1-3, the triangle hand, a real Robotiq scene (meshes from
// ../shared/models) and the concave scenes.
const char* const kScenes[] = {"example1.xml",
                               "example2.xml",
                               "example3.xml",
                               "hand_triangles.xml",
                               "real_robotiq_cup.xml",
                               "concave_bowl_lift.xml",
                               "concave_project_thinbox.xml",
                               "concave_robotiq_bowl_rim.xml",
                               "concave_robotiq_mug_handle.xml",
                               "concave_robotiq_mug_rim.xml",
                               "concave_shadow_mug_hook.xml"};

constexpr int kPassIterations = 20;

// "BM_Floor/SCENE/VARIANT/rep:K", one benchmark per repetition, scene by scene, so that a slow
// moment of the machine falls on all parts of one repetition of a scene (as in mujoco_bench.cpp;
// perf_summary.py folds "/rep:K").
void register_floor(int repetitions) {
  for (int k = 0; k < repetitions; ++k) {
    for (const char* scene : kScenes) {
      const std::string s = scene;
      const std::string stem = "BM_Floor/" + s.substr(0, s.size() - 4) + "/";
      const std::string rep = "/rep:" + std::to_string(k);
      for (const char* variant : {"native", "served", "replay"}) {
        benchmark::RegisterBenchmark((stem + variant + rep).c_str(),
                                     [s, variant](benchmark::State& st) { grasp(st, s, variant); })
            ->UseManualTime()
            ->Iterations(1)
            ->Repetitions(1)
            ->Unit(benchmark::kMicrosecond);
      }
      benchmark::RegisterBenchmark((stem + "tritri" + rep).c_str(),
                                   [s](benchmark::State& st) { tritri(st, s); })
          ->UseManualTime()
          ->Iterations(kPassIterations)
          ->Repetitions(1)
          ->Unit(benchmark::kMicrosecond);
      benchmark::RegisterBenchmark((stem + "contact" + rep).c_str(),
                                   [s](benchmark::State& st) { contact(st, s); })
          ->UseManualTime()
          ->Iterations(kPassIterations)
          ->Repetitions(1)
          ->Unit(benchmark::kMicrosecond);
      benchmark::RegisterBenchmark((stem + "write" + rep).c_str(),
                                   [s](benchmark::State& st) { write(st, s); })
          ->UseManualTime()
          ->Iterations(kPassIterations)
          ->Repetitions(1)
          ->Unit(benchmark::kMicrosecond);
    }
  }
}

// --benchmark_repetitions=N of the command line (1 when absent), taken over as one benchmark per
// repetition and removed, so that Google Benchmark does not repeat each of them.
int take_repetitions(int& argc, char** argv) {
  const std::string key = "--benchmark_repetitions=";
  int n = 1;
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind(key, 0) == 0) {
      n = std::max(1, std::atoi(arg.c_str() + key.size()));
    } else {
      argv[kept++] = argv[i];
    }
  }
  argc = kept;
  return n;
}

}  // namespace

int main(int argc, char** argv) {
  register_floor(take_repetitions(argc, argv));
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  try {
    benchmark::RunSpecifiedBenchmarks();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "graspcd_floor_bench: %s\n", e.what());
    return 1;
  }
  benchmark::Shutdown();
  return g_failed ? 1 : 0;
}
