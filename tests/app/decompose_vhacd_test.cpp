// `graspcd decompose --engine vhacd` through the executable: V-HACD 4 (node and the npm package
// vhacd-js of tools/vhacd) cuts a closed ring into at most N convex, closed pieces that do not
// fill the hole; the manifest names the engine and its parameters and is read back, and `graspcd
// grasp --decomposed` loads the pieces. Where node or vhacd-js is missing the engine is one line
// with exit code 2 (checked with PATH lacking node and with a missing script, which needs neither);
// the tests that run V-HACD are skipped there, saying so.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>

#include "graspcd/core/geometry.h"
#include "graspcd/decompose/manifest.h"
#include "graspcd/decompose/vhacd.h"
#include "graspcd/io/mesh_io.h"
#include "helpers/command_test.h"
#include "helpers/convex_check.h"
#include "helpers/envelope_check.h"
#include "helpers/ring_mesh.h"

namespace graspcd::testing {
namespace {

namespace fs = std::filesystem;

const fs::path kModels = GRASPCD_MODELS_DIR;

class DecomposeVhacd : public CommandTest {
 protected:
  void SetUp() override {
    CommandTest::SetUp();
    // A closed ring (radii 3 and 5 cm, 2 cm thick, 24 segments): its hull fills the hole, which
    // adds 56% to its volume.
    ring_ = write("ring.obj", ring_obj(0.03, 0.05, 0.01, 0, 2 * std::acos(-1.0), 24));
  }

  // Skips the test where V-HACD cannot run here.
  static std::string missing() { return decompose::vhacd_missing(decompose::VhacdOptions{}); }

  std::string ring_;
};

#define SKIP_WITHOUT_VHACD()                                                              \
  if (const std::string why = missing(); !why.empty()) {                                  \
    GTEST_SKIP() << "the V-HACD engine cannot run here (" << why << "): run ./run build"; \
  }

// The coarsest --resolution keeps the test short (about 1.5 s of V-HACD).
TEST_F(DecomposeVhacd, RingPiecesAreConvexClosedAndLoad) {
  SKIP_WITHOUT_VHACD();
  const int max_pieces = 6;
  const fs::path out = dir_ / "ring6";
  const fs::path json = dir_ / "ring6.json";
  const Outcome r = run(std::string("{ '") + GRASPCD_EXE + "' decompose '" + ring_ + "' --out '" +
                        out.string() + "' --engine vhacd --pieces " + std::to_string(max_pieces) +
                        " --resolution 10000 --json > '" + json.string() + "'; }");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json doc = load(json);
  expect_envelope(doc, -1);
  EXPECT_EQ(doc.at("engine"), "vhacd");
  EXPECT_EQ(doc.at("engine_parameters").at("max_hulls"), max_pieces);
  EXPECT_EQ(doc.at("engine_parameters").at("voxel_resolution"), 10000);
  EXPECT_TRUE(doc.at("simplify").is_null());

  // At most N pieces, and more than one: one convex piece cannot follow a ring.
  const int pieces = doc.at("piece_count").get<int>();
  EXPECT_LE(pieces, max_pieces);
  EXPECT_GE(pieces, 2);
  ASSERT_EQ(doc.at("pieces").size(), static_cast<std::size_t>(pieces));
  for (const auto& p : doc.at("pieces")) {
    const std::string file = (out / p.at("file").get<std::string>()).string();
    io::MeshStats stats;
    const TriangleMesh hull = io::load_mesh(file, &stats);
    EXPECT_TRUE(stats.closedness.closed()) << file;
    EXPECT_EQ(hull.faces.size(), p.at("faces").get<std::size_t>()) << file;
    expect_convex(hull, 1e-9, file);
  }
  // The pieces leave the hole open: they add far less than the hull's 56%.
  ASSERT_TRUE(doc.at("volume").is_object());
  EXPECT_LT(doc.at("volume").at("added_fraction").get<double>(), 0.25);
  EXPECT_GT(doc.at("volume").at("pieces").get<double>(), 0.0);

  // The manifest is read back with its engine.
  const decompose::Manifest m = decompose::read_manifest(out.string());
  EXPECT_EQ(m.engine, "vhacd");
  EXPECT_EQ(m.pieces.size(), static_cast<std::size_t>(pieces));
  ASSERT_FALSE(m.engine_parameters.empty());

  // grasp --decomposed puts the pieces in place of the ring in a scene of the ring (one step).
  if (!fs::exists(kModels)) return;  // the scene's hand is one of the real models
  const fs::path scene = dir_ / "scene";
  const Outcome w = graspcd("grasp --object '" + ring_ + "' --fit --write-scene '" +
                            scene.string() + "' --max-steps 1");
  ASSERT_EQ(w.exit_code, 0) << w.err;
  const fs::path grasp_json = dir_ / "grasp.json";
  const Outcome g = run(std::string("{ '") + GRASPCD_EXE + "' grasp '" +
                        (scene / "ring.xml").string() + "' --decomposed '" + out.string() +
                        "' --max-steps 1 --json > '" + grasp_json.string() + "'; }");
  ASSERT_EQ(g.exit_code, 0) << g.err;
  const nlohmann::json grasp = load(grasp_json);
  EXPECT_EQ(grasp.at("decomposed").at("pieces"), pieces);
  EXPECT_EQ(grasp.at("decomposed").at("geoms"), 1);
}

// A timeout shorter than node's start: node is stopped, one line naming the mesh, exit code 2.
TEST_F(DecomposeVhacd, TimeoutStopsNode) {
  SKIP_WITHOUT_VHACD();
  const Outcome r = graspcd("decompose '" + ring_ + "' --out '" + (dir_ / "t").string() +
                            "' --engine vhacd --timeout 0.001");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err.find(ring_ + ": "), 0u) << r.err;
  EXPECT_NE(r.err.find("timeout"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "t" / decompose::kManifestFile));
}

// Without node, or without the script, --engine vhacd is one line saying what it needs, exit
// code 2, and nothing is written; HACD still runs under the same PATH.
TEST_F(DecomposeVhacd, MissingNodeOrScriptIsOneLine) {
  const std::string no_node = "PATH=" + (dir_ / "empty").string() + " ";
  const std::string no_script =
      "GRASPCD_VHACD_SCRIPT='" + (dir_ / "nowhere" / "vhacd.mjs").string() + "' ";
  for (const std::string& env : {no_node, no_script}) {
    const fs::path out = dir_ / "v";
    const Outcome r = run(env + "'" + GRASPCD_EXE + "' decompose '" + ring_ + "' --out '" +
                          out.string() + "' --engine vhacd");
    EXPECT_EQ(r.exit_code, 2) << env;
    EXPECT_EQ(r.err.find("graspcd: decompose: the V-HACD engine needs node and the vhacd-js "
                         "package"),
              0u)
        << r.err;
    EXPECT_NE(r.err.find(env == no_node ? "node is not on PATH" : "nowhere/vhacd.mjs"),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("./run build"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(out)) << env;
  }
  const Outcome hacd = run(no_node + "'" + GRASPCD_EXE + "' decompose '" + ring_ + "' --out '" +
                           (dir_ / "h").string() + "' --pieces 4");
  EXPECT_EQ(hacd.exit_code, 0) << hacd.err;
  EXPECT_EQ(decompose::read_manifest((dir_ / "h").string()).engine, "hacd");
}

// The options of one engine are refused with the other: one line naming the option, exit code 2.
TEST_F(DecomposeVhacd, OptionsOfTheOtherEngineAreRefused) {
  const std::pair<std::string, std::string> cases[] = {
      {"--engine vhacd --simplify 100", "--simplify"},
      {"--resolution 20000", "--resolution"},
      {"--engine hacd --timeout 5", "--timeout"},
      {"--engine vhacd2", "--engine"}};
  for (const auto& [args, option] : cases) {
    const Outcome r =
        graspcd("decompose '" + ring_ + "' --out '" + (dir_ / "o").string() + "' " + args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
    EXPECT_NE(r.err.find(option), std::string::npos) << args << ": " << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "o" / decompose::kManifestFile)) << args;
  }
}

}  // namespace
}  // namespace graspcd::testing
