// The generated scenes in mjcf/ (mjcf/generator/generate_scenes.py): every scene loads; the arm and
// hand have the same kinematics in every scene (3 arm hinges, 4 fingers x 3 segments named
// finger{1..4}_{A,B,C}, a motor per joint); the box hand's segments are boxes and the triangle
// hand's are meshes of 100-5000 faces; every mesh is closed and consistently outward-oriented; the
// non-convex objects are non-convex (a point of the convex hull lies outside the mesh); each
// scene's pair config serves 12 segments x the object's geoms; and closing the fingers in grasp
// steps of 0.003 rad makes them touch the object (through graspcd for the triangle hand).
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "graspcd/mujoco/collision.h"
#include "graspcd/mujoco/mujoco_ptr.h"
#include "graspcd/mujoco/registry.h"

namespace graspcd::grasp::scenes_test {
namespace {

const std::string kMjcf = GRASPCD_MJCF_DIR;
const std::vector<std::string> kTriangleScenes = {"hand_triangles", "example1", "example2",
                                                  "example3", "concave_project_thinbox"};
// Every scene whose start MuJoCo's native collision can simulate (concave_project_thinbox starts
// with the thumb inside the box's convex hull: its tests are in concave_hands_test.cpp).
const std::vector<std::string> kAllScenes = {"hand_boxes", "hand_triangles", "example1", "example2",
                                             "example3"};
constexpr double kGraspStep = 0.003;  // rad, the paper's grasp step
constexpr int kSegments = 12;

mujoco::ModelPtr load(const std::string& scene) {
  const std::string file = kMjcf + "/" + scene + ".xml";
  char error[1024] = "";
  mujoco::ModelPtr m(mj_loadXML(file.c_str(), nullptr, error, sizeof(error)));
  if (!m) ADD_FAILURE() << file << ": " << error;
  return m;
}

std::vector<std::string> segment_names() {
  std::vector<std::string> out;
  for (int i = 1; i <= 4; ++i) {
    for (const char* s : {"A", "B", "C"}) out.push_back("finger" + std::to_string(i) + "_" + s);
  }
  return out;
}

int id(const mjModel* m, mjtObj type, const std::string& name) {
  return mj_name2id(m, type, name.c_str());
}

bool is_finger_geom(const mjModel* m, int g, const std::string& prefix = "finger") {
  const char* n = mj_id2name(m, mjOBJ_GEOM, g);
  return n && std::string(n).rfind(prefix, 0) == 0;
}
// Geoms of bodies whose name starts with `prefix` (the objects).
std::vector<int> object_geoms(const mjModel* m, const std::string& prefix) {
  std::vector<int> out;
  for (int g = 0; g < m->ngeom; ++g) {
    const char* n = mj_id2name(m, mjOBJ_BODY, m->geom_bodyid[g]);
    if (n && std::string(n).rfind(prefix, 0) == 0) out.push_back(g);
  }
  return out;
}

using P3 = std::array<double, 3>;

// The faces of mesh `mesh` in world coordinates as placed by geom `g` (after mj_forward).
std::vector<std::array<P3, 3>> world_faces(const mjModel* m, const mjData* d, int g) {
  const int mesh = m->geom_dataid[g];
  std::vector<std::array<P3, 3>> out;
  for (int f = 0; f < m->mesh_facenum[mesh]; ++f) {
    std::array<P3, 3> t{};
    for (int k = 0; k < 3; ++k) {
      const int v = m->mesh_vertadr[mesh] + m->mesh_face[3 * (m->mesh_faceadr[mesh] + f) + k];
      const float* p = m->mesh_vert + 3 * v;
      for (int r = 0; r < 3; ++r) {
        t[k][r] = d->geom_xpos[3 * g + r];
        for (int c = 0; c < 3; ++c) t[k][r] += d->geom_xmat[9 * g + 3 * r + c] * p[c];
      }
    }
    out.push_back(t);
  }
  return out;
}

P3 sub(const P3& a, const P3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
P3 cross(const P3& a, const P3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const P3& a, const P3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Ray parity: how many faces the ray p + t dir (t > 0) crosses (Moller-Trumbore). Odd: inside.
int crossings(const std::vector<std::array<P3, 3>>& faces, const P3& p, const P3& dir) {
  int n = 0;
  for (const auto& t : faces) {
    const P3 e1 = sub(t[1], t[0]), e2 = sub(t[2], t[0]);
    const P3 h = cross(dir, e2);
    const double a = dot(e1, h);
    if (std::abs(a) < 1e-15) continue;
    const P3 s = sub(p, t[0]);
    const double u = dot(s, h) / a;
    if (u < 0 || u > 1) continue;
    const P3 q = cross(s, e1);
    const double v = dot(dir, q) / a;
    if (v < 0 || u + v > 1) continue;
    if (dot(e2, q) / a > 0) ++n;
  }
  return n;
}

// A generic direction (no face is hit on an edge in practice).
const P3 kRayDir = {0.3141592653589793, 0.2718281828459045, 0.9102961894582719};

// A point of the convex hull of a mesh: the midpoint of two vertices of extreme world x (those
// nearest the y of `centre`) in the band of mid-height.
P3 hull_point(const std::vector<std::array<P3, 3>>& faces, const P3& centre) {
  double zmin = 1e9, zmax = -1e9;
  for (const auto& t : faces) {
    for (const P3& p : t) zmin = std::min(zmin, p[2]), zmax = std::max(zmax, p[2]);
  }
  const double zmid = (zmin + zmax) / 2, band = 0.1 * (zmax - zmin);
  const auto better = [&](const P3& p, const P3& best, double sign) {
    const double dx = sign * (p[0] - best[0]);
    return dx > 1e-12 ||
           (dx > -1e-12 && std::abs(p[1] - centre[1]) < std::abs(best[1] - centre[1]));
  };
  P3 lo{1e9, 0, 0}, hi{-1e9, 0, 0};
  for (const auto& t : faces) {
    for (const P3& p : t) {
      if (std::abs(p[2] - zmid) > band) continue;
      if (better(p, lo, -1)) lo = p;
      if (better(p, hi, 1)) hi = p;
    }
  }
  return {(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2};
}

// ---------------------------------------------------------------------------------------------

class EveryScene : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryScene, LoadsWithTheArmAndHandKinematics) {
  const mujoco::ModelPtr m = load(GetParam());
  ASSERT_TRUE(m);
  EXPECT_EQ(m->opt.timestep, 0.002);
  EXPECT_LT(m->opt.gravity[2], -9.0);
  EXPECT_GE(m->nconmax, 200);
  EXPECT_GE(m->njmax, 500);
  EXPECT_LE(m->njmax, 1000);
  // Three arm hinges, each the parent chain of the next.
  std::vector<std::string> joints = {"arm1", "arm2", "arm3"};
  for (const std::string& s : segment_names()) joints.push_back(s);
  int hinges = 0;
  for (const std::string& j : joints) {
    const int jid = id(m.get(), mjOBJ_JOINT, j);
    ASSERT_GE(jid, 0) << j;
    EXPECT_EQ(m->jnt_type[jid], mjJNT_HINGE) << j;
    ++hinges;
    // A motor named after the joint, gear 1, on that joint.
    const int a = id(m.get(), mjOBJ_ACTUATOR, j);
    ASSERT_GE(a, 0) << j;
    EXPECT_EQ(m->actuator_trntype[a], mjTRN_JOINT);
    EXPECT_EQ(m->actuator_trnid[2 * a], jid);
    EXPECT_EQ(m->actuator_gear[6 * a], 1.0);
    EXPECT_EQ(m->actuator_gaintype[a], mjGAIN_FIXED);
    EXPECT_EQ(m->actuator_biastype[a], mjBIAS_NONE);
  }
  EXPECT_EQ(hinges, 15);
  EXPECT_EQ(m->nu, 15);
  // Segments: A on the palm, B on A, C on B; each body carries its geom of the same name.
  const int palm = id(m.get(), mjOBJ_BODY, "palm");
  ASSERT_GE(palm, 0);
  for (int i = 1; i <= 4; ++i) {
    int parent = palm;
    for (const char* s : {"A", "B", "C"}) {
      const std::string n = "finger" + std::to_string(i) + "_" + s;
      const int b = id(m.get(), mjOBJ_BODY, n);
      ASSERT_GE(b, 0) << n;
      EXPECT_EQ(m->body_parentid[b], parent) << n;
      const int g = id(m.get(), mjOBJ_GEOM, n);
      ASSERT_GE(g, 0) << n;
      EXPECT_EQ(m->geom_bodyid[g], b);
      parent = b;
    }
  }
  // The arm chain ends at the palm; the object is a free body.
  EXPECT_EQ(m->body_parentid[palm], id(m.get(), mjOBJ_BODY, "link3"));
  const int object = id(m.get(), mjOBJ_BODY, "object");
  ASSERT_GE(object, 0);
  ASSERT_EQ(m->body_jntnum[object], 1);
  EXPECT_EQ(m->jnt_type[m->body_jntadr[object]], mjJNT_FREE);
}

// Fingers collide with objects, not with each other or the palm.
TEST_P(EveryScene, ContactFilterLetsFingersTouchObjectsOnly) {
  const mujoco::ModelPtr m = load(GetParam());
  ASSERT_TRUE(m);
  const auto collide = [&](int a, int b) {
    return (m->geom_contype[a] & m->geom_conaffinity[b]) ||
           (m->geom_contype[b] & m->geom_conaffinity[a]);
  };
  const int palm = id(m.get(), mjOBJ_GEOM, "palm");
  const auto objects = object_geoms(m.get(), "object");
  ASSERT_FALSE(objects.empty());
  for (const std::string& s : segment_names()) {
    const int g = id(m.get(), mjOBJ_GEOM, s);
    EXPECT_FALSE(collide(g, palm)) << s;
    for (const std::string& t : segment_names())
      EXPECT_FALSE(collide(g, id(m.get(), mjOBJ_GEOM, t)));
    for (int o : objects) EXPECT_TRUE(collide(g, o)) << s;
    EXPECT_EQ(m->geom_margin[g], 0.0);
  }
  for (int o : objects) EXPECT_TRUE(collide(o, id(m.get(), mjOBJ_GEOM, "floor")));
}

// At rest: with the arm and fingers held by gravity compensation (qfrc_applied = qfrc_bias), half
// a second of simulation leaves the object resting where it stands (it starts on the floor) and
// MuJoCo reports no instability.
TEST_P(EveryScene, ObjectRestsOnTheFloorAndTheSceneIsStable) {
  const mujoco::ModelPtr m = load(GetParam());
  ASSERT_TRUE(m);
  const mujoco::DataPtr d(mj_makeData(m.get()));
  const int object = id(m.get(), mjOBJ_BODY, "object");
  mj_forward(m.get(), d.get());
  const P3 start = {d->xpos[3 * object], d->xpos[3 * object + 1], d->xpos[3 * object + 2]};
  const int free_dofs = m->jnt_dofadr[m->body_jntadr[object]];
  for (int i = 0; i < 250; ++i) {
    for (int v = 0; v < m->nv; ++v) {
      d->qfrc_applied[v] = (v >= free_dofs && v < free_dofs + 6) ? 0.0 : d->qfrc_bias[v];
    }
    mj_step(m.get(), d.get());
  }
  const P3 end = {d->xpos[3 * object], d->xpos[3 * object + 1], d->xpos[3 * object + 2]};
  EXPECT_LT(std::sqrt(dot(sub(end, start), sub(end, start))), 0.002);
  EXPECT_EQ(d->warning[mjWARN_BADQACC].number, 0);
  EXPECT_EQ(d->warning[mjWARN_CONTACTFULL].number, 0);
  EXPECT_EQ(d->warning[mjWARN_CNSTRFULL].number, 0);
  // The hand held its pose: the arm joints moved by less than 0.01 rad.
  for (const char* j : {"arm1", "arm2", "arm3"}) {
    EXPECT_LT(std::abs(d->qpos[m->jnt_qposadr[id(m.get(), mjOBJ_JOINT, j)]]), 0.01) << j;
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, EveryScene, ::testing::ValuesIn(kAllScenes));

TEST(SceneBoxHand, SegmentsAndObjectAreBoxes) {
  const mujoco::ModelPtr m = load("hand_boxes");
  ASSERT_TRUE(m);
  for (const std::string& s : segment_names()) {
    EXPECT_EQ(m->geom_type[id(m.get(), mjOBJ_GEOM, s)], mjGEOM_BOX) << s;
  }
  const auto objects = object_geoms(m.get(), "object");
  EXPECT_EQ(objects.size(), 3u);
  for (int g : objects) EXPECT_EQ(m->geom_type[g], mjGEOM_BOX);
  EXPECT_EQ(m->nmesh, 0);
}

class TriangleScene : public ::testing::TestWithParam<std::string> {};

TEST_P(TriangleScene, SegmentsAreMeshesOfAFewHundredToAFewThousandFaces) {
  const mujoco::ModelPtr m = load(GetParam());
  ASSERT_TRUE(m);
  for (const std::string& s : segment_names()) {
    const int g = id(m.get(), mjOBJ_GEOM, s);
    ASSERT_EQ(m->geom_type[g], mjGEOM_MESH) << s;
    const int faces = m->mesh_facenum[m->geom_dataid[g]];
    EXPECT_GE(faces, 100) << s;
    EXPECT_LE(faces, 5000) << s;
  }
  for (int g : object_geoms(m.get(), "object")) {
    ASSERT_EQ(m->geom_type[g], mjGEOM_MESH);
    EXPECT_LE(m->mesh_facenum[m->geom_dataid[g]], 5000);
  }
}

// Each undirected edge is used by exactly two faces, once in each direction, after welding the
// vertices by exact coordinates; the signed volume is positive (outward normals).
TEST_P(TriangleScene, EveryMeshIsClosedAndConsistentlyOutward) {
  const mujoco::ModelPtr m = load(GetParam());
  ASSERT_TRUE(m);
  ASSERT_GT(m->nmesh, 3);
  for (int mesh = 0; mesh < m->nmesh; ++mesh) {
    const char* name = mj_id2name(m.get(), mjOBJ_MESH, mesh);
    std::map<std::array<float, 3>, int> weld;
    const auto vid = [&](int v) {
      const float* p = m->mesh_vert + 3 * (m->mesh_vertadr[mesh] + v);
      return weld.emplace(std::array<float, 3>{p[0], p[1], p[2]}, static_cast<int>(weld.size()))
          .first->second;
    };
    std::map<std::pair<int, int>, int> directed;
    double volume6 = 0;
    for (int f = 0; f < m->mesh_facenum[mesh]; ++f) {
      const int* face = m->mesh_face + 3 * (m->mesh_faceadr[mesh] + f);
      std::array<int, 3> w{};
      std::array<P3, 3> p{};
      for (int k = 0; k < 3; ++k) {
        w[k] = vid(face[k]);
        const float* q = m->mesh_vert + 3 * (m->mesh_vertadr[mesh] + face[k]);
        p[k] = {q[0], q[1], q[2]};
      }
      for (int k = 0; k < 3; ++k) ++directed[{w[k], w[(k + 1) % 3]}];
      volume6 += dot(p[0], cross(p[1], p[2]));
    }
    int bad = 0;
    for (const auto& [e, n] : directed) {
      const auto rev = directed.find({e.second, e.first});
      bad += n != 1 || rev == directed.end() || rev->second != 1;
    }
    EXPECT_EQ(bad, 0) << name << ": directed edges not used exactly once with their reverse";
    EXPECT_GT(volume6, 0) << name;
    // Euler characteristic 2 (a sphere's topology): V - E + F with E = half the directed edges.
    EXPECT_EQ(static_cast<long>(weld.size()) - static_cast<long>(directed.size() / 2) +
                  m->mesh_facenum[mesh],
              2)
        << name;
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, TriangleScene, ::testing::ValuesIn(kTriangleScenes));

// The cup, the bowl and the C-block: a point of the convex hull (between two wall vertices) lies
// outside the mesh by ray parity, where MuJoCo's native (convex hull) collision would see solid.
// The can, the control: the same construction gives a point inside.
TEST(SceneObjects, CupBowlAndCBlockAreNonConvexTheCanIsNot) {
  const mujoco::ModelPtr m = load("hand_triangles");
  ASSERT_TRUE(m);
  const mujoco::DataPtr d(mj_makeData(m.get()));
  mj_forward(m.get(), d.get());
  for (const auto& [geom, convex] : std::vector<std::pair<std::string, bool>>{
           {"object", false}, {"object_bowl", false}, {"object_can", true}}) {
    const int g = id(m.get(), mjOBJ_GEOM, geom);
    ASSERT_GE(g, 0) << geom;
    const auto faces = world_faces(m.get(), d.get(), g);
    const P3 centre = {d->geom_xpos[3 * g], d->geom_xpos[3 * g + 1], d->geom_xpos[3 * g + 2]};
    const P3 p = hull_point(faces, centre);
    const int n = crossings(faces, p, kRayDir);
    EXPECT_EQ(n % 2, convex ? 1 : 0) << geom << ": " << n << " crossings";
    // And a point just above the centre of the bottom is inside the solid only for the can.
    const P3 axis = {centre[0], centre[1], 0.012};
    EXPECT_EQ(crossings(faces, axis, kRayDir) % 2, convex ? 1 : 0) << geom;
  }
}

// The pair config beside each scene: 12 segments x the object's geoms. The triangle scenes build
// a Registry from it; the box scene's patterns are checked by glob (box geoms are not served by
// the registry yet).
TEST(ScenePairConfigs, ServeEverySegmentAgainstEveryObjectGeom) {
  for (const std::string& scene : kAllScenes) {
    SCOPED_TRACE(scene);
    const mujoco::ModelPtr m = load(scene);
    ASSERT_TRUE(m);
    const std::string path = kMjcf + "/" + scene + ".pairs.json";
    mujoco::RegistryConfig config;
    ASSERT_NO_THROW(config = mujoco::load_registry_config(path));
    ASSERT_EQ(config.patterns.size(), 1u);
    const std::string b = config.patterns[0].b;
    ASSERT_EQ(b.rfind("body:", 0), 0u);
    std::size_t object_count = 0;
    for (int g = 0; g < m->ngeom; ++g) {
      object_count +=
          mujoco::glob_match(b.substr(5), mj_id2name(m.get(), mjOBJ_BODY, m->geom_bodyid[g])
                                              ? mj_id2name(m.get(), mjOBJ_BODY, m->geom_bodyid[g])
                                              : "");
    }
    EXPECT_EQ(object_count, scene == "hand_boxes" ? 3u : scene == "hand_triangles" ? 4u : 1u);
    std::size_t finger_count = 0;
    ASSERT_EQ(config.patterns[0].a.rfind("geom:", 0), 0u);
    for (int g = 0; g < m->ngeom; ++g) {
      const char* n = mj_id2name(m.get(), mjOBJ_GEOM, g);
      finger_count += n && mujoco::glob_match(config.patterns[0].a.substr(5), n);
    }
    EXPECT_EQ(finger_count, static_cast<std::size_t>(kSegments));
    if (scene == "hand_boxes") continue;
    std::unique_ptr<mujoco::Registry> registry;
    ASSERT_NO_THROW(registry = std::make_unique<mujoco::Registry>(m.get(), config, path));
    EXPECT_EQ(registry->pairs().size(), kSegments * object_count);
    EXPECT_TRUE(registry->warnings().empty());
    EXPECT_EQ(registry->tree_count(), 3u + object_count);  // finger_A/B/C + one per object mesh
  }
}

// Sets every finger hinge to `angle` and runs mj_forward; returns the contacts between a finger
// segment (whose geom name starts with `prefix`) and an object geom.
int finger_object_contacts(const mjModel* m, mjData* d, double angle,
                           const std::string& prefix = "finger") {
  mj_resetData(m, d);
  for (const std::string& s : segment_names()) {
    d->qpos[m->jnt_qposadr[id(m, mjOBJ_JOINT, s)]] = angle;
  }
  mj_forward(m, d);
  const auto objects = object_geoms(m, "object");
  const std::set<int> obj(objects.begin(), objects.end());
  int n = 0;
  for (int i = 0; i < d->ncon; ++i) {
    const mjContact& c = d->contact[i];
    n += (is_finger_geom(m, c.geom1, prefix) && obj.count(c.geom2)) ||
         (is_finger_geom(m, c.geom2, prefix) && obj.count(c.geom1));
  }
  return n;
}

// Closing in grasp steps: open at step 0, touching after some steps (returns the first step).
int first_contact_step(const mjModel* m, mjData* d, const std::string& prefix = "finger") {
  EXPECT_EQ(finger_object_contacts(m, d, 0.0, prefix), 0) << "fingers touch the object while open";
  for (int step = 1; step * kGraspStep <= 1.6; ++step) {
    if (finger_object_contacts(m, d, step * kGraspStep, prefix) > 0) return step;
  }
  return -1;
}

TEST(SceneGrasp, ClosingTheBoxHandTouchesTheObject) {
  const mujoco::ModelPtr m = load("hand_boxes");
  ASSERT_TRUE(m);
  const mujoco::DataPtr d(mj_makeData(m.get()));
  const int step = first_contact_step(m.get(), d.get());
  std::printf("hand_boxes: first finger-object contact at grasp step %d\n", step);
  EXPECT_GT(step, 5);
}

TEST(SceneGrasp, ClosingTheTriangleHandTouchesTheObjectThroughTheBridge) {
  mujoco::ScopedInstall scope;
  for (const std::string& scene : kTriangleScenes) {
    SCOPED_TRACE(scene);
    const mujoco::ModelPtr m = load(scene);
    ASSERT_TRUE(m);
    mujoco::Registry registry(m.get(),
                              mujoco::load_registry_config(kMjcf + "/" + scene + ".pairs.json"));
    const mujoco::Attachment attached = mujoco::attach(registry);
    const mujoco::DataPtr d(mj_makeData(m.get()));
    const int step = first_contact_step(m.get(), d.get());
    std::printf("%s: first finger-object contact at grasp step %d\n", scene.c_str(), step);
    EXPECT_GT(step, 5);
    EXPECT_GT(registry.stats().contacts, 0u);  // the contacts came from graspcd
  }
}

// Example 3, where the convex hull is wrong: finger 2 closes into the C-block's slot. MuJoCo's
// native (convex hull) collision has it touch the object when it reaches the slot's mouth;
// graspcd, answering on the real surface, only when it reaches the slot's back wall, later.
TEST(SceneGrasp, InExample3TheBridgeLetsFinger2IntoTheSlotWhereTheHullIsSolid) {
  const mujoco::ModelPtr m = load("example3");
  ASSERT_TRUE(m);
  const mujoco::DataPtr d(mj_makeData(m.get()));
  const int native = first_contact_step(m.get(), d.get(), "finger2_");
  int ours = -1;
  {
    mujoco::ScopedInstall scope;
    mujoco::Registry registry(m.get(),
                              mujoco::load_registry_config(kMjcf + "/example3.pairs.json"));
    const mujoco::Attachment attached = mujoco::attach(registry);
    ours = first_contact_step(m.get(), d.get(), "finger2_");
  }
  std::printf("example3, finger 2: first contact at grasp step %d natively, %d with graspcd\n",
              native, ours);
  EXPECT_GT(native, 5);
  EXPECT_GT(ours, native + 10);
}

}  // namespace
}  // namespace graspcd::grasp::scenes_test
