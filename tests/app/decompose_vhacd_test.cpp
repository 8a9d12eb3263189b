// `graspcd decompose --engine vhacd` through the executable: V-HACD 4 (node and the npm package
// vhacd-js of tools/vhacd) cuts a closed ring into at most N convex, closed pieces that do not
// fill the hole; the manifest names the engine and its parameters and is read back, and `graspcd
// grasp --decomposed` loads the pieces. Where node or vhacd-js is missing the engine is one line
// with exit code 2 (checked with PATH lacking node and with a missing script, which needs neither);
// the tests that run V-HACD are skipped there, saying so.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
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
#include "helpers/processes.h"
#include "helpers/ring_mesh.h"

namespace graspcd::testing::decompose_vhacd_test {
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

// INT, TERM and HUP while node runs V-HACD: node dies with graspcd (it is not left running,
// orphaned), the temporary folder and the private output folder are removed, exit 128 + signal.
TEST_F(DecomposeVhacd, ASignalStopsNodeAndRemovesItsFolders) {
  SKIP_WITHOUT_VHACD();
  for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
    const fs::path tmp = dir_ / ("tmp" + std::to_string(sig));
    fs::create_directories(tmp);
    const fs::path out = dir_ / ("v" + std::to_string(sig));
    const pid_t pid =
        spawn(GRASPCD_EXE, {"decompose", ring_, "--out", out.string(), "--engine", "vhacd"},
              {"TMPDIR=" + tmp.string()}, (dir_ / "out.txt").string(), (dir_ / "err.txt").string());
    pid_t node = 0;
    const bool started = wait_for(
        [&] {
          for (const auto& [child, name] : children_of(pid)) {
            if (name == "node") node = child;
          }
          return node != 0;
        },
        60);
    kill(pid, sig);
    EXPECT_EQ(finish(pid, 60), 128 + sig) << read_file(dir_ / "err.txt");
    ASSERT_TRUE(started) << "node never started: " << read_file(dir_ / "err.txt");
    EXPECT_TRUE(wait_for([&] { return !process_runs(node); }, 10)) << "node runs on, orphaned";
    if (process_runs(node)) kill(node, SIGKILL);
    EXPECT_TRUE(fs::is_empty(tmp)) << sig;
    EXPECT_FALSE(fs::exists(out)) << sig;
    for (const auto& e : fs::directory_iterator(dir_)) {
      EXPECT_EQ(e.path().filename().string().rfind(".v", 0), std::string::npos) << e.path();
    }
  }
}

class FakeVhacd : public DecomposeVhacd {
 protected:
  // tools/vhacd/vhacd.mjs beside a stand-in for the vhacd-js package whose module is `module`,
  // named by GRASPCD_VHACD_SCRIPT; runs `decompose RING --engine vhacd` with it.
  Outcome run_with(const std::string& module, const std::string& extra = "") {
    const fs::path fake = dir_ / "fake";
    const fs::path lib = fake / "node_modules" / "vhacd-js" / "lib";
    fs::create_directories(lib);
    fs::copy_file(decompose::default_vhacd_script(), fake / "vhacd.mjs",
                  fs::copy_options::overwrite_existing);
    std::ofstream(fake / "node_modules" / "vhacd-js" / "package.json") << R"({"type": "module"})";
    std::ofstream(lib / "vhacd.js") << module;
    return run("{ GRASPCD_VHACD_SCRIPT='" + (fake / "vhacd.mjs").string() + "' '" + GRASPCD_EXE +
               "' decompose '" + ring_ + "' --out '" + (dir_ / "out").string() +
               "' --engine vhacd" + extra + "; }");
  }
  // A vhacd-js whose decomposer answers with `hulls` (JavaScript) or throws.
  static std::string module_answering(const std::string& hulls) {
    return "export const ConvexMeshDecomposition = { create: async () => ({ computeConvexHulls: "
           "() => " +
           hulls + " }) };\n";
  }
  static void expect_said(const Outcome& r, const std::string& mesh, const std::string& words) {
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err.rfind(mesh + ": V-HACD", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(words), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    for (const char* jargon : {"Node.js v", "json.exception", "    at "}) {
      EXPECT_EQ(r.err.find(jargon), std::string::npos) << r.err;
    }
  }
};

#define SKIP_WITHOUT_NODE()                                                                      \
  if (const std::string why = missing(); why.find("node is not on PATH") != std::string::npos) { \
    GTEST_SKIP() << "node is not on PATH";                                                       \
  }

// node's failures in words: a package that fails at import, V-HACD's WebAssembly out of memory, an
// answer that is not hulls. Never node's version banner, a stack frame or the JSON library's tag.
TEST_F(FakeVhacd, NodeErrorsAreSaidPlainly) {
  SKIP_WITHOUT_NODE();
  expect_said(run_with("throw new Error(\"half installed\");\n"), ring_,
              "V-HACD failed: node could not load the vhacd-js package (Error: half installed): "
              "run ./run build");
  expect_said(
      run_with(module_answering("{ throw new WebAssembly.RuntimeError(\"Aborted(OOM)\"); }")),
      ring_, "V-HACD failed: V-HACD ran out of memory");
  expect_said(run_with(module_answering("[{ positions: [\"a\", \"b\", \"c\"], indices: [0, 1, "
                                        "2] }]")),
              ring_, "V-HACD: node's answer is not hulls graspcd can read");
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

// Hulls 100 m from the ring (an engine's wrong answer) are warned about: no piece of a
// decomposition lies farther from the mesh than its bounding box diagonal.
TEST_F(FakeVhacd, PiecesFarFromTheMeshAreWarnedAbout) {
  SKIP_WITHOUT_NODE();
  const std::string cube =
      "[{ positions: [100,100,100, 100.03,100,100, 100,100.03,100, 100.03,100.03,100, "
      "100,100,100.03, 100.03,100,100.03, 100,100.03,100.03, 100.03,100.03,100.03], indices: "
      "[0,2,1, 1,2,3, 4,5,6, 5,7,6, 0,1,4, 1,5,4, 2,6,3, 3,6,7, 0,4,2, 2,4,6, 1,3,5, 3,7,5] }]";
  const fs::path json = dir_ / "far.json";
  const Outcome r = run_with(module_answering(cube), " --json > '" + json.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: " + ring_ + ": V-HACD's pieces lie up to 17"), std::string::npos)
      << r.err;
  const nlohmann::json doc = load(json);
  bool warned = false;
  for (const nlohmann::json& w : doc["warnings"]) {
    warned = warned || w["code"] == "decompose_far_pieces";
  }
  EXPECT_TRUE(warned);
  // The real engine's pieces of the ring lie close: no such warning (RingPiecesAreConvex...).
}

}  // namespace
}  // namespace graspcd::testing::decompose_vhacd_test
