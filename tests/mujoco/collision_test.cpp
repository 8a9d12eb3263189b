// The collision function in mjCOLLISIONFUNC: served pairs get graspcd's contacts and none of
// MuJoCo's, every other pair is untouched and goes to the original entry of its own type pair,
// uninstall restores the table, contacts follow MuJoCo's contract, the contact answer agrees with
// CGAL, and a body inside a non-convex cavity gets no contact from us while MuJoCo's convex hull
// reports one. (Primitive pairs: primitives_test.cpp.)
#include "graspcd/mujoco/collision.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <memory>
#include <random>
#include <set>

#include "graspcd/exact/exact.h"
#include "graspcd/support/seeded.h"
#include "helpers/scene_support.h"

namespace graspcd::mujoco {
namespace {

using testing::contacts_between;
using testing::DataPtr;
using testing::load_scene;
using testing::ModelPtr;
using testing::TempDir;

mjfCollision& table_entry() { return mjCOLLISIONFUNC[mjGEOM_MESH][mjGEOM_MESH]; }

// A stand-in for MuJoCo's original mesh-mesh function that records each call and forwards it.
struct CallLog {
  static mjfCollision real;
  static std::vector<std::pair<int, int>> calls;
  static int collide(const mjModel* m, const mjData* d, mjContact* con, int g1, int g2,
                     mjtNum margin) {
    calls.emplace_back(g1, g2);
    return real(m, d, con, g1, g2, margin);
  }
  static int count(int a, int b) {
    int n = 0;
    for (const auto& [g1, g2] : calls) n += (g1 == a && g2 == b) || (g1 == b && g2 == a);
    return n;
  }
};
mjfCollision CallLog::real = nullptr;
std::vector<std::pair<int, int>> CallLog::calls;

void expect_same_contact(const mjContact& x, const mjContact& y) {
  EXPECT_EQ(x.geom1, y.geom1);
  EXPECT_EQ(x.geom2, y.geom2);
  EXPECT_EQ(x.dist, y.dist);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(x.pos[k], y.pos[k]);
  for (int k = 0; k < 9; ++k) EXPECT_EQ(x.frame[k], y.frame[k]);
}

Vec3 normal_of(const mjContact& c) { return Vec3(c.frame[0], c.frame[1], c.frame[2]); }
Vec3 xpos(const mjData* d, int g) {
  return Vec3(d->geom_xpos[3 * g], d->geom_xpos[3 * g + 1], d->geom_xpos[3 * g + 2]);
}

// Three stacked cubes and a ball on the floor: cube_a/cube_b overlap by 1 cm (served), cube_b/
// cube_c overlap (not served), the ball sinks 5 mm into the floor (a primitive pair).
const char* kStackScene = R"(
<mujoco>
  <size nconmax="200" njmax="800"/>
  <option gravity="0 0 0"/>
  <asset><mesh name="cube" file="cube.obj"/></asset>
  <worldbody>
    <geom name="floor" type="plane" size="2 2 0.1"/>
    <body pos="1 0 0.045"><freejoint/><geom name="ball" type="sphere" size="0.05"/></body>
    <body pos="0 0 0.3"><freejoint/><geom name="cube_a" type="mesh" mesh="cube"/></body>
    <body pos="0.03 0.01 0.37"><freejoint/><geom name="cube_b" type="mesh" mesh="cube"/></body>
    <body pos="0.05 0.02 0.45" euler="0.3 0.2 0"><freejoint/>
      <geom name="cube_c" type="mesh" mesh="cube"/></body>
  </worldbody>
</mujoco>)";

class StackScene : public ::testing::Test {
 protected:
  void SetUp() override {
    model_ = load_scene(dir_, kStackScene, {{"cube", testing::make_box_mesh(0.04, 0.04, 0.04)}});
    ASSERT_TRUE(model_);
    ball_ = geom("ball");
    floor_ = geom("floor");
    a_ = geom("cube_a");
    b_ = geom("cube_b");
    c_ = geom("cube_c");
  }
  int geom(const char* name) const { return mj_name2id(model_.get(), mjOBJ_GEOM, name); }
  DataPtr forward() const {
    DataPtr d(mj_makeData(model_.get()));
    mj_forward(model_.get(), d.get());
    return d;
  }

  TempDir dir_;
  ModelPtr model_;
  int ball_ = -1, floor_ = -1, a_ = -1, b_ = -1, c_ = -1;
};

// (a) and (b): with graspcd installed, the served pair's contacts are all ours and MuJoCo's
// function is never called for it; the unserved mesh pair and the primitive pair get exactly
// MuJoCo's contacts, bit for bit.
TEST_F(StackScene, ServedPairsGetOurContactsOthersAreUntouched) {
  // Without graspcd installed.
  const DataPtr native = forward();
  const auto native_ab = contacts_between(native.get(), a_, b_);
  const auto native_bc = contacts_between(native.get(), b_, c_);
  const auto native_ball = contacts_between(native.get(), ball_, floor_);
  ASSERT_EQ(native_ab.size(), 1u);  // MuJoCo 2.2's convex mesh collision: one contact per pair
  ASSERT_EQ(native_bc.size(), 1u);
  ASSERT_EQ(native_ball.size(), 1u);

  // With graspcd installed, MuJoCo's original entry wrapped in a call log.
  const mjfCollision saved = table_entry();
  CallLog::real = saved;
  CallLog::calls.clear();
  table_entry() = &CallLog::collide;
  DataPtr ours;
  BridgeStats stats;
  {
    ScopedInstall scope;
    RegistryConfig config;
    config.patterns = {{"cube_a", "cube_b"}};
    Registry registry(model_.get(), config);
    const Attachment attached = attach(registry);
    ours = forward();
    stats = registry.stats();
  }
  EXPECT_EQ(table_entry(), &CallLog::collide);
  table_entry() = saved;

  // The served pair: ours only.
  EXPECT_EQ(CallLog::count(a_, b_), 0);
  const auto ours_ab = contacts_between(ours.get(), a_, b_);
  EXPECT_EQ(stats.calls, 1u);
  EXPECT_GT(stats.counters.tri_pairs, 0u);
  EXPECT_EQ(ours_ab.size(), stats.contacts);
  EXPECT_GT(ours_ab.size(), native_ab.size());
  // The overlap is 1 cm along z: every contact pushes along z, 1 cm deep at most.
  for (const mjContact* c : ours_ab) {
    EXPECT_GT(std::abs(c->frame[2]), 0.99);
    EXPECT_LE(c->dist, 0.0);
    EXPECT_GE(c->dist, -0.0100001);
  }
  // Everything else: MuJoCo's, unchanged.
  EXPECT_GE(CallLog::count(b_, c_), 1);
  const auto ours_bc = contacts_between(ours.get(), b_, c_);
  const auto ours_ball = contacts_between(ours.get(), ball_, floor_);
  ASSERT_EQ(ours_bc.size(), 1u);
  ASSERT_EQ(ours_ball.size(), 1u);
  expect_same_contact(*ours_bc[0], *native_bc[0]);
  expect_same_contact(*ours_ball[0], *native_ball[0]);
  EXPECT_EQ(ours->ncon, native->ncon - 1 + static_cast<int>(ours_ab.size()));
  std::printf("served cube pair: %zu contacts (native 1), %llu triangle pairs, %llu ns\n",
              ours_ab.size(), static_cast<unsigned long long>(stats.counters.tri_pairs),
              static_cast<unsigned long long>(stats.detection_ns));
}

// A registry that is attached but serves other pairs leaves a model exactly as MuJoCo sees it.
TEST_F(StackScene, AttachedRegistryWithoutThisPairDelegates) {
  const DataPtr native = forward();
  ScopedInstall scope;
  RegistryConfig config;
  config.patterns = {{"cube_a", "cube_c"}};  // 11 cm apart: no contact either way
  Registry registry(model_.get(), config);
  const Attachment attached = attach(registry);
  const DataPtr ours = forward();
  ASSERT_EQ(ours->ncon, native->ncon);
  for (int i = 0; i < ours->ncon; ++i) expect_same_contact(ours->contact[i], native->contact[i]);
  EXPECT_TRUE(contacts_between(ours.get(), a_, c_).empty());
}

// Non-finite state (collision.h): a served pair whose placement holds NaN, an infinity or a number
// beyond mjMAXVAL gets 0 contacts, runs no query and is counted; other pairs are MuJoCo's.
TEST_F(StackScene, NonFinitePlacementIsSkippedAndCounted) {
  ScopedInstall scope;
  RegistryConfig config;
  config.patterns = {{"cube_a", "cube_b"}};
  Registry registry(model_.get(), config);
  const Attachment attached = attach(registry);
  const DataPtr d = forward();
  ASSERT_FALSE(contacts_between(d.get(), a_, b_).empty());
  ASSERT_EQ(registry.stats().nonfinite_skips, 0u);

  // The callback itself, on a placement made bad entry by entry.
  std::vector<mjContact> con(mjMAXCONPAIR);
  const double kBad[] = {std::nan(""), INFINITY, -INFINITY, 2 * mjMAXVAL};
  std::uint64_t skips = 0;
  for (const double bad : kBad) {
    for (mjtNum* x : {&d->geom_xpos[3 * b_ + 2], &d->geom_xpos[3 * a_], &d->geom_xmat[9 * b_ + 4],
                      &d->geom_xmat[9 * a_ + 8]}) {
      const mjtNum saved = *x;
      *x = bad;
      registry.reset_stats();
      EXPECT_EQ(collide_geoms(model_.get(), d.get(), con.data(), a_, b_, 0), 0) << bad;
      EXPECT_EQ(registry.stats().calls, 1u);
      EXPECT_EQ(registry.stats().nonfinite_skips, 1u);
      EXPECT_EQ(registry.stats().counters.box_tests, 0u);
      skips += registry.stats().nonfinite_skips;
      *x = saved;
    }
  }
  EXPECT_EQ(skips, 16u);
  // The placement restored: contacts again.
  registry.reset_stats();
  EXPECT_GT(collide_geoms(model_.get(), d.get(), con.data(), a_, b_, 0), 0);
  EXPECT_EQ(registry.stats().nonfinite_skips, 0u);

  // Through MuJoCo: mj_forward does not check qpos (mj_step would reset it), so a NaN in cube_b's
  // free joint reaches the kinematics and the collision; the served pair gets no contact.
  const int q = model_->jnt_qposadr[model_->body_jntadr[model_->geom_bodyid[b_]]];
  d->qpos[q] = std::nan("");
  registry.reset_stats();
  mj_forward(model_.get(), d.get());
  EXPECT_TRUE(contacts_between(d.get(), a_, b_).empty());
  EXPECT_EQ(registry.stats().calls, 1u);
  EXPECT_EQ(registry.stats().nonfinite_skips, 1u);
  EXPECT_EQ(registry.stats().counters.box_tests, 0u);
}

// (c) install/uninstall: every entry among the served types (sphere, capsule, ellipsoid,
// cylinder, box, mesh; t1 <= t2) gets graspcd's function and its original is saved; every other
// entry (plane and hfield rows, the unused lower triangle) is untouched; uninstall restores each.
TEST(Install, UninstallRestoresEveryOriginalEntry) {
  const int served[] = {mjGEOM_SPHERE,   mjGEOM_CAPSULE, mjGEOM_ELLIPSOID,
                        mjGEOM_CYLINDER, mjGEOM_BOX,     mjGEOM_MESH};
  const auto is_served = [&](int t) {
    for (int s : served) {
      if (s == t) return true;
    }
    return false;
  };
  std::vector<mjfCollision> before(&mjCOLLISIONFUNC[0][0],
                                   &mjCOLLISIONFUNC[0][0] + mjNGEOMTYPES * mjNGEOMTYPES);
  const auto was = [&](int i, int j) {
    return before[static_cast<std::size_t>(i * mjNGEOMTYPES + j)];
  };
  ASSERT_NE(table_entry(), nullptr);
  ASSERT_FALSE(installed());
  EXPECT_EQ(original_collision(mjGEOM_MESH, mjGEOM_MESH), nullptr);
  EXPECT_TRUE(install());
  EXPECT_TRUE(installed());
  int replaced = 0;
  for (int i = 0; i < mjNGEOMTYPES; ++i) {
    for (int j = 0; j < mjNGEOMTYPES; ++j) {
      EXPECT_EQ(installable_type(i), is_served(i));
      if (i <= j && is_served(i) && is_served(j) && was(i, j)) {
        EXPECT_EQ(mjCOLLISIONFUNC[i][j], &collide_geoms) << i << " " << j;
        EXPECT_EQ(original_collision(i, j), was(i, j)) << i << " " << j;
        EXPECT_EQ(original_collision(j, i), was(i, j)) << i << " " << j;  // either order
        ++replaced;
      } else {
        EXPECT_EQ(mjCOLLISIONFUNC[i][j], was(i, j)) << i << " " << j;
      }
    }
  }
  EXPECT_EQ(replaced, 21);  // MuJoCo 2.2.2 has all 21 entries among the six types
  EXPECT_EQ(original_collision(mjGEOM_PLANE, mjGEOM_SPHERE), nullptr);
  EXPECT_FALSE(install());  // idempotent: the saved entries stay MuJoCo's
  EXPECT_EQ(original_collision(mjGEOM_MESH, mjGEOM_MESH), was(mjGEOM_MESH, mjGEOM_MESH));
  EXPECT_TRUE(uninstall());
  EXPECT_FALSE(uninstall());
  const auto table_unchanged = [&] {
    for (int i = 0; i < mjNGEOMTYPES; ++i) {
      for (int j = 0; j < mjNGEOMTYPES; ++j) EXPECT_EQ(mjCOLLISIONFUNC[i][j], was(i, j));
    }
  };
  table_unchanged();
  EXPECT_EQ(original_collision(mjGEOM_BOX, mjGEOM_BOX), nullptr);
  {
    ScopedInstall s;
    EXPECT_EQ(table_entry(), &collide_geoms);
    EXPECT_EQ(mjCOLLISIONFUNC[mjGEOM_SPHERE][mjGEOM_BOX], &collide_geoms);
  }
  table_unchanged();
  EXPECT_FALSE(installed());
}

// Stand-ins for MuJoCo's entries that record (type pair, g1, g2, margin) and forward the call.
struct TypedLog {
  struct Call {
    int t1, t2, g1, g2;
    mjtNum margin;
  };
  static mjfCollision real[mjNGEOMTYPES][mjNGEOMTYPES];
  static std::vector<Call> calls;
  template <int T1, int T2>
  static int collide(const mjModel* m, const mjData* d, mjContact* con, int g1, int g2,
                     mjtNum margin) {
    calls.push_back({T1, T2, g1, g2, margin});
    return real[T1][T2](m, d, con, g1, g2, margin);
  }
};
mjfCollision TypedLog::real[mjNGEOMTYPES][mjNGEOMTYPES] = {};
std::vector<TypedLog::Call> TypedLog::calls;

template <int T1, int T2>
void wrap_entry() {
  TypedLog::real[T1][T2] = mjCOLLISIONFUNC[T1][T2];
  mjCOLLISIONFUNC[T1][T2] = &TypedLog::collide<T1, T2>;
}

// Unserved pairs of every installed type pair go to the saved original of THAT type pair, with
// the same geoms and margin, and get MuJoCo's contacts bit for bit; the served pair gets ours.
TEST(Install, UnservedPairsGoToTheOriginalOfTheirOwnTypePair) {
  TempDir dir;
  const ModelPtr m = load_scene(dir, R"(
<mujoco>
  <size nconmax="200" njmax="800"/>
  <option gravity="0 0 0"/>
  <asset><mesh name="cube" file="cube.obj"/></asset>
  <worldbody>
    <body pos="0 0 0"><freejoint/><geom name="ball" type="sphere" size="0.03" margin="0.001"/></body>
    <body pos="0.04 0 0"><freejoint/><geom name="rod" type="capsule" size="0.02 0.03"/></body>
    <body pos="0.02 0.045 0"><freejoint/><geom name="brick" type="box" size="0.02 0.02 0.02"/></body>
    <body pos="-0.02 -0.04 0.01"><freejoint/><geom name="can" type="cylinder" size="0.02 0.02"/></body>
    <body pos="0.03 -0.03 0.04"><freejoint/><geom name="egg" type="ellipsoid" size="0.02 0.015 0.025"/></body>
    <body pos="-0.04 0.03 0"><freejoint/><geom name="cube" type="mesh" mesh="cube"/></body>
    <body pos="-0.07 0.06 0.02"><freejoint/><geom name="cube2" type="mesh" mesh="cube"/></body>
  </worldbody>
</mujoco>)",
                                {{"cube", testing::make_box_mesh(0.025, 0.025, 0.025)}});
  ASSERT_TRUE(m);
  const DataPtr native(mj_makeData(m.get()));
  mj_forward(m.get(), native.get());

  std::vector<mjfCollision> before(&mjCOLLISIONFUNC[0][0],
                                   &mjCOLLISIONFUNC[0][0] + mjNGEOMTYPES * mjNGEOMTYPES);
  wrap_entry<mjGEOM_SPHERE, mjGEOM_CAPSULE>();
  wrap_entry<mjGEOM_SPHERE, mjGEOM_BOX>();
  wrap_entry<mjGEOM_SPHERE, mjGEOM_MESH>();
  wrap_entry<mjGEOM_SPHERE, mjGEOM_CYLINDER>();
  wrap_entry<mjGEOM_CAPSULE, mjGEOM_BOX>();
  wrap_entry<mjGEOM_CAPSULE, mjGEOM_ELLIPSOID>();
  wrap_entry<mjGEOM_ELLIPSOID, mjGEOM_BOX>();
  wrap_entry<mjGEOM_CYLINDER, mjGEOM_MESH>();
  wrap_entry<mjGEOM_BOX, mjGEOM_MESH>();
  wrap_entry<mjGEOM_MESH, mjGEOM_MESH>();
  TypedLog::calls.clear();
  const int cube = mj_name2id(m.get(), mjOBJ_GEOM, "cube");
  const int cube2 = mj_name2id(m.get(), mjOBJ_GEOM, "cube2");
  DataPtr ours;
  {
    ScopedInstall scope;
    RegistryConfig config;
    config.patterns = {{"cube", "cube2"}};
    Registry registry(m.get(), config);
    const Attachment attached = attach(registry);
    ours = DataPtr(mj_makeData(m.get()));
    mj_forward(m.get(), ours.get());
    EXPECT_EQ(registry.stats().calls, 1u);
  }
  // Every logged call was for its own type pair, never for the served pair.
  std::set<std::pair<int, int>> logged_types;
  for (const TypedLog::Call& c : TypedLog::calls) {
    EXPECT_EQ(m->geom_type[c.g1], c.t1);
    EXPECT_EQ(m->geom_type[c.g2], c.t2);
    EXPECT_FALSE((c.g1 == cube && c.g2 == cube2) || (c.g1 == cube2 && c.g2 == cube));
    const double expected_margin = std::max(m->geom_margin[c.g1], m->geom_margin[c.g2]);
    EXPECT_EQ(c.margin, expected_margin);
    logged_types.insert({c.t1, c.t2});
  }
  EXPECT_GE(logged_types.size(), 6u);
  // Each native contact of an unserved pair is in ours, bit for bit, in the same order.
  int compared = 0;
  std::vector<const mjContact*> ours_unserved;
  for (int i = 0; i < ours->ncon; ++i) {
    const mjContact& c = ours->contact[i];
    if (!((c.geom1 == cube && c.geom2 == cube2) || (c.geom1 == cube2 && c.geom2 == cube))) {
      ours_unserved.push_back(&c);
    }
  }
  std::vector<const mjContact*> native_unserved;
  for (int i = 0; i < native->ncon; ++i) {
    const mjContact& c = native->contact[i];
    if (!((c.geom1 == cube && c.geom2 == cube2) || (c.geom1 == cube2 && c.geom2 == cube))) {
      native_unserved.push_back(&c);
    }
  }
  ASSERT_EQ(ours_unserved.size(), native_unserved.size());
  for (std::size_t i = 0; i < ours_unserved.size(); ++i) {
    expect_same_contact(*ours_unserved[i], *native_unserved[i]);
    ++compared;
  }
  EXPECT_GE(compared, 5);
  // Restore MuJoCo's entries.
  std::copy(before.begin(), before.end(), &mjCOLLISIONFUNC[0][0]);
  std::printf("delegation: %zu logged calls over %zu type pairs, %d native contacts compared\n",
              TypedLog::calls.size(), logged_types.size(), compared);
}

// Many models come and go: each attachment detaches its registry, and a model without one collides
// natively.
TEST(Install, ManyModelsAttachAndDetach) {
  ScopedInstall scope;
  TempDir dir;
  for (int round = 0; round < 12; ++round) {
    ModelPtr m = load_scene(dir, kStackScene, {{"cube", testing::make_box_mesh(0.04, 0.04, 0.04)}});
    ASSERT_TRUE(m);
    {
      RegistryConfig config;
      config.patterns = {{"cube_a", "cube_b"}};
      Registry registry(m.get(), config);
      const Attachment attached = attach(registry);
      EXPECT_EQ(find_registry(m.get()), &registry);
      DataPtr d(mj_makeData(m.get()));
      mj_forward(m.get(), d.get());
      EXPECT_EQ(registry.stats().calls, 1u);
    }
    EXPECT_EQ(find_registry(m.get()), nullptr);
    DataPtr d(mj_makeData(m.get()));
    mj_forward(m.get(), d.get());
    const int a = mj_name2id(m.get(), mjOBJ_GEOM, "cube_a");
    const int b = mj_name2id(m.get(), mjOBJ_GEOM, "cube_b");
    EXPECT_EQ(contacts_between(d.get(), a, b).size(), 1u);  // native again
  }
}

// (d) Two deeply overlapping triangulated spheres: hundreds of intersecting triangle pairs, a
// manifold of the pair's budget (8 by default; 50, mjMAXCONPAIR, when the config asks), each
// contact with a unit normal from geom1 toward geom2, an orthonormal frame, and a penetration
// within the cap.
TEST(Contacts, TheManifoldBudgetWithUnitNormalsFromGeom1ToGeom2) {
  TempDir dir;
  const ModelPtr m = load_scene(dir, R"(
<mujoco>
  <size nconmax="200" njmax="800"/>
  <asset><mesh name="s" file="s.obj"/></asset>
  <worldbody>
    <body pos="0 0 0"><freejoint/><geom name="s1" type="mesh" mesh="s"/></body>
    <body pos="0.06 0.01 -0.02" euler="0.4 0.1 0.7"><freejoint/><geom name="s2" type="mesh" mesh="s"/></body>
  </worldbody>
</mujoco>)",
                                {{"s", testing::make_uv_sphere(0.05, 24, 48)}});
  ASSERT_TRUE(m);
  ScopedInstall scope;
  RegistryConfig config;
  config.patterns = {{"s1", "s2"}};
  config.max_depth = 0.004;
  const DataPtr d(mj_makeData(m.get()));
  {
    Registry registry(m.get(), config);
    const Attachment attached = attach(registry);
    mj_forward(m.get(), d.get());
    EXPECT_EQ(contacts_between(d.get(), 0, 1).size(), 8u) << "the default budget";
    EXPECT_GT(registry.stats().patches, 1u) << "a ring of contact: several patches";
  }
  config.manifold.max_per_pair = mjMAXCONPAIR;
  config.manifold.max_per_patch = mjMAXCONPAIR;
  Registry registry(m.get(), config);
  const Attachment attached = attach(registry);
  mj_forward(m.get(), d.get());
  const auto cs = contacts_between(d.get(), 0, 1);
  EXPECT_GT(registry.stats().counters.tri_pairs, 50u);
  EXPECT_EQ(registry.stats().capped_pairs, 1u);
  EXPECT_EQ(registry.stats().candidates, registry.stats().counters.tri_pairs);
  ASSERT_EQ(cs.size(), static_cast<std::size_t>(mjMAXCONPAIR));
  for (const mjContact* c : cs) {
    const Vec3 n = normal_of(*c);
    const Vec3 t1(c->frame[3], c->frame[4], c->frame[5]);
    const Vec3 t2(c->frame[6], c->frame[7], c->frame[8]);
    EXPECT_NEAR(n.norm(), 1.0, 1e-12);
    EXPECT_NEAR(t1.norm(), 1.0, 1e-12);
    EXPECT_NEAR(n.dot(t1), 0.0, 1e-12);
    EXPECT_NEAR(n.cross(t1).dot(t2), 1.0, 1e-12);
    // Sphere meshes are recentred on their centres: geom1 -> geom2 is the centre difference.
    const Vec3 towards = (xpos(d.get(), c->geom2) - xpos(d.get(), c->geom1)).normalized();
    EXPECT_GT(n.dot(towards), 0.3);
    EXPECT_LE(c->dist, 0.0);
    EXPECT_GE(c->dist, -0.004);
  }
  std::printf("spheres: %llu triangle pairs -> %zu contacts, %llu box tests, %llu ns\n",
              static_cast<unsigned long long>(registry.stats().counters.tri_pairs), cs.size(),
              static_cast<unsigned long long>(registry.stats().counters.box_tests),
              static_cast<unsigned long long>(registry.stats().detection_ns));
}

// (e) At random poses of a sphere around a torus (non-convex), "any contact" from graspcd is
// CGAL's "any intersecting triangle pair" on the same posed float vertices, and the tree found
// exactly CGAL's number of intersecting pairs; for every method of the detector.
class CgalAgreement : public ::testing::TestWithParam<Method> {};

TEST_P(CgalAgreement, AnswerAgreesWithCgalOnTheSamePosedVertices) {
  TempDir dir;
  const ModelPtr m = load_scene(dir, R"(
<mujoco>
  <size nconmax="200" njmax="800"/>
  <asset><mesh name="torus" file="torus.obj"/><mesh name="ball" file="ball.obj"/></asset>
  <worldbody>
    <body><freejoint/><geom name="torus" type="mesh" mesh="torus"/></body>
    <body><freejoint/><geom name="ball" type="mesh" mesh="ball"/></body>
  </worldbody>
</mujoco>)",
                                {{"torus", testing::make_torus(0.05, 0.015, 40, 20)},
                                 {"ball", testing::make_uv_sphere(0.02, 12, 16)}});
  ASSERT_TRUE(m);
  ScopedInstall scope;
  RegistryConfig config;
  config.method = GetParam();
  // The answer cannot depend on the pass cap (a capped perceptron says "may overlap"); a small
  // cap keeps the perceptron methods fast here (at the default 1,500 they take seconds).
  config.detector.cap = 60;
  config.detector.switch_passes = 20;
  config.patterns = {{"torus", "ball"}};
  Registry registry(m.get(), config);
  const Attachment attached = attach(registry);
  const int g_lo = registry.pairs()[0].geom_lo, g_hi = registry.pairs()[0].geom_hi;
  const std::vector<Triangle> lo = Registry::mesh_triangles(m.get(), m->geom_dataid[g_lo]);
  const std::vector<Triangle> hi = Registry::mesh_triangles(m.get(), m->geom_dataid[g_hi]);
  const int ball_q =
      m->jnt_qposadr[m->body_jntadr[m->geom_bodyid[mj_name2id(m.get(), mjOBJ_GEOM, "ball")]]];
  seeded::Rng rng(20261122);
  const DataPtr d(mj_makeData(m.get()));
  int hits = 0, misses = 0;
  for (int pose = 0; pose < 60; ++pose) {
    mj_resetData(m.get(), d.get());
    double* qp = d->qpos + ball_q;
    qp[0] = seeded::uniform(rng, -0.08, 0.08);
    qp[1] = seeded::uniform(rng, -0.08, 0.08);
    qp[2] = seeded::uniform(rng, -0.035, 0.035);
    for (int k = 3; k < 7; ++k) qp[k] = seeded::uniform(rng, -1, 1);
    mju_normalize4(qp + 3);
    const std::uint64_t before = registry.stats().counters.tri_pairs;
    mj_forward(m.get(), d.get());
    const std::uint64_t found = registry.stats().counters.tri_pairs - before;
    const Pose rel = relative_pose(d.get(), g_lo, g_hi);
    std::vector<Triangle> posed;
    for (const Triangle& t : hi) posed.push_back(apply_pose(rel, t));
    const auto truth = exact::mesh_mesh_pairs(lo, posed);
    const bool ours = !contacts_between(d.get(), g_lo, g_hi).empty();
    EXPECT_EQ(ours, !truth.empty()) << "pose " << pose;
    EXPECT_EQ(found, truth.size()) << "pose " << pose;
    (truth.empty() ? misses : hits) += 1;
  }
  // The sample mixes both answers.
  EXPECT_GE(hits, 10);
  EXPECT_GE(misses, 10);
  const BridgeStats& st = registry.stats();
  std::printf(
      "torus/ball, %s: %d poses with contact, %d without, all agree with CGAL; per pose %.0f box "
      "tests, %.0f triangle tests, %.1f us\n",
      method_name(GetParam()), hits, misses, static_cast<double>(st.counters.box_tests) / 60,
      static_cast<double>(st.counters.tri_tests) / 60, static_cast<double>(st.detection_ns) / 60e3);
}

// perceptron-nodisp is left out: its planes through the origin prove almost no node pair of
// these meshes disjoint, so the query is near brute force (measured: 205,000 box tests and
// 99,000 triangle tests, 0.5 s per pose; 30 s for this test). The core's tests cover its answers.
std::vector<Method> methods_for_agreement() {
  std::vector<Method> out;
  for (Method m : all_methods()) {
    if (m != Method::kPerceptronNoDisp) out.push_back(m);
  }
  return out;
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, CgalAgreement, ::testing::ValuesIn(methods_for_agreement()),
                         [](const ::testing::TestParamInfo<Method>& param) {
                           std::string name = method_name(param.param);
                           for (char& c : name) {
                             if (c == '-') c = '_';
                           }
                           return name;
                         });

// (f) A U-shape (non-convex) with a small cube in its cavity, 3 cm from each wall: MuJoCo's
// convex hull says contact; the surfaces do not meet, and graspcd says none. Pushed into the
// right wall, the cube gets our contacts with the wall's normal.
const char* kCavityScene = R"(
<mujoco>
  <size nconmax="200" njmax="800"/>
  <option gravity="0 0 0"/>
  <asset><mesh name="u" file="u.obj"/><mesh name="cube" file="cube.obj"/></asset>
  <worldbody>
    <geom name="u" type="mesh" mesh="u"/>
    <body name="probe" pos="0 0.04 0"><freejoint/><geom name="cube" type="mesh" mesh="cube"/></body>
  </worldbody>
</mujoco>)";

TEST(Contacts, BodyInsideANonConvexCavityGetsNoContactFromUs) {
  TempDir dir;
  const TriangleMesh u = testing::make_u_mesh(0.05, 0.08, 0.01, 0.03);
  ASSERT_GT(testing::signed_volume6(u), 0.0);  // closed and outward
  const ModelPtr m =
      load_scene(dir, kCavityScene, {{"u", u}, {"cube", testing::make_box_mesh(0.01, 0.01, 0.01)}});
  ASSERT_TRUE(m);
  const int gu = mj_name2id(m.get(), mjOBJ_GEOM, "u");
  const int gc = mj_name2id(m.get(), mjOBJ_GEOM, "cube");

  // Native: the hull covers the cavity.
  const DataPtr native(mj_makeData(m.get()));
  mj_forward(m.get(), native.get());
  const auto hull = contacts_between(native.get(), gu, gc);
  ASSERT_EQ(hull.size(), 1u);
  EXPECT_LT(hull[0]->dist, 0.0);

  // Ours: asked, searched, nothing.
  ScopedInstall scope;
  RegistryConfig config;
  config.patterns = {{"u", "cube"}};
  Registry registry(m.get(), config);
  const Attachment attached = attach(registry);
  const DataPtr d(mj_makeData(m.get()));
  mj_forward(m.get(), d.get());
  EXPECT_EQ(registry.stats().calls, 1u);
  EXPECT_GT(registry.stats().counters.box_tests, 0u);
  EXPECT_TRUE(contacts_between(d.get(), gu, gc).empty());
  std::printf(
      "cavity: native hull contact %.4f m deep; ours none (%llu box tests, %llu tri tests)\n",
      -hull[0]->dist, static_cast<unsigned long long>(registry.stats().counters.box_tests),
      static_cast<unsigned long long>(registry.stats().counters.tri_tests));

  // Into the right wall (inner face x = 0.04): 5 mm deep, normal along x.
  const int q = m->jnt_qposadr[m->body_jntadr[m->geom_bodyid[gc]]];
  d->qpos[q] = 0.035;
  registry.reset_stats();
  mj_forward(m.get(), d.get());
  const auto wall = contacts_between(d.get(), gu, gc);
  ASSERT_FALSE(wall.empty());
  for (const mjContact* c : wall) {
    // From the U toward the cube is -x; from the cube toward the U is +x.
    const double toward_geom2 = c->geom1 == gu ? -c->frame[0] : c->frame[0];
    EXPECT_GT(toward_geom2, 0.99);
    EXPECT_NEAR(c->dist, -0.005, 1e-6);
  }
}

// The containment check (docs/design.md "Semantics"): a small cube wholly inside a big closed cube
// gets no contact (the surfaces do not meet, as CGAL would say) but is reported as contained;
// moved through the big cube's wall it gets contacts and is not contained; moved outside, neither.
const char* kNestedScene = R"(
<mujoco>
  <size nconmax="200" njmax="800"/>
  <option gravity="0 0 0"/>
  <asset><mesh name="big" file="big.obj"/><mesh name="small" file="small.obj"/></asset>
  <worldbody>
    <geom name="big" type="mesh" mesh="big"/>
    <body name="probe"><freejoint/><geom name="small" type="mesh" mesh="small"/></body>
  </worldbody>
</mujoco>)";

TEST(Containment, ASegmentWhollyInsideIsReportedNotContacted) {
  TempDir dir;
  const ModelPtr m = load_scene(dir, kNestedScene,
                                {{"big", testing::make_box_mesh(0.05, 0.05, 0.05)},
                                 {"small", testing::make_box_mesh(0.01, 0.01, 0.01)}});
  ASSERT_TRUE(m);
  const int gb = mj_name2id(m.get(), mjOBJ_GEOM, "big");
  const int gs = mj_name2id(m.get(), mjOBJ_GEOM, "small");
  ScopedInstall scope;
  RegistryConfig config;
  config.patterns = {{"small", "big"}};
  Registry registry(m.get(), config);
  const Attachment attached = attach(registry);
  ASSERT_EQ(registry.pairs().size(), 1u);
  for (const auto& [mesh, tree] :
       std::vector<std::pair<int, const MeshTree*>>{{m->geom_dataid[gb], registry.geom_tree(gb)},
                                                    {m->geom_dataid[gs], registry.geom_tree(gs)}}) {
    ASSERT_TRUE(tree) << mesh;
    EXPECT_TRUE(tree->closedness.closed()) << tree->closedness.describe();
  }
  const DataPtr d(mj_makeData(m.get()));
  const int q = m->jnt_qposadr[m->body_jntadr[m->geom_bodyid[gs]]];
  struct Case {
    double x;
    bool contacts;
    bool contained;
  };
  // Inside (centre, and 1 mm from the wall), through the wall, outside but within MuJoCo's
  // bounding spheres, so that the pair is still served.
  for (const Case c : {Case{0.0, false, true}, Case{0.039, false, true}, Case{0.045, true, false},
                       Case{0.065, false, false}}) {
    d->qpos[q] = c.x;
    registry.reset_stats();
    mj_forward(m.get(), d.get());
    ASSERT_EQ(registry.stats().calls, 1u) << c.x;
    EXPECT_EQ(!contacts_between(d.get(), gb, gs).empty(), c.contacts) << c.x;
    EXPECT_EQ(registry.find_pair_state(d.get(), 0)->contained, c.contained) << c.x;
    EXPECT_EQ(registry.stats().contained, c.contained ? 1u : 0u) << c.x;
  }
}

// Containment needs a closed solid: inside an open mesh it is not checked. The registry says so
// in one warning, and the pair still gets its surface contacts.
TEST(Containment, InsideAnOpenMeshIsNotCheckedAndTheRegistryWarns) {
  TempDir dir;
  TriangleMesh open = testing::make_box_mesh(0.05, 0.05, 0.05);
  // Without the top's two triangles (make_prism lists each cap triangle top, then bottom).
  open.faces.erase(open.faces.begin() + 2);
  open.faces.erase(open.faces.begin());
  const ModelPtr m = load_scene(
      dir, kNestedScene, {{"big", open}, {"small", testing::make_box_mesh(0.01, 0.01, 0.01)}});
  ASSERT_TRUE(m);
  const int gb = mj_name2id(m.get(), mjOBJ_GEOM, "big");
  const int gs = mj_name2id(m.get(), mjOBJ_GEOM, "small");
  ScopedInstall scope;
  RegistryConfig config;
  config.patterns = {{"small", "big"}};
  Registry registry(m.get(), config, "nested.json");
  const Attachment attached = attach(registry);
  ASSERT_FALSE(registry.geom_tree(gb)->closedness.closed());
  ASSERT_EQ(registry.warnings().size(), 1u);
  EXPECT_EQ(registry.warnings()[0],
            "nested.json: mesh " + std::to_string(m->geom_dataid[gb]) +
                " 'big' is not closed: 4 boundary edges (10 faces); containment inside it is not "
                "checked (surface contacts only)");
  const DataPtr d(mj_makeData(m.get()));
  const int q = m->jnt_qposadr[m->body_jntadr[m->geom_bodyid[gs]]];
  for (const double x : {0.0, 0.045}) {  // inside (not decided), through the wall (contacts)
    d->qpos[q] = x;
    registry.reset_stats();
    mj_forward(m.get(), d.get());
    ASSERT_EQ(registry.stats().calls, 1u) << x;
    EXPECT_EQ(!contacts_between(d.get(), gb, gs).empty(), x > 0) << x;
    EXPECT_FALSE(registry.find_pair_state(d.get(), 0)->contained) << x;
    EXPECT_EQ(registry.stats().contained, 0u) << x;
  }
}

// The solver can use our contacts: under gravity along -y, a cube released in the U's cavity
// falls onto the cavity floor (y = 0.01) and rests there, between the walls, for 1.5 s. With
// MuJoCo's native collision the cube starts 5 cm deep inside the convex hull and is thrown out.
const char* kDropScene = R"(
<mujoco>
  <size nconmax="200" njmax="800"/>
  <option gravity="0 -9.81 0" timestep="0.002"/>
  <asset><mesh name="u" file="u.obj"/><mesh name="cube" file="cube.obj"/></asset>
  <worldbody>
    <geom name="u" type="mesh" mesh="u"/>
    <body name="probe" pos="0.005 0.05 0"><freejoint/><geom name="cube" type="mesh" mesh="cube"/></body>
  </worldbody>
</mujoco>)";

TEST(Dynamics, CubeFallsIntoTheCavityAndRestsOnItsFloor) {
  TempDir dir;
  const ModelPtr m = load_scene(dir, kDropScene,
                                {{"u", testing::make_u_mesh(0.05, 0.08, 0.01, 0.03)},
                                 {"cube", testing::make_box_mesh(0.01, 0.01, 0.01)}});
  ASSERT_TRUE(m);
  const int body = mj_name2id(m.get(), mjOBJ_BODY, "probe");
  const auto run = [&](bool served, double seconds) {
    DataPtr d(mj_makeData(m.get()));
    std::unique_ptr<ScopedInstall> install;
    std::unique_ptr<Registry> registry;
    Attachment attached;
    if (served) {
      install = std::make_unique<ScopedInstall>();
      RegistryConfig config;
      config.patterns = {{"u", "cube"}};
      registry = std::make_unique<Registry>(m.get(), config);
      attached = attach(*registry);
    }
    while (d->time < seconds) mj_step(m.get(), d.get());
    return d;
  };
  // Ours: on the floor of the cavity (centre at y = 0.01 + 0.01), between the walls, at rest.
  const DataPtr ours = run(true, 1.5);
  const double* p = ours->xpos + 3 * body;
  EXPECT_NEAR(p[1], 0.02, 0.002);
  EXPECT_LT(std::abs(p[0]), 0.03);
  EXPECT_LT(std::abs(p[2]), 0.02);
  const double* v = ours->cvel + 6 * body;  // [angular, linear]
  EXPECT_LT(Vec3(v[3], v[4], v[5]).norm(), 0.01);
  // Native: the hull throws the cube out of the cavity (it never reaches the floor).
  const DataPtr native = run(false, 1.5);
  const double* q = native->xpos + 3 * body;
  std::printf("cube after 1.5 s: ours (%.4f, %.4f, %.4f), native hull (%.4f, %.4f, %.4f)\n", p[0],
              p[1], p[2], q[0], q[1], q[2]);
  EXPECT_GT(std::abs(q[0] - p[0]) + std::abs(q[1] - p[1]) + std::abs(q[2] - p[2]), 0.02);
}

// A cube dropped 2 cm onto a fixed cube (both meshes, served) comes to rest on its top face.
TEST(Dynamics, CubeStacksOnACube) {
  TempDir dir;
  const ModelPtr m = load_scene(dir, R"(
<mujoco>
  <size nconmax="200" njmax="800"/>
  <option timestep="0.002"/>
  <asset><mesh name="cube" file="cube.obj"/></asset>
  <worldbody>
    <geom name="base" type="mesh" mesh="cube"/>
    <body name="top" pos="0.01 -0.005 0.1" euler="0 0 0.3"><freejoint/>
      <geom name="top" type="mesh" mesh="cube"/></body>
  </worldbody>
</mujoco>)",
                                {{"cube", testing::make_box_mesh(0.04, 0.04, 0.04)}});
  ASSERT_TRUE(m);
  ScopedInstall scope;
  RegistryConfig config;
  config.patterns = {{"base", "top"}};
  Registry registry(m.get(), config);
  const Attachment attached = attach(registry);
  const DataPtr d(mj_makeData(m.get()));
  std::uint64_t steps = 0;
  while (d->time < 1.5) {
    mj_step(m.get(), d.get());
    ++steps;
  }
  const int body = mj_name2id(m.get(), mjOBJ_BODY, "top");
  EXPECT_NEAR(d->xpos[3 * body + 2], 0.08, 0.002);
  EXPECT_NEAR(d->xpos[3 * body], 0.01, 0.005);
  const BridgeStats st = registry.take_stats();
  EXPECT_EQ(registry.stats().calls, 0u);  // taken and reset
  EXPECT_GE(st.calls, steps / 2);         // touching from ~0.14 s on
  EXPECT_GT(st.contacts, 0u);
  EXPECT_LE(st.contacts, 8 * st.calls) << "the default budget of 8 per pair";
  std::printf("stacked cube: z %.5f; per step %.1f contacts, %.1f us detection\n",
              d->xpos[3 * body + 2], static_cast<double>(st.contacts) / static_cast<double>(steps),
              static_cast<double>(st.detection_ns) / static_cast<double>(steps) / 1e3);
}

// A real non-convex object (../shared/models, skipped when absent): a ball dropped into a
// plastic bowl (720 faces, closed and outward) rests on the bowl's inner bottom with our
// contacts; MuJoCo's convex hull holds it above the rim.
TEST(Dynamics, BallRestsInsideARealBowl) {
  const std::filesystem::path bowl =
      std::filesystem::path(GRASPCD_MODELS_DIR) / "objects/prl_assets/plastic_bowl_visual.obj";
  if (!std::filesystem::exists(bowl)) GTEST_SKIP() << "no real models at " << bowl;
  TempDir dir;
  const std::string xml = R"(
<mujoco>
  <size nconmax="200" njmax="800"/>
  <option timestep="0.002"/>
  <asset><mesh name="bowl" file=")" +
                          bowl.string() +
                          R"("/><mesh name="ball" file="ball.obj"/></asset>
  <worldbody>
    <geom name="bowl" type="mesh" mesh="bowl"/>
    <body name="ball" pos="0.01 0 0.12"><freejoint/><geom name="ball" type="mesh" mesh="ball"/></body>
  </worldbody>
</mujoco>)";
  const ModelPtr m = load_scene(dir, xml, {{"ball", testing::make_uv_sphere(0.015, 12, 16)}});
  ASSERT_TRUE(m);
  const int body = mj_name2id(m.get(), mjOBJ_BODY, "ball");
  const auto final_z = [&](bool served) {
    std::unique_ptr<ScopedInstall> install;
    std::unique_ptr<Registry> registry;
    Attachment attached;
    if (served) {
      install = std::make_unique<ScopedInstall>();
      RegistryConfig config;
      config.patterns = {{"bowl", "ball"}};
      registry = std::make_unique<Registry>(m.get(), config);
      attached = attach(*registry);
    }
    DataPtr d(mj_makeData(m.get()));
    while (d->time < 2.0) mj_step(m.get(), d.get());
    // Ours comes to rest in the bowl (on the flat hull top the native ball may still roll).
    const double* v = d->cvel + 6 * body;
    if (served) {
      EXPECT_LT(Vec3(v[3], v[4], v[5]).norm(), 0.02);
    }
    return d->xpos[3 * body + 2];
  };
  const double ours = final_z(true), native = final_z(false);
  std::printf("ball in bowl after 2 s: ours z = %.4f, native hull z = %.4f (rim at 0.076)\n", ours,
              native);
  // The inner bottom lies at z ~ 0.008-0.010: the ball's centre 1.5 cm above it.
  EXPECT_GT(ours, 0.015);
  EXPECT_LT(ours, 0.035);
  EXPECT_GT(native, 0.076);
}

}  // namespace
}  // namespace graspcd::mujoco
