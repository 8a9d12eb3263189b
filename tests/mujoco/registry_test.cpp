// The pair registry: glob patterns on geom and body names, the JSON config and its errors, and
// trees built once per mesh, only for meshes of served pairs.
#include "graspcd/mujoco/registry.h"

#include <gtest/gtest.h>

#include <fstream>

#include "graspcd/mujoco/primitives.h"
#include "helpers/scene_support.h"

namespace graspcd::mujoco {
namespace {

using testing::load_scene;
using testing::TempDir;

// Two finger segments sharing one box mesh, a U-shaped object with a visual-only box beside it,
// an unregistered mesh ball, a sphere primitive and a floor.
const char* kScene = R"(
<mujoco>
  <size nconmax="200" njmax="800"/>
  <asset>
    <mesh name="seg" file="seg.obj"/>
    <mesh name="u" file="u.obj"/>
    <mesh name="ball" file="ball.obj"/>
  </asset>
  <worldbody>
    <geom name="floor" type="plane" size="1 1 0.1"/>
    <body name="finger1" pos="0 0 0.5"><freejoint/><geom name="f1_a" type="mesh" mesh="seg"/></body>
    <body name="finger2" pos="0.2 0 0.5"><freejoint/><geom name="f2_a" type="mesh" mesh="seg"/></body>
    <body name="object" pos="0 0.3 0.5"><freejoint/>
      <geom name="cup" type="mesh" mesh="u"/>
      <geom name="label" type="box" size="0.01 0.01 0.01" pos="0 0 0.2" contype="0" conaffinity="0"/>
    </body>
    <body name="other" pos="0.5 0.5 0.5"><freejoint/>
      <geom name="marble" type="mesh" mesh="ball" margin="0.002"/></body>
    <body name="probe" pos="-0.5 0 0.5"><freejoint/><geom name="prim" type="sphere" size="0.02"/></body>
  </worldbody>
</mujoco>)";

class RegistryTest : public ::testing::Test {
 protected:
  void SetUp() override {
    model_ = load_scene(dir_, kScene,
                        {{"seg", testing::make_box_mesh(0.01, 0.01, 0.03)},
                         {"u", testing::make_u_mesh(0.05, 0.06, 0.01, 0.03)},
                         {"ball", testing::make_uv_sphere(0.02, 8, 12)}});
    ASSERT_TRUE(model_);
  }
  int geom(const char* name) const { return mj_name2id(model_.get(), mjOBJ_GEOM, name); }
  int mesh_of(const char* name) const { return model_->geom_dataid[geom(name)]; }

  // The message of the runtime_error a config raises, or "" when it raises none.
  std::string error_of(const std::string& json) const {
    try {
      Registry r(model_.get(), parse_registry_config(json, "hand.json"), "hand.json");
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "";
  }

  TempDir dir_;
  testing::ModelPtr model_;
};

TEST(GlobMatch, StarMatchesAnyRunAndOtherCharactersThemselves) {
  EXPECT_TRUE(glob_match("*", ""));
  EXPECT_TRUE(glob_match("f*_a", "f1_a"));
  EXPECT_TRUE(glob_match("f*_a", "f_a"));
  EXPECT_TRUE(glob_match("*cup*", "a cup here"));
  EXPECT_TRUE(glob_match("a*b*c", "axxbyybc"));
  EXPECT_FALSE(glob_match("f*_a", "f1_b"));
  EXPECT_FALSE(glob_match("cup", "cups"));
  EXPECT_FALSE(glob_match("cup*", "teacup"));
  EXPECT_FALSE(glob_match("", "x"));
}

TEST(RegistryConfig, ParsesEveryField) {
  const RegistryConfig c = parse_registry_config(
      R"({"method": "neurosat", "cap": 900, "switch": 40, "cache_slots": 64, "max_depth": 0.002,
          "max_contacts": 12, "max_patch_contacts": 3, "front_list": false,
          "contact_reuse": 5e-5, "reduction": "moment",
          "pairs": [{"a": "finger*", "b": "geom:cup"},
                    {"a": "palm", "b": "cup", "max_contacts": 2, "max_patch_contacts": 1}]})",
      "x.json");
  EXPECT_EQ(c.method, Method::kNeuroSat);
  EXPECT_EQ(c.detector.cap, 900);
  EXPECT_EQ(c.detector.switch_passes, 40);
  EXPECT_EQ(c.detector.cache_slots, 64u);
  EXPECT_DOUBLE_EQ(c.max_depth, 0.002);
  EXPECT_EQ(c.manifold.max_per_pair, 12);
  EXPECT_EQ(c.manifold.max_per_patch, 3);
  EXPECT_FALSE(c.front_list);
  EXPECT_DOUBLE_EQ(c.contact_reuse, 5e-5);
  EXPECT_EQ(c.manifold.reduction, ManifoldReduction::kMoment);
  ASSERT_EQ(c.patterns.size(), 2u);
  EXPECT_EQ(c.patterns[0].a, "finger*");
  EXPECT_EQ(c.patterns[0].b, "geom:cup");
  EXPECT_FALSE(c.patterns[0].max_contacts.has_value());
  EXPECT_EQ(c.patterns[1].max_contacts, 2);
  EXPECT_EQ(c.patterns[1].max_patch_contacts, 1);
  // The defaults (tolerances.h): 4 per patch, 8 per pair.
  const RegistryConfig d = parse_registry_config(R"({"pairs": [{"a": "x", "b": "y"}]})", "d.json");
  EXPECT_EQ(d.manifold.max_per_patch, 4);
  EXPECT_EQ(d.manifold.max_per_pair, 8);
  EXPECT_TRUE(d.front_list);
  // Contacts reused within 20 um unless a config asks for exact ones ("contact_reuse": 0).
  EXPECT_EQ(d.contact_reuse, RegistryConfig::kDefaultContactReuse);
  EXPECT_EQ(d.contact_reuse, 2e-5);
  EXPECT_EQ(d.manifold.reduction, ManifoldReduction::kSupport);
  EXPECT_EQ(
      parse_registry_config(R"({"reduction": "force", "pairs": [{"a": "x", "b": "y"}]})", "f.json")
          .manifold.reduction,
      ManifoldReduction::kForce);
}

// Each bad config gives one line that starts with the config's name.
TEST(RegistryConfig, ErrorsAreOneLineAndNameTheSource) {
  for (const char* bad : {
           R"({"pairs": [)",                        // bad JSON
           R"({"method": "magic", "pairs": []})",   // unknown method
           R"({"cap": 0, "pairs": []})",            // cap < 1
           R"({"max_depth": -1, "pairs": []})",     // depth <= 0
           R"({"colour": "red", "pairs": []})",     // unknown field
           R"({"method": "sat"})",                  // no pairs
           R"({"method": "sat", "pairs": []})",     // an empty pair list: nothing served
           R"({"cap": 2, "cap": 3, "pairs": []})",  // a key given twice
           R"({"pairs": [{"a": "x"}]})",            // pair without b
           R"([1, 2])",                             // not an object
           R"({"max_depth": 1e999, "pairs": []})",  // overflow: nlohmann's out_of_range 406
           R"({"cap": -1e400, "pairs": []})",
           R"({"max_contacts": 0, "pairs": []})",                       // below 1
           R"({"max_contacts": 51, "pairs": []})",                      // above mjMAXCONPAIR
           R"({"max_patch_contacts": 2.5, "pairs": []})",               // not an integer
           R"({"pairs": [{"a": "x", "b": "y", "max_contacts": -3}]})",  // per pair, below 1
           R"({"pairs": [{"a": "x", "b": "y", "colour": 1}]})",         // unknown pair field
           R"({"front_list": 1, "pairs": []})",                         // not a boolean
           R"({"contact_reuse": -1e-5, "pairs": []})",                  // negative
           R"({"contact_reuse": 0.002, "pairs": []})",                  // above 1 mm
           R"({"contact_reuse": "5e-5", "pairs": []})",                 // not a number
           R"({"reduction": "fewest", "pairs": []})",                   // unknown reduction
           R"({"reduction": 4, "pairs": []})",                          // not a string
       }) {
    try {
      parse_registry_config(bad, "cfg/hand.json");
      ADD_FAILURE() << "accepted: " << bad;
    } catch (const std::runtime_error& e) {
      const std::string what = e.what();
      // A syntax error, an overflowing number or a duplicate key also names its line
      // (json_config.h).
      EXPECT_TRUE(what.rfind("cfg/hand.json: ", 0) == 0 ||
                  what.rfind("cfg/hand.json:1: bad JSON: ", 0) == 0 ||
                  what.rfind("cfg/hand.json:1: duplicate key ", 0) == 0)
          << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
}

// nlohmann's reader stops at a NUL byte: a config with one is refused at its line, whatever
// follows it (here a key that is not UTF-8), never read as far as the NUL and accepted.
TEST(RegistryConfig, ANulByteIsRefusedAtItsLine) {
  const char raw[] = "{\"pairs\": [{\"a\": \"x\", \"b\": \"y\"}]}\n\0{\"\x86\": 1}";
  const std::string text(raw, sizeof raw - 1);
  try {
    parse_registry_config(text, "cfg/hand.json");
    ADD_FAILURE() << "accepted a config with a NUL byte";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "cfg/hand.json:2: a NUL byte in the config (byte 35)");
  }
}

TEST(RegistryConfig, LoadReadsAFileAndNamesItInErrors) {
  TempDir dir;
  const std::string good = (dir.path() / "good.json").string();
  std::ofstream(good) << R"({"method": "perceptron-warm", "pairs": [{"a": "f1_a", "b": "cup"}]})";
  EXPECT_EQ(load_registry_config(good).method, Method::kPerceptronWarm);
  const std::string bad = (dir.path() / "bad.json").string();
  std::ofstream(bad) << "{ nope";
  try {
    load_registry_config(bad);
    ADD_FAILURE() << "bad JSON accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind(bad + ":1: bad JSON: ", 0), 0u) << e.what();
  }
  const std::string missing = (dir.path() / "missing.json").string();
  EXPECT_THROW(load_registry_config(missing), std::runtime_error);
}

// Body patterns pick the body's collidable geoms (the visual-only label is skipped); geom
// patterns pick geoms; both fingers share one mesh, so two trees serve the two pairs.
TEST_F(RegistryTest, PatternsResolveToPairsAndTreesAreSharedPerMesh) {
  RegistryConfig c;
  c.patterns = {{"body:finger*", "body:object"}};
  const Registry r(model_.get(), c, "hand.json");
  ASSERT_EQ(r.pairs().size(), 2u);
  EXPECT_GE(r.find_pair(geom("f1_a"), geom("cup")), 0);
  EXPECT_GE(r.find_pair(geom("cup"), geom("f2_a")), 0);  // either order
  EXPECT_EQ(r.find_pair(geom("f1_a"), geom("f2_a")), -1);
  EXPECT_EQ(r.find_pair(geom("f1_a"), geom("marble")), -1);
  EXPECT_EQ(r.tree_count(), 2u);
  ASSERT_NE(r.tree(mesh_of("f1_a")), nullptr);
  EXPECT_EQ(r.tree(mesh_of("f1_a")), r.tree(mesh_of("f2_a")));
  EXPECT_NE(r.tree(mesh_of("cup")), nullptr);
  EXPECT_EQ(r.tree(mesh_of("marble")), nullptr);  // in no served pair: no tree
  EXPECT_TRUE(r.warnings().empty());
  // The tree holds every face of MuJoCo's mesh.
  EXPECT_EQ(static_cast<int>(r.tree(mesh_of("cup"))->tree.triangles().size()),
            model_->mesh_facenum[mesh_of("cup")]);
}

// Overlapping patterns and both orders collapse into unordered pairs; a geom never pairs with
// itself.
TEST_F(RegistryTest, DuplicatePairsCollapse) {
  RegistryConfig c;
  c.patterns = {{"geom:f*_a", "geom:f*_a"}, {"f2_a", "f1_a"}, {"cup", "marble"}};
  c.geom_pairs = {{geom("marble"), geom("cup")}};
  const Registry r(model_.get(), c);
  EXPECT_EQ(r.pairs().size(), 2u);  // (f1, f2) and (cup, marble)
  // Budgets: the first entry to register a pair decides.
  for (const ServedPair& p : r.pairs()) EXPECT_EQ(p.manifold.max_per_pair, 8);
  c.patterns[1].max_contacts = 3;
  c.patterns[2].max_contacts = 5;
  c.patterns[2].max_patch_contacts = 2;
  const Registry budgets(model_.get(), c);
  const ServedPair& fingers =
      budgets.pairs()[static_cast<std::size_t>(budgets.find_pair(geom("f1_a"), geom("f2_a")))];
  const ServedPair& marble =
      budgets.pairs()[static_cast<std::size_t>(budgets.find_pair(geom("cup"), geom("marble")))];
  EXPECT_EQ(fingers.manifold.max_per_pair, 8) << "registered first by the first entry";
  EXPECT_EQ(marble.manifold.max_per_pair, 5);
  EXPECT_EQ(marble.manifold.max_per_patch, 2);
  EXPECT_EQ(r.tree_count(), 3u);
  // The marble has a margin: one warning, naming it.
  ASSERT_EQ(r.warnings().size(), 1u);
  EXPECT_NE(r.warnings()[0].find("'marble' has margin"), std::string::npos) << r.warnings()[0];
}

TEST_F(RegistryTest, PatternErrorsNameTheConfig) {
  const std::string nothing = error_of(R"({"pairs": [{"a": "thumb*", "b": "cup"}]})");
  EXPECT_EQ(nothing.rfind("hand.json: pattern 'thumb*' matches no collidable geom", 0), 0u)
      << nothing;
  // Planes (and height fields) are not served: one line naming the config, pattern and geom.
  const std::string plane = error_of(R"({"pairs": [{"a": "floor", "b": "cup"}]})");
  EXPECT_EQ(plane.rfind("hand.json: pattern 'floor' matches geom", 0), 0u) << plane;
  EXPECT_NE(plane.find("'floor' of type plane, which graspcd does not serve"), std::string::npos)
      << plane;
  EXPECT_EQ(plane.find('\n'), std::string::npos) << plane;
  const std::string everything = error_of(R"({"pairs": [{"a": "*", "b": "cup"}]})");
  EXPECT_NE(everything.find("of type plane"), std::string::npos) << everything;
  // A primitive is served now (through its tessellation).
  EXPECT_EQ(error_of(R"({"pairs": [{"a": "body:probe", "b": "cup"}]})"), "");
  // The visual-only label alone is not collidable: nothing to serve.
  EXPECT_NE(error_of(R"({"pairs": [{"a": "label", "b": "cup"}]})").find("matches no collidable"),
            std::string::npos);
  // A pair whose two sides are the same single geom.
  EXPECT_NE(error_of(R"({"pairs": [{"a": "cup", "b": "geom:cup"}]})").find("no pair of distinct"),
            std::string::npos);
  EXPECT_EQ(error_of(R"({"pairs": [{"a": "f1_a", "b": "cup"}]})"), "");
}

// Primitives: box-box pairs take the exact path without trees; every other pair with a primitive
// takes the tree path through one tessellation per (type, size), shared by the geoms of equal
// shape; a box in a tree pair is its 12 triangles; the tessellation lives in the geom frame.
TEST(RegistryPrimitives, PathsAndTreesPerTypeAndSize) {
  TempDir dir;
  const testing::ModelPtr m = load_scene(dir, R"(
<mujoco>
  <asset><mesh name="u" file="u.obj"/></asset>
  <worldbody>
    <geom name="floor" type="plane" size="1 1 0.1"/>
    <body name="object" pos="0 0.3 0.5"><freejoint/><geom name="cup" type="mesh" mesh="u"/></body>
    <body name="tips" pos="0 0 0.5"><freejoint/>
      <geom name="tip1" type="sphere" size="0.008"/>
      <geom name="tip2" type="sphere" size="0.008" pos="0.05 0 0"/>
      <geom name="tip3" type="sphere" size="0.009" pos="0.1 0 0"/>
      <geom name="pad1" type="box" size="0.01 0.01 0.02" pos="0 0.1 0"/>
      <geom name="pad2" type="box" size="0.01 0.01 0.02" pos="0 0.2 0"/>
      <geom name="rod" type="capsule" size="0.005 0.02" pos="0 0.3 0"/>
    </body>
    <body name="brick" pos="1 0 0.5"><freejoint/><geom name="brick" type="box" size="0.02 0.03 0.04"/></body>
  </worldbody>
</mujoco>)",
                                         {{"u", testing::make_u_mesh(0.05, 0.06, 0.01, 0.03)}});
  ASSERT_TRUE(m);
  const auto id = [&](const char* name) { return mj_name2id(m.get(), mjOBJ_GEOM, name); };
  RegistryConfig c;
  c.patterns = {{"geom:tip*", "cup"}, {"geom:pad*", "brick"}, {"pad1", "rod"}};
  const Registry r(m.get(), c, "prims.json");
  ASSERT_EQ(r.pairs().size(), 6u);
  const auto path_of = [&](const char* a, const char* b) {
    const int i = r.find_pair(id(a), id(b));
    EXPECT_GE(i, 0) << a << " " << b;
    return r.pairs()[static_cast<std::size_t>(i)].path;
  };
  EXPECT_EQ(path_of("tip1", "cup"), PairPath::kTrees);
  EXPECT_EQ(path_of("pad1", "brick"), PairPath::kBoxBox);
  EXPECT_EQ(path_of("brick", "pad2"), PairPath::kBoxBox);
  EXPECT_EQ(path_of("rod", "pad1"), PairPath::kTrees);
  // Trees: the cup's mesh, sphere 0.008 (shared by tip1 and tip2), sphere 0.009, the capsule and
  // pad1's box (for the capsule pair). pad2 and brick are only in box-box pairs: no tree.
  EXPECT_EQ(r.tree_count(), 5u);
  EXPECT_EQ(r.primitive_tree_count(), 4u);
  ASSERT_NE(r.geom_tree(id("tip1")), nullptr);
  EXPECT_EQ(r.geom_tree(id("tip1")), r.geom_tree(id("tip2")));
  EXPECT_NE(r.geom_tree(id("tip1")), r.geom_tree(id("tip3")));
  EXPECT_EQ(r.geom_tree(id("cup")), r.tree(m->geom_dataid[id("cup")]));
  EXPECT_EQ(r.geom_tree(id("pad2")), nullptr);
  EXPECT_EQ(r.geom_tree(id("brick")), nullptr);
  EXPECT_EQ(r.geom_tree(id("floor")), nullptr);
  ASSERT_NE(r.geom_tree(id("pad1")), nullptr);
  EXPECT_EQ(r.geom_tree(id("pad1"))->tree.triangles().size(), 12u);
  // In the geom frame: the box's tree spans exactly its half-extents.
  Vec3 lo = Vec3::Constant(1e9), hi = Vec3::Constant(-1e9);
  for (const Triangle& t : r.geom_tree(id("pad1"))->tree.triangles()) {
    for (const Vec3& v : t.v) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
  }
  EXPECT_EQ(hi, Vec3(0.01, 0.01, 0.02));
  EXPECT_EQ(lo, Vec3(-0.01, -0.01, -0.02));
  // A sphere's tree lies around the origin, within radius (1 + tolerance).
  const double tip_reach = 0.008 * tess_round_factor();
  for (const Triangle& t : r.geom_tree(id("tip1"))->tree.triangles()) {
    for (const Vec3& v : t.v) EXPECT_LE(v.norm(), tip_reach);
  }
  // Direct geom pairs with a plane are refused too, naming the geom and its type.
  RegistryConfig direct;
  direct.geom_pairs = {{id("floor"), id("tip1")}};
  try {
    const Registry bad(m.get(), direct, "prims.json");
    ADD_FAILURE() << "a plane was accepted";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("prims.json: ", 0), 0u) << what;
    EXPECT_NE(what.find("'floor' of type plane"), std::string::npos) << what;
  }
}

// A tetrahedron with a fifth face that is a point (three equal vertices), beside a sphere.
constexpr const char* kTetWithAPointFace = R"(
<mujoco>
  <asset>
    <mesh name="tet" vertex="0 0 0  .1 0 0  0 .1 0  0 0 .1  .2 0 0  .2 0 0  .2 0 0"
          face="0 2 1  4 5 6  0 1 3  0 3 2  1 2 3"/>
  </asset>
  <worldbody>
    <body name="object" pos="0 0 0.5"><freejoint/><geom name="tet" type="mesh" mesh="tet"/></body>
    <body name="tip" pos="0.3 0 0.5"><freejoint/><geom name="tip" type="sphere" size="0.01"/></body>
  </worldbody>
</mujoco>)";

// Mesh hygiene in the MuJoCo layer: a MuJoCo mesh with a zero-area face (MuJoCo 2.2 keeps it) gets
// a tree without it, one warning naming the mesh and MuJoCo's face id, and a map from the tree's
// face ids to MuJoCo's.
TEST(RegistryHygiene, ZeroAreaFacesAreLeftOutOfTheTreeWithAWarning) {
  TempDir dir;
  const testing::ModelPtr m = load_scene(dir, kTetWithAPointFace, {});
  ASSERT_TRUE(m);
  ASSERT_EQ(m->mesh_facenum[0], 5);  // MuJoCo keeps face 4 5 6, a point (three equal vertices stay
                                     // equal through MuJoCo's recentring; collinear ones need not)
  RegistryConfig c;
  c.patterns = {{"geom:tip", "body:object"}};
  const Registry r(m.get(), c, "hyg.json");
  const MeshTree* t = r.tree(0);
  ASSERT_NE(t, nullptr);
  EXPECT_EQ(t->tree.triangles().size(), 4u);
  EXPECT_EQ(t->source_face, (std::vector<std::int32_t>{0, 2, 3, 4}));
  // Each tree face is MuJoCo's face source_face[f].
  const std::vector<Triangle> mujoco_faces = Registry::mesh_triangles(m.get(), 0);
  for (std::int32_t f = 0; f < 4; ++f) {
    const Triangle& mj =
        mujoco_faces[static_cast<std::size_t>(t->source_face[static_cast<std::size_t>(f)])];
    for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(t->face(f).v[k], mj.v[k]);
  }
  ASSERT_EQ(r.warnings().size(), 1u);
  EXPECT_EQ(r.warnings()[0],
            "hyg.json: mesh 0 'tet': dropped 1 zero-area faces (MuJoCo face ids, from 0: 1; each "
            "spans a segment or a point)");
  EXPECT_TRUE(t->closedness.closed()) << t->closedness.describe();
}

// A scene graspcd wrote (scene_names.h): the registry's messages name the config the user knows
// and call a mesh of the hand the hand's; the object's mesh is the user's file, whose reader
// (io::load_mesh) already reported its zero-area faces in the file's own face numbers, so the
// registry does not report them again.
TEST(RegistryHygiene, AWrittenScenesWarningsNameTheUsersFilesAndTheHandsMeshes) {
  TempDir dir;
  const testing::ModelPtr m = load_scene(dir, kTetWithAPointFace, {});
  ASSERT_TRUE(m);
  RegistryConfig c;
  c.patterns = {{"geom:tip", "body:object"}};
  SceneNames names;
  names.files = {{"/tmp/written/hyg.pairs.json", "template.pairs.json"}};
  names.hand = "the robotiq hand's ";
  names.object_mesh = "object_mesh";
  const Registry hand(m.get(), c, "/tmp/written/hyg.pairs.json", names);
  ASSERT_EQ(hand.warnings().size(), 1u);
  EXPECT_EQ(hand.warnings()[0].rfind("template.pairs.json: the robotiq hand's mesh 0 'tet': "
                                     "dropped 1 zero-area faces",
                                     0),
            0u)
      << hand.warnings()[0];
  names.object_mesh = "tet";
  const Registry object(m.get(), c, "/tmp/written/hyg.pairs.json", names);
  EXPECT_TRUE(object.warnings().empty()) << object.warnings()[0];
  try {
    c.patterns = {{"geom:tip", "geom:none*"}};
    const Registry refused(m.get(), c, "/tmp/written/hyg.pairs.json", names);
    FAIL() << "no exception";
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.file(), "template.pairs.json");
  }
}

}  // namespace
}  // namespace graspcd::mujoco
