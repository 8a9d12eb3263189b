// The start rule of run_grasp (grasp.h): each configuration is checked against the geometry it
// collides. Example 2 with the can replaced by a wide ring (radii 20 and 22 cm, 2 cm tall) around
// the open fingers: graspcd's contacts (the true ring) start it, MuJoCo's native collision (the
// ring's convex hull, a disc through the fingers) is refused with the hull named as the limit, and
// so is the ring cut in two halves by a decomposition (--decomposed: each half's hull closes
// across the hole).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "graspcd/grasp/decomposed_scene.h"
#include "graspcd/grasp/grasp.h"
#include "helpers/ring_mesh.h"
#include "helpers/temp_dir.h"

namespace graspcd::grasp::start_rule_test {
namespace {

const std::string kMjcf = GRASPCD_MJCF_DIR;

class StartRule : public testing::TempDirTest {
 protected:
  // The scene, its pair config (example 2's) beside it; the ring's OBJ is ring.obj.
  std::string ring_scene() {
    std::ifstream in(kMjcf + "/example2.xml");
    std::stringstream text;
    text << in.rdbuf();
    std::string xml = text.str();
    const std::string ring = write("ring.obj", ring_obj(0, kTwoPi, 32));
    replace(xml, "meshdir=\"meshes\"", "meshdir=\"" + kMjcf + "/meshes\"");
    replace(xml, "file=\"can.obj\"", "file=\"" + ring + "\"");
    replace(xml, "<body name=\"object\" pos=\"0.000000 0.000000 0.000000\">",
            "<body name=\"object\" pos=\"0 0 0.06\">");
    std::filesystem::copy_file(kMjcf + "/example2.pairs.json", dir_ / "ring.pairs.json");
    return write("ring.xml", xml);
  }

  static std::string ring_obj(double a0, double a1, int n) {
    return testing::ring_obj(0.2, 0.22, 0.01, a0, a1, n);
  }

  static void replace(std::string& text, const std::string& from, const std::string& to) {
    const std::size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  }

  // A short grasp: the start is what is tested.
  static GraspOptions options(bool native) {
    GraspOptions o;
    o.native = native;
    o.max_steps = 5;
    o.settle_time = 0.05;
    o.lift_time = 0.05;
    o.hold_time = 0.05;
    return o;
  }

  const double kTwoPi = 2 * std::acos(-1.0);
};

TEST_F(StartRule, GraspcdStartsTheRingButNativeCollisionIsRefusedByItsHull) {
  const std::string scene = ring_scene();
  EXPECT_NO_THROW(run_grasp(scene, options(false)));
  try {
    run_grasp(scene, options(true));
    ADD_FAILURE() << "a native start inside the hull ran";
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.file(), scene);
    // The finger's edges lie inside the ring's hull (a 32-gon prism) up to its top and bottom,
    // 10 mm away; MuJoCo collides the finger's mesh as its hull too.
    EXPECT_EQ(e.message(),
              "cannot start with --native: MuJoCo collides mesh 'can' as its convex hull, which "
              "the hull of geom 'finger1_B' lies 10.0 mm inside at the start (a limit of the "
              "hull, not of the scene; graspcd's contacts start this scene)");
  }
}

TEST_F(StartRule, TheDecomposedRingIsRefusedByThePiecesHulls) {
  const std::string scene = ring_scene();
  const std::string pieces = (dir_ / "halves").string();
  std::filesystem::create_directory(pieces);
  write("halves/piece_0.obj", ring_obj(0, kTwoPi / 2, 16));
  write("halves/piece_1.obj", ring_obj(kTwoPi / 2, kTwoPi, 16));
  write("halves/decomposition.json",
        "{\"source\": \"" + (dir_ / "ring.obj").string() +
            "\", \"pieces\": [{\"file\": \"piece_0.obj\"}, {\"file\": \"piece_1.obj\"}]}");
  try {
    run_decomposed_grasp(scene, pieces, options(false));
    ADD_FAILURE() << "a decomposed start inside a piece's hull ran";
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.file(), scene);
    // The halves meet in the plane y = 0, which each half's hull closes: finger 2's middle
    // segment straddles it, 8 mm wide.
    EXPECT_EQ(e.message(), "with " + pieces +
                               ": cannot start with --decomposed: the hull of geom 'finger2_B' "
                               "lies 8.0 mm inside piece 0 of mesh 'can' (" +
                               pieces +
                               "/piece_0.obj) at the start (a limit of the "
                               "pieces, not of the scene; graspcd's contacts start this scene)");
  }
}

}  // namespace
}  // namespace graspcd::grasp::start_rule_test
