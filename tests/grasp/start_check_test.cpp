// grasp/start_check.h on small scenes: a cube object (closed OBJ, 2 cm) resting on a floor, sunk
// into it, inside a box "finger", wholly inside one, and a finger wholly inside a large object;
// and a ring with a finger through its hole, which the true mesh lets start but its convex hull
// (native collision) does not, nor the hulls of the ring cut in two halves (a decomposition's
// pieces), while the hulls of its quarters do. And the deepest probe of a surface inside a hollow
// solid (grasp/surface_cache.h), which both checks measure, against every probe tested alone.
#include "graspcd/grasp/start_check.h"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "graspcd/core/penetration.h"
#include "graspcd/grasp/surface_cache.h"
#include "graspcd/io/mesh_io.h"
#include "graspcd/io/warnings.h"
#include "helpers/ring_mesh.h"
#include "helpers/temp_dir.h"

namespace graspcd::grasp {
namespace {

// A closed cube of half-extent h (OBJ, outward faces), its centre at the origin.
std::string cube_obj(double h) {
  std::string out;
  for (int k = 0; k < 8; ++k) {
    out += "v " + std::to_string(k & 1 ? h : -h) + ' ' + std::to_string(k & 2 ? h : -h) + ' ' +
           std::to_string(k & 4 ? h : -h) + '\n';
  }
  return out +
         "f 1 3 2\nf 2 3 4\nf 5 6 7\nf 6 8 7\nf 1 2 5\nf 2 6 5\n"
         "f 3 7 4\nf 4 7 8\nf 1 5 3\nf 3 5 7\nf 2 4 6\nf 4 8 6\n";
}

class StartCheckTest : public testing::TempDirTest {
 protected:
  // The check on a scene: the object (a cube of half-extent `h` at `object_pos`) over a floor,
  // and a box "finger" of half-extents `finger_half` at `finger_pos`.
  std::string check(double h, const std::string& object_pos, const std::string& finger_pos,
                    const std::string& finger_half = "0.005 0.005 0.02") {
    write("cube.obj", cube_obj(h));
    const std::string scene =
        write("s.xml",
              "<mujoco><compiler meshdir=\".\"/><asset><mesh name=\"cube\" file=\"cube.obj\"/>"
              "</asset><worldbody><geom name=\"floor\" type=\"plane\" size=\"1 1 0.1\"/>"
              "<body name=\"finger\" pos=\"" +
                  finger_pos + "\"><geom name=\"finger\" type=\"box\" size=\"" + finger_half +
                  "\"/></body><body name=\"object\" pos=\"" + object_pos +
                  "\"><freejoint/><geom name=\"cube\" type=\"mesh\" mesh=\"cube\"/></body>"
                  "</worldbody></mujoco>");
    char error[1000] = "";
    mjModel* m = mj_loadXML(scene.c_str(), nullptr, error, sizeof error);
    EXPECT_NE(m, nullptr) << error;
    if (m == nullptr) return "no model";
    mjData* d = mj_makeData(m);
    mj_forward(m, d);
    const std::string problem = check_start_state(m, d, mj_name2id(m, mjOBJ_BODY, "object"));
    mj_deleteData(d);
    mj_deleteModel(m);
    return problem;
  }
};

TEST_F(StartCheckTest, AnObjectRestingOnTheFloorClearOfTheFingerPasses) {
  EXPECT_EQ(check(0.01, "0 0 0.0104", "0.1 0 0.05"), "");
  // Touching the finger's face (x = 0.095) and 0.4 mm into the floor: within 0.5 mm.
  EXPECT_EQ(check(0.01, "0.085 0 0.0096", "0.1 0 0.05"), "");
}

TEST_F(StartCheckTest, AnObjectSunkIntoTheFloorIsRefusedWithItsDepth) {
  // Its centre 1 cm below the floor's plane: the lowest point 2 cm deep.
  const std::string problem = check(0.01, "0 0 -0.01", "0.1 0 0.05");
  EXPECT_EQ(problem,
            "geom 'cube' of the object lies 20.0 mm below the plane geom 'floor' (at most 0.5 mm "
            "allowed): put its lowest point on the support");
  EXPECT_NE(check(0.01, "0 0 0.0094", "0.1 0 0.05"), "");  // 0.6 mm
}

TEST_F(StartCheckTest, AnObjectInsideAFingerIsRefusedWithTheDeepestPoint) {
  // A wide finger (1 x 3 x 4 cm): its face at x = 0.095, the cube's corners at x = 0.097 inside
  // it, 2 mm deep.
  EXPECT_EQ(check(0.01, "0.087 0 0.0104", "0.1 0 0.0104", "0.005 0.015 0.02"),
            "geom 'cube' of the object penetrates geom 'finger' by 2.0 mm (at most 0.5 mm "
            "allowed)");
  // A thin finger (1 x 1 x 4 cm) across the cube's edge, 2 mm deep, with no vertex of either
  // inside the other: found along the edges.
  EXPECT_EQ(check(0.01, "0.087 0 0.0104", "0.1 0 0.0104"),
            "geom 'cube' of the object penetrates geom 'finger' by 2.0 mm (at most 0.5 mm "
            "allowed)");
}

TEST_F(StartCheckTest, ObjectsWhollyInsideEitherWayAreRefused) {
  // A 2 mm cube in a 1 x 1 x 4 cm finger (its vertices 4 mm inside, the surfaces apart).
  EXPECT_EQ(check(0.001, "0.1 0 0.05", "0.1 0 0.05"),
            "geom 'cube' of the object lies wholly inside geom 'finger'");
  // A 5 mm finger in a 10 cm cube.
  EXPECT_EQ(check(0.05, "0 0 0.0504", "0 0 0.05", "0.0025 0.0025 0.0025"),
            "geom 'finger' lies wholly inside the object (geom 'cube' of the object)");
}

class RingStartTest : public testing::TempDirTest {
 protected:
  // The ring (r_in 2 cm, r_out 3 cm, 2 cm tall) as the object, in `pieces` pieces (meshes
  // ring__piece_K, the names graspcd grasp --decomposed gives them; 1: the whole ring, mesh
  // 'ring'), and a box finger 8 x 8 x 40 mm through its hole. Returns check_start_state's and
  // check_hull_start's messages.
  std::pair<std::string, std::string> check(int pieces) {
    const double kTwoPi = 2 * std::acos(-1.0);
    std::string assets, geoms;
    for (int k = 0; k < pieces; ++k) {
      const std::string name = pieces == 1 ? "ring" : "ring__piece_" + std::to_string(k);
      write(name + ".obj", testing::ring_obj(0.02, 0.03, 0.01, kTwoPi * k / pieces,
                                             kTwoPi * (k + 1) / pieces, 32 / pieces));
      assets += "<mesh name=\"" + name + "\" file=\"" + name + ".obj\"/>";
      geoms += "<geom name=\"" + name + "\" type=\"mesh\" mesh=\"" + name + "\"/>";
    }
    const std::string scene =
        write("ring.xml", "<mujoco><compiler meshdir=\".\"/><asset>" + assets +
                              "</asset><worldbody><body name=\"finger\"><geom name=\"finger\" "
                              "type=\"box\" size=\"0.004 0.004 0.02\"/></body>"
                              "<body name=\"object\"><freejoint/>" +
                              geoms + "</body></worldbody></mujoco>");
    char error[1000] = "";
    mjModel* m = mj_loadXML(scene.c_str(), nullptr, error, sizeof error);
    EXPECT_NE(m, nullptr) << error;
    if (m == nullptr) return {"no model", "no model"};
    mjData* d = mj_makeData(m);
    mj_forward(m, d);
    const int object = mj_name2id(m, mjOBJ_BODY, "object");
    std::pair<std::string, std::string> out{check_start_state(m, d, object),
                                            check_hull_start(m, d, object)};
    mj_deleteData(d);
    mj_deleteModel(m);
    return out;
  }
};

TEST_F(RingStartTest, AFingerThroughTheHoleStartsOnTheTrueMeshButNotInsideTheHull) {
  const auto [truth, hull] = check(1);
  EXPECT_EQ(truth, "");
  // The finger's edges lie inside the hull (a 32-gon prism) up to its top and bottom, 10 mm away.
  EXPECT_EQ(hull,
            "MuJoCo collides mesh 'ring' as its convex hull, which geom 'finger' lies 10.0 mm "
            "inside at the start");
}

TEST_F(RingStartTest, PiecesAreCheckedByTheirOwnHulls) {
  // Quarters: each hull reaches 14 mm from the axis, the finger's corners 5.7 mm.
  EXPECT_EQ(check(4), std::make_pair(std::string(), std::string()));
  // Halves: each hull is closed by the plane through the axis, which the 8 mm finger crosses.
  const auto [truth, hull] = check(2);
  EXPECT_EQ(truth, "");
  EXPECT_EQ(hull, "geom 'finger' lies 4.0 mm inside piece 0 of mesh 'ring' at the start");
}

// deepest_probe_inside against every probe tested alone (core's deepest_point_inside: the exact
// inside test and the distance to the surface of each): the same deepest depth, and a bound at
// least it, for a small ring placed at random through the wall and the hole of a large one. The
// hole lies inside the solid's boxes, so its probes reach the inside test, which the search
// answers for most of them from a ball free of the surface around an earlier probe.
TEST_F(RingStartTest, TheDeepestProbeIsTheDeepestOfEveryProbeTestedAlone) {
  const double kTwoPi = 2 * std::acos(-1.0);
  const double kSpacing = 1e-3, kFloor = 5e-4;
  const GeomSurface solid(posed_triangles(
      io::load_mesh(write("ring.obj", testing::ring_obj(0.02, 0.03, 0.01, 0, kTwoPi, 48))),
      Pose{}));
  const GeomSurface probed(posed_triangles(
      io::load_mesh(write("link.obj", testing::ring_obj(0.004, 0.012, 0.006, 0, kTwoPi, 24))),
      Pose{}));
  ASSERT_TRUE(solid.closed());
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::vector<Vec3> placed;
  int deep = 0, shallow = 0;
  for (int k = 0; k < 150; ++k) {
    const Vec3 axis = Vec3(unit(random), unit(random), unit(random)).normalized();
    const Pose pose{Eigen::AngleAxisd(3 * unit(random), axis).toRotationMatrix(),
                    Vec3(0.045 * unit(random), 0.045 * unit(random), 0.02 * unit(random))};
    const ProbeDepth found = deepest_probe_inside(solid, probed, pose, kSpacing, kFloor, placed);
    std::vector<Vec3> every;
    for (const Vec3& p : probed.probes(kSpacing).points) every.push_back(apply_pose(pose, p));
    const double truth = deepest_point_inside(solid.tree(), every).depth;
    if (truth > kFloor) {
      ++deep;
      EXPECT_EQ(found.depth, truth) << "pose " << k;
    } else {
      ++shallow;
      EXPECT_EQ(found.depth, 0) << "pose " << k;
    }
    EXPECT_GE(found.bound, truth) << "pose " << k;
  }
  // The poses reach both answers.
  EXPECT_GE(deep, 30);
  EXPECT_GE(shallow, 30) << deep;
}

}  // namespace
}  // namespace graspcd::grasp
