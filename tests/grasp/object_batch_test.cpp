// A batch of grasps of one object (object_batch.h): the scene compiled once and the object moved
// between grasps gives each grasp the verdicts and measures of its placement run alone, in a
// scene compiled with the object there; the placements come from the seed alone.
#include "graspcd/grasp/object_batch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "graspcd/grasp/grasp_output.h"
#include "graspcd/grasp/hand_templates.h"
#include "graspcd/grasp/object_run.h"
#include "helpers/temp_dir.h"

namespace graspcd::grasp::object_batch_test {
namespace {

const std::string kMjcf = GRASPCD_MJCF_DIR;

// A 3 x 3 x 4 cm block, its faces outward, in metres.
const char* const kBlock =
    "v -0.015 -0.015 -0.02\nv 0.015 -0.015 -0.02\nv 0.015 0.015 -0.02\nv -0.015 0.015 -0.02\n"
    "v -0.015 -0.015 0.02\nv 0.015 -0.015 0.02\nv 0.015 0.015 0.02\nv -0.015 0.015 0.02\n"
    "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
    "f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";

// A short grasp: 20 closing steps, short squeeze, settling, lift and hold.
GraspOptions short_grasp() {
  GraspOptions options;
  options.max_steps = 20;
  options.squeeze_time = 0.02;
  options.settle_time = 0.05;
  options.lift_time = 0.1;
  options.hold_time = 0.1;
  options.true_penetration = true;
  return options;
}

// The grasp's document without what the clock measures (the detection times and the cost).
nlohmann::json verdicts(const GraspResult& r) {
  nlohmann::json doc = grasp_json(r);
  for (const char* timed : {"cost", "steps", "detection_ns_close", "detection_ns_total",
                            "ms_per_physics_step", "cpu_ms_per_physics_step"}) {
    doc.erase(timed);
  }
  return doc;
}

class ObjectBatchTest : public testing::TempDirTest {};

TEST_F(ObjectBatchTest, EachGraspGivesTheVerdictsOfItsPlacementRunAlone) {
  ObjectBatchOptions options;
  options.run.file = write("block.obj", kBlock);
  options.run.hand = hand_template(kMjcf + "/example1.xml");
  options.grasp = short_grasp();
  ObjectPlacement base;
  base.file = options.run.file;
  BatchPlacementOptions draw;
  draw.count = 2;
  draw.seed = 7;
  draw.ups = {"z", "x"};
  const std::vector<ObjectPlacement> placements = draw_placements(base, draw);
  ASSERT_EQ(placements.size(), 2u);
  // Two different places, so that the second grasp moves the object.
  EXPECT_NE(placements[0].offset, placements[1].offset);
  options.first = placements[0];

  ObjectBatch batch(options);
  std::vector<BatchGrasp> grasps;
  for (const ObjectPlacement& p : placements) grasps.push_back(batch.grasp(p));
  for (std::size_t k = 0; k < placements.size(); ++k) {
    SCOPED_TRACE("placement " + std::to_string(k));
    ASSERT_EQ(grasps[k].outcome, BatchOutcome::kGrasped) << grasps[k].refusal;
    ObjectRun alone({options.run.file, options.run.hand, "", false});
    alone.write(placements[k]);
    EXPECT_EQ(alone.description().scene.pos, grasps[k].placed.pos);
    EXPECT_EQ(alone.description().scene.quat, grasps[k].placed.quat);
    const GraspResult single = alone.grasp(short_grasp());
    EXPECT_GT(single.physics_steps, 0);
    EXPECT_EQ(verdicts(grasps[k].result), verdicts(single));
  }
  // The batch's own parts go with its first grasp only.
  EXPECT_GT(grasps[0].result.cost[CostPart::kCompile].cpu_s, 0);
  EXPECT_EQ(grasps[1].result.cost[CostPart::kCompile].cpu_s, 0);
  EXPECT_GT(grasps[1].result.cost[CostPart::kPhysics].cpu_s, 0);
}

TEST(DrawPlacements, AreTheSeedsAloneAndAPlacementDependsOnItsIndexOnly) {
  ObjectPlacement base;
  base.file = "x.obj";
  BatchPlacementOptions draw;
  draw.count = 5;
  draw.seed = 3;
  const std::vector<ObjectPlacement> five = draw_placements(base, draw);
  draw.count = 2;
  const std::vector<ObjectPlacement> two = draw_placements(base, draw);
  for (std::size_t k = 0; k < two.size(); ++k) {
    EXPECT_EQ(two[k].up, five[k].up);
    EXPECT_EQ(two[k].yaw_degrees, five[k].yaw_degrees);
    EXPECT_EQ(two[k].offset, five[k].offset);
  }
  for (const ObjectPlacement& p : five) {
    EXPECT_GE(p.yaw_degrees, 0);
    EXPECT_LT(p.yaw_degrees, 360);
    EXPECT_LE(std::hypot(p.offset[0], p.offset[1]), draw.max_offset);
  }
  draw.seed = 4;
  EXPECT_NE(draw_placements(base, draw)[0].yaw_degrees, five[0].yaw_degrees);
  draw.ups = {"up"};
  EXPECT_THROW(draw_placements(base, draw), std::invalid_argument);
}

}  // namespace
}  // namespace graspcd::grasp::object_batch_test
