// NonconvexContacts, the public entry point: it attaches its registry and installs the
// collision function for as long as it lives, counts installs across instances, leaves a
// program's own install alone, installs nothing when the config is bad, and its statistics are
// the served pairs' work of each step.
#include "graspcd/mujoco/nonconvex_contacts.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "graspcd/grasp/grasp.h"
#include "graspcd/mujoco/model_loading.h"
#include "graspcd/mujoco/mujoco_ptr.h"

namespace graspcd::mujoco {
namespace {

const std::string kMjcf = GRASPCD_MJCF_DIR;

struct Scene {
  ModelPtr model;
  DataPtr data;
  explicit Scene(const std::string& name)
      : model(mujoco::load_model(kMjcf + "/" + name + ".xml")), data(mj_makeData(model.get())) {}
  std::string config(const std::string& name) const { return kMjcf + "/" + name + ".pairs.json"; }
};

TEST(NonconvexContacts, AttachesAndInstallsWhileAlive) {
  Scene s("example1");
  ASSERT_FALSE(installed());
  {
    NonconvexContacts contacts(s.model.get(), s.config("example1"));
    EXPECT_TRUE(installed());
    EXPECT_EQ(find_registry(s.model.get()), &contacts.registry());
    EXPECT_GT(contacts.served_pairs(), 0u);
    EXPECT_EQ(contacts.method(), Method::kSat);  // the config's
  }
  EXPECT_FALSE(installed());
  EXPECT_EQ(find_registry(s.model.get()), nullptr);
}

TEST(NonconvexContacts, MethodOverridesTheConfig) {
  Scene s("example1");
  NonconvexContacts contacts(s.model.get(), s.config("example1"), Method::kNeuroSat);
  EXPECT_EQ(contacts.method(), Method::kNeuroSat);
  // Each pair's detector lives in its state on an mjData, made at the first served call there.
  for (int step = 0; step < 500 && contacts.stats().calls == 0; ++step) {
    mj_step(s.model.get(), s.data.get());
  }
  ASSERT_GT(contacts.stats().calls, 0u);
  for (int i = 0; i < static_cast<int>(contacts.served_pairs()); ++i) {
    const Registry::DataPairState* state = contacts.registry().find_pair_state(s.data.get(), i);
    ASSERT_NE(state, nullptr);
    EXPECT_EQ(state->detector.method(), Method::kNeuroSat);
  }
}

TEST(NonconvexContacts, InstallLastsUntilTheLastInstanceGoes) {
  Scene a("example1");
  Scene b("hand_triangles");
  auto first = std::make_unique<NonconvexContacts>(a.model.get(), a.config("example1"));
  auto second = std::make_unique<NonconvexContacts>(b.model.get(), b.config("hand_triangles"));
  first.reset();
  EXPECT_TRUE(installed());
  EXPECT_EQ(find_registry(a.model.get()), nullptr);
  EXPECT_EQ(find_registry(b.model.get()), &second->registry());
  second.reset();
  EXPECT_FALSE(installed());
}

TEST(NonconvexContacts, LeavesTheProgramsOwnInstallInPlace) {
  Scene s("example1");
  ScopedInstall program_install;
  { NonconvexContacts contacts(s.model.get(), s.config("example1")); }
  EXPECT_TRUE(installed());
}

TEST(NonconvexContacts, BadConfigThrowsAndInstallsNothing) {
  Scene s("example1");
  const std::string missing = kMjcf + "/no-such.pairs.json";
  try {
    NonconvexContacts contacts(s.model.get(), missing);
    FAIL() << "no error for a missing config";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind(missing, 0), 0u) << e.what();
  }
  RegistryConfig config;
  config.patterns.push_back({"geom:no_such_geom*", "body:object"});
  EXPECT_THROW(NonconvexContacts(s.model.get(), config), std::runtime_error);
  EXPECT_FALSE(installed());
  EXPECT_EQ(find_registry(s.model.get()), nullptr);
}

// The hand sinks onto the cup under gravity (zero controls): every step's statistics are that
// step's served calls, and the contacts they report are among MuJoCo's contacts of the step.
TEST(NonconvexContacts, StatisticsArePerStep) {
  Scene s("example1");
  NonconvexContacts contacts(s.model.get(), s.config("example1"));
  std::uint64_t total_contacts = 0;
  for (int step = 0; step < 100; ++step) {
    mj_step(s.model.get(), s.data.get());
    const BridgeStats st = contacts.take_stats();
    EXPECT_GT(st.calls, 0u);
    EXPECT_LE(st.calls, contacts.served_pairs());  // one collision pass per mj_step
    EXPECT_LE(st.contacts, static_cast<std::uint64_t>(s.data->ncon));
    total_contacts += st.contacts;
    EXPECT_EQ(contacts.stats().calls, 0u);  // taken
  }
  EXPECT_GT(total_contacts, 0u);
}

// Temporal coherence inside mj_step (registry.h, "front_list"): the same grasp (grasp.h: close,
// squeeze, settle, lift, hold) run with each served pair's tree query restarted from its front on
// the mjData and run with every query from the roots gives bitwise the same trajectory and the
// same contacts at every closing grasp step, and the same result. The grasps include large jumps,
// as a user's program makes them: after grasp step 20 the state of grasp step 10 is restored
// (mj_copyData), after step 35 the model is reset (mj_resetData) and the state of step 25 restored
// over it. The front saves box tests.
TEST(NonconvexContacts, FrontListGivesBitwiseTheSameGraspWithStateRestores) {
  for (const std::string name : {"example1", "example3"}) {
    struct Trace {
      std::vector<std::vector<mjtNum>> qpos;
      std::vector<std::vector<mjContact>> contacts;
      grasp::GraspResult result;
    };
    const auto run = [&](bool front_list) {
      Trace trace;
      DataPtr saved10, saved25;
      grasp::GraspOptions options;
      options.front_list = front_list;
      options.settle_time = 0.1;
      options.lift_time = 0.3;
      options.hold_time = 0.3;
      options.on_grasp_step = [&](const mjModel* m, const mjData* cd, int step) {
        trace.qpos.emplace_back(cd->qpos, cd->qpos + m->nq);
        trace.contacts.emplace_back(cd->contact, cd->contact + cd->ncon);
        // The jumps: the driver hands out its state read-only; a user's program owns its mjData.
        mjData* d = const_cast<mjData*>(cd);
        if (step == 10) saved10.reset(mj_copyData(nullptr, m, d));
        if (step == 25) saved25.reset(mj_copyData(nullptr, m, d));
        if (step == 20) mj_copyData(d, m, saved10.get());
        if (step == 35) {
          mj_resetData(m, d);
          mj_forward(m, d);
          mj_copyData(d, m, saved25.get());
        }
      };
      trace.result = grasp::run_grasp(kMjcf + "/" + name + ".xml", options);
      return trace;
    };
    const Trace coherent = run(true);
    const Trace fresh = run(false);
    ASSERT_EQ(coherent.qpos.size(), fresh.qpos.size()) << name;
    ASSERT_GT(coherent.qpos.size(), 35u) << name;
    int touching_steps = 0;
    for (std::size_t k = 0; k < coherent.qpos.size(); ++k) {
      ASSERT_EQ(coherent.qpos[k], fresh.qpos[k]) << name << " grasp step " << k + 1;
      ASSERT_EQ(coherent.contacts[k].size(), fresh.contacts[k].size()) << name << " step " << k + 1;
      for (std::size_t i = 0; i < coherent.contacts[k].size(); ++i) {
        const mjContact& x = coherent.contacts[k][i];
        const mjContact& y = fresh.contacts[k][i];
        ASSERT_TRUE(x.geom1 == y.geom1 && x.geom2 == y.geom2 && x.dist == y.dist &&
                    std::memcmp(x.pos, y.pos, sizeof x.pos) == 0 &&
                    std::memcmp(x.frame, y.frame, sizeof x.frame) == 0)
            << name << " grasp step " << k + 1 << " contact " << i;
      }
      touching_steps += coherent.result.steps[k].contacts > 0;
    }
    const grasp::GraspResult& a = coherent.result;
    const grasp::GraspResult& b = fresh.result;
    EXPECT_EQ(a.first_contact, b.first_contact) << name;
    EXPECT_EQ(a.gripped, b.gripped) << name;
    EXPECT_EQ(a.object_z_final, b.object_z_final) << name;
    EXPECT_EQ(a.hold_min_z, b.hold_min_z) << name;
    EXPECT_EQ(a.max_contacts, b.max_contacts) << name;
    EXPECT_EQ(a.physics_steps, b.physics_steps) << name;
    // Served contacts on many closing steps, and the front did less box work.
    EXPECT_GT(touching_steps, 10) << name;
    std::uint64_t box_a = 0, box_b = 0;
    for (std::size_t k = 0; k < a.steps.size(); ++k) {
      box_a += a.steps[k].box_tests;
      box_b += b.steps[k].box_tests;
    }
    EXPECT_LT(box_a, box_b) << name;
    std::printf("%s: %zu closing grasp steps, %d with contacts, box tests %llu (front) vs %llu\n",
                name.c_str(), a.steps.size(), touching_steps,
                static_cast<unsigned long long>(box_a), static_cast<unsigned long long>(box_b));
  }
}

// Contacts reused across steps (registry.h, "contact_reuse"; contact.h, ReusedContacts), against
// exact contacts: two copies of example 1 at the closed hand of its grasp, one registry reusing
// (drift 50 um) and one exact, then the object moved in small steps. Within the drift the reusing
// registry queries nothing, and each touching pair's deepest contact stays within twice the drift
// of the exact one (its points move at most the drift; the exact deepest moves as little); beyond
// it, and back at the pose of its last query, it gives bitwise the exact contacts. Then the
// object turned about a finger segment: reused by contact_drift's bound seen from the segment.
TEST(NonconvexContacts, ReusedContactsStayWithinTheDriftOfTheExactOnes) {
  const std::string scene = kMjcf + "/example1.xml";
  std::vector<mjtNum> closed;
  grasp::GraspOptions options;
  options.settle_time = 0.01;
  options.lift_time = 0.01;
  options.hold_time = 0.01;
  options.on_grasp_step = [&](const mjModel* m, const mjData* d, int) {
    closed.assign(d->qpos, d->qpos + m->nq);  // the last closing step's: every finger touches
  };
  grasp::run_grasp(scene, options);
  ASSERT_FALSE(closed.empty());

  const double drift = 5e-5;
  Scene reusing("example1"), exact("example1");
  RegistryConfig config = load_registry_config(reusing.config("example1"));
  config.contact_reuse = drift;
  NonconvexContacts ours(reusing.model.get(), config);
  config.contact_reuse = 0;
  NonconvexContacts reference(exact.model.get(), config);
  const mjModel* m = reusing.model.get();
  const int object = mj_name2id(m, mjOBJ_BODY, "object");
  ASSERT_EQ(m->jnt_type[m->body_jntadr[object]], mjJNT_FREE);
  const int x = m->jnt_qposadr[m->body_jntadr[object]];

  // The deepest contact of each touching served geom pair.
  const auto deepest = [&](const mjData* d) {
    std::map<std::pair<int, int>, double> out;
    for (int i = 0; i < d->ncon; ++i) {
      if (ours.registry().find_pair(d->contact[i].geom1, d->contact[i].geom2) < 0) continue;
      double& v = out[{d->contact[i].geom1, d->contact[i].geom2}];
      v = std::max(v, -d->contact[i].dist);
    }
    return out;
  };
  const auto same = [](const mjData* a, const mjData* b) {
    if (a->ncon != b->ncon) return false;
    for (int i = 0; i < a->ncon; ++i) {
      const mjContact& p = a->contact[i];
      const mjContact& q = b->contact[i];
      if (p.geom1 != q.geom1 || p.geom2 != q.geom2 || p.dist != q.dist ||
          std::memcmp(p.pos, q.pos, sizeof p.pos) != 0 ||
          std::memcmp(p.frame, q.frame, sizeof p.frame) != 0) {
        return false;
      }
    }
    return true;
  };
  // Both at `closed` with the object moved by `dx` along x; the reusing registry's calls answered
  // by kept contacts.
  // Or turned by `turn` about the vertical through `pivot` (world).
  const auto at = [&](double dx, double turn = 0, const Vec3& pivot = Vec3::Zero()) {
    for (Scene* s : {&reusing, &exact}) {
      mjData* d = s->data.get();
      std::copy(closed.begin(), closed.end(), d->qpos);
      d->qpos[x] += dx;
      const double cs = std::cos(turn), sn = std::sin(turn);
      const double px = d->qpos[x] - pivot.x(), py = d->qpos[x + 1] - pivot.y();
      d->qpos[x] = pivot.x() + cs * px - sn * py;
      d->qpos[x + 1] = pivot.y() + sn * px + cs * py;
      const mjtNum about_z[4] = {std::cos(turn / 2), 0, 0, std::sin(turn / 2)};
      mjtNum q[4];
      mju_mulQuat(q, about_z, d->qpos + x + 3);
      std::copy(q, q + 4, d->qpos + x + 3);
      mj_forward(s->model.get(), d);
    }
    reference.take_stats();
    return ours.take_stats().reused;
  };

  // Each touching pair's deepest contact, reused against exact: within twice the drift.
  double worst = 0;
  const auto within_twice_the_drift = [&](double step) {
    const auto a = deepest(reusing.data.get());
    const auto b = deepest(exact.data.get());
    ASSERT_EQ(a.size(), b.size()) << step;
    for (const auto& [pair, depth] : b) {
      ASSERT_TRUE(a.count(pair)) << step;
      worst = std::max(worst, std::abs(a.at(pair) - depth));
      EXPECT_LE(std::abs(a.at(pair) - depth), 2 * drift)
          << step << " geoms " << pair.first << ", " << pair.second;
    }
  };

  EXPECT_EQ(at(0), 0u);  // the first query is exact
  ASSERT_TRUE(same(reusing.data.get(), exact.data.get()));
  ASSERT_GE(deepest(exact.data.get()).size(), 2u);  // fingers touch the cup
  int reused_steps = 0;
  for (const double dx : {1e-5, 2e-5, 3e-5, 4e-5}) {
    const std::uint64_t reused = at(dx);
    EXPECT_EQ(reused, deepest(exact.data.get()).size()) << dx;  // every touching pair
    reused_steps += reused > 0;
    within_twice_the_drift(dx);
  }
  EXPECT_EQ(reused_steps, 4);
  // Back at the pose of the last query: exactly its contacts, reused.
  EXPECT_GT(at(0), 0u);
  EXPECT_TRUE(same(reusing.data.get(), exact.data.get()));
  // Beyond the drift: queried again, exact.
  EXPECT_EQ(at(6e-5), 0u);
  EXPECT_TRUE(same(reusing.data.get(), exact.data.get()));
  // Turned about the vertical through a touching finger segment's origin (geom1 of its pair): the
  // object's origin moves by the turn times its distance from the pivot, beyond the drift, but
  // the object's points near the segment only by the turn times the segment's radius. That pair
  // is reused by contact_drift's bound seen from the segment (pose_drift's would query it), and
  // every reused pair stays within twice the drift of the exact contacts.
  const int segment = deepest(exact.data.get()).begin()->first.first;
  const Vec3 pivot(exact.data->geom_xpos[3 * segment], exact.data->geom_xpos[3 * segment + 1], 0);
  EXPECT_EQ(at(0), 0u);  // 60 um back: queried again at the closed hand
  std::uint64_t reused_turning = 0;
  for (const double turn : {5e-4, 1e-3}) {
    reused_turning += at(0, turn, pivot);
    within_twice_the_drift(turn);
  }
  std::printf("reused calls turning: %llu\n", static_cast<unsigned long long>(reused_turning));
  EXPECT_GT(reused_turning, 0u);
  std::printf("deepest contact of a touching pair, reused against exact: at most %.1f um apart\n",
              worst * 1e6);
}

}  // namespace
}  // namespace graspcd::mujoco
