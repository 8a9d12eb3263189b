// A hand of one's own grasping (docs/hands.md): a YCB box held by the Allegro hand through
// `--hand allegro`, and through the Allegro hand's Menagerie file with its drive file
// (`--hand right_hand.xml --drive mjcf/allegro_right_hand.drive.json`), the scene written around
// the hand file unchanged. Release pass only (label slow).
#include "app/cli_helpers.h"

namespace {

using namespace graspcd::cli_testing;

const fs::path kAllegro = fs::path(GRASPCD_MODELS_DIR) / "hands" / "wonik_allegro";
const fs::path kBox = fs::path(GRASPCD_MODELS_DIR) / "objects" / "ycb" / YCB_OBJECT;

// The verdict of a held grasp, from its numbers.
void expect_held(const nlohmann::json& doc) {
  EXPECT_TRUE(doc["gripped"]) << doc["reason"];
  EXPECT_TRUE(doc["held"]) << doc["reason"];
  EXPECT_TRUE(doc["reason"].is_null()) << doc["reason"];
  EXPECT_GE(doc["object_rise"].get<double>(), 0.8 * doc["hand_travel"].get<double>());
  EXPECT_LT(doc["hold_drift"].get<double>(), 0.01);
}

TEST_F(CliTest, AllegroHandHoldsAYcbBox) {
  if (!fs::exists(kAllegro / "right_hand.xml") || !fs::exists(kBox)) {
    GTEST_SKIP() << "Allegro hand or YCB object not in " << GRASPCD_MODELS_DIR;
  }
  const Result r = run("grasp --object " + kBox.string() + " --hand allegro --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["object"]["hand"], "allegro");
  expect_held(doc);
}

TEST_F(CliTest, AHandFileWithItsDriveIsWrappedAndHolds) {
  if (!fs::exists(kAllegro / "right_hand.xml") || !fs::exists(kBox)) {
    GTEST_SKIP() << "Allegro hand or YCB object not in " << GRASPCD_MODELS_DIR;
  }
  const std::string hand = (kAllegro / "right_hand.xml").string();
  const std::string drive = GRASPCD_MJCF_DIR "/allegro_right_hand.drive.json";
  const std::string before = read_file(hand);
  const fs::path kept = dir_ / "kept";
  const Result r = run("grasp --object " + kBox.string() + " --hand " + hand + " --drive " + drive +
                       " --json --write-scene " + kept.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_held(nlohmann::json::parse(r.out));
  // The hand file is included unchanged; the kept scene names it and the drive.
  EXPECT_EQ(read_file(hand), before);
  const std::string scene = read_file(kept / (kBox.stem().string() + ".xml"));
  const auto shown = [](const std::string& f) {
    return fs::absolute(f).lexically_normal().string();
  };
  EXPECT_NE(scene.find("the hand file " + shown(hand)), std::string::npos) << scene.substr(0, 600);
  EXPECT_NE(scene.find("with the drive " + shown(drive)), std::string::npos)
      << scene.substr(0, 600);
}

}  // namespace
