// `graspcd decompose`, `graspcd grasp --decomposed` and `graspcd validate --decomposed`
// through the executable: the pieces are convex, the MJCF fragment and the decomposed scene load
// in MuJoCo 2.2, validate checks the true meshes at the decomposed grasp's poses, bad input is
// one line with exit code 2.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "graspcd/core/geometry.h"
#include "graspcd/grasp/decomposed_scene.h"
#include "graspcd/io/mesh_io.h"
#include "graspcd/mujoco/mujoco_ptr.h"
#include "helpers/command_test.h"
#include "helpers/convex_check.h"
#include "helpers/envelope_check.h"
#include "helpers/test_scale.h"

namespace graspcd::testing {
namespace {

namespace fs = std::filesystem;

const fs::path kModels = GRASPCD_MODELS_DIR;
const fs::path kMjcf = GRASPCD_MJCF_DIR;

class DecomposeCommand : public CommandTest {
 protected:
  // Runs decompose with --json (and `options`) into `out` (below the test's folder); the document
  // it printed.
  nlohmann::json decompose(const fs::path& mesh, int pieces, const std::string& out,
                           const std::string& options = "") {
    const fs::path json = dir_ / (out + ".json");
    const Outcome r =
        run(std::string("{ '") + GRASPCD_EXE + "' decompose '" + mesh.string() + "' --out '" +
            (dir_ / out).string() + "' --pieces " + std::to_string(pieces) + " " + options +
            " --json > '" + json.string() + "'; }");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return load(json);
  }

  // Runs graspcd with `args`; its stdout (exit code 0 expected).
  std::string stdout_of(const std::string& args) {
    const fs::path text = dir_ / "stdout.txt";
    const Outcome r =
        run(std::string("{ '") + GRASPCD_EXE + "' " + args + " > '" + text.string() + "'; }");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return read_file(text);
  }

  // Example 1's hand grasping `cup` fitted to its room (grasp --object --fit writes the scene,
  // DIR/scene/cube_cup.xml).
  fs::path write_cube_cup_scene(const fs::path& cup) {
    const Outcome r = graspcd("grasp --object '" + cup.string() + "' --fit --write-scene '" +
                              (dir_ / "scene").string() + "' --max-steps 1");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return dir_ / "scene/cube_cup.xml";
  }

  // `graspcd COMMAND SCENE --decomposed DIR EXTRA --json` (COMMAND grasp or validate) on example
  // 1's hand grasping `cup` (write_cube_cup_scene), the cup decomposed into at most `pieces`
  // (DIR/cupN): the scene, decompose's document and the command's (null when it failed).
  struct DecomposedRun {
    fs::path scene;
    nlohmann::json decomposition;
    nlohmann::json output;
  };
  DecomposedRun run_decomposed(const fs::path& cup, const std::string& command, int pieces,
                               const std::string& extra) {
    DecomposedRun out;
    out.scene = write_cube_cup_scene(cup);
    const std::string name = "cup" + std::to_string(pieces);
    out.decomposition = decompose(cup, pieces, name);
    EXPECT_TRUE(out.decomposition.contains("piece_count"));
    const fs::path json = dir_ / (command + ".json");
    const Outcome r = run(std::string("{ '") + GRASPCD_EXE + "' " + command + " '" +
                          out.scene.string() + "' --decomposed '" + (dir_ / name).string() + "' " +
                          extra + " --json > '" + json.string() + "'; }");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    if (r.exit_code == 0) {
      out.output = load(json);
      expect_envelope(out.output, -1);
    }
    return out;
  }

  // The scene a --decomposed run writes beside the cube_cup scene is gone.
  void expect_no_written_scene_left() {
    for (const auto& entry : fs::directory_iterator(dir_ / "scene")) {
      EXPECT_EQ(entry.path().filename().string().rfind(".cube_cup.decomposed-", 0),
                std::string::npos)
          << "left behind: " << entry.path();
    }
  }

  // The fragment included by a model whose meshdir is the output folder: it must load, with one
  // mesh and one geom per piece. (MuJoCo 2.2 reads an include's file relative to the including
  // file's folder.)
  void expect_fragment_loads(const fs::path& out, const nlohmann::json& doc) {
    const fs::path model = write("include_" + out.filename().string() + ".xml",
                                 "<mujoco model=\"fragment\"><compiler meshdir=\"" + out.string() +
                                     "\"/><include file=\"" + out.filename().string() + "/" +
                                     doc.at("fragment").get<std::string>() + "\"/></mujoco>");
    char error[1000] = "";
    const mujoco::ModelPtr m(mj_loadXML(model.c_str(), nullptr, error, sizeof(error)));
    ASSERT_NE(m, nullptr) << error;
    const int pieces = doc.at("piece_count").get<int>();
    EXPECT_EQ(m->nmesh, pieces);
    EXPECT_EQ(m->ngeom, pieces);
    EXPECT_EQ(m->nbody, 2);  // the world and the fragment's body
  }
};

TEST_F(DecomposeCommand, CubeCupPiecesAreConvexAndLoad) {
  const fs::path cup = kModels / "objects/mujoco/cube_cup.obj";
  if (!fs::exists(cup)) GTEST_SKIP() << "real models not found at " << kModels;
  const TriangleMesh source = io::load_mesh(cup.string());
  for (const int n : {4, 8}) {
    const std::string out = "cup" + std::to_string(n);
    const nlohmann::json doc = decompose(cup, n, out);
    expect_envelope(doc, -1);
    const int pieces = doc.at("piece_count").get<int>();
    EXPECT_GE(pieces, 1);
    EXPECT_LE(pieces, n);
    EXPECT_EQ(doc.at("pieces").size(), static_cast<std::size_t>(pieces));
    EXPECT_EQ(doc.at("source_faces").get<std::size_t>(), source.faces.size());
    // The manifest in the folder is the printed document.
    EXPECT_EQ(load(dir_ / out / "decomposition.json"), doc);
    // The Hausdorff distance is a distance within the object's size, with its bound.
    const double bound = doc.at("hausdorff").at("error_bound").get<double>();
    const double h = doc.at("hausdorff").at("distance").get<double>();
    EXPECT_GT(bound, 0);
    EXPECT_GE(h, 0);
    Vec3 lo = source.vertices.front(), hi = lo;
    for (const Vec3& v : source.vertices) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
    EXPECT_LE(h, (hi - lo).norm() + bound);
    // Every piece file is a convex mesh within the source's box (its scale kept).
    const double tol = 1e-9 * (hi - lo).norm();
    for (const auto& p : doc.at("pieces")) {
      const fs::path file = dir_ / out / p.at("file").get<std::string>();
      const TriangleMesh piece = io::load_mesh(file.string());
      EXPECT_EQ(piece.faces.size(), p.at("faces").get<std::size_t>());
      expect_convex(piece, tol, file.string());
      for (const Vec3& v : piece.vertices) {
        EXPECT_TRUE((v.array() >= lo.array() - tol).all() && (v.array() <= hi.array() + tol).all());
      }
    }
    expect_fragment_loads(dir_ / out, doc);
  }
}

TEST_F(DecomposeCommand, GlassPiecesAreConvexAndLoad) {
  const fs::path glass = kModels / "objects/prl_assets/plastic_glass_visual.obj";
  if (!fs::exists(glass)) GTEST_SKIP() << "real models not found at " << kModels;
  const nlohmann::json doc = decompose(glass, 4, "glass4");
  const int pieces = doc.at("piece_count").get<int>();
  EXPECT_GE(pieces, 1);
  EXPECT_LE(pieces, 4);
  for (const auto& p : doc.at("pieces")) {
    const fs::path file = dir_ / "glass4" / p.at("file").get<std::string>();
    expect_convex(io::load_mesh(file.string()), 1e-9, file.string());
  }
  expect_fragment_loads(dir_ / "glass4", doc);
}

// --simplify on the glass (400 faces): HACD partitions a copy of at most 100 faces, the counts
// before and after are reported, the pieces are convex and load, every vertex of the glass lies
// in some piece (the pieces are hulls of the glass's own vertices, not of the decimated copy's),
// and the Hausdorff distance is measured against the glass.
TEST_F(DecomposeCommand, SimplifiedGlassPiecesHoldEveryOriginalVertex) {
  const fs::path glass = kModels / "objects/prl_assets/plastic_glass_visual.obj";
  if (!fs::exists(glass)) GTEST_SKIP() << "real models not found at " << kModels;
  const TriangleMesh source = io::load_mesh(glass.string());
  const nlohmann::json doc = decompose(glass, 8, "glass8s", "--simplify 100");
  expect_envelope(doc, -1);
  const nlohmann::json& simplify = doc.at("simplify");
  EXPECT_EQ(simplify.at("max_faces"), 100);
  EXPECT_EQ(simplify.at("faces_before").get<std::size_t>(), source.faces.size());
  EXPECT_LE(simplify.at("faces_after").get<int>(), 100);
  EXPECT_GE(simplify.at("faces_after").get<int>(), 50);
  EXPECT_TRUE(simplify.at("decimated").get<bool>());
  EXPECT_GE(simplify.at("seconds").get<double>(), 0.0);
  EXPECT_EQ(doc.at("source_faces").get<std::size_t>(), source.faces.size());
  const int pieces = doc.at("piece_count").get<int>();
  EXPECT_GE(pieces, 2);
  EXPECT_LE(pieces, 8);
  std::vector<TriangleMesh> hulls;
  for (const auto& p : doc.at("pieces")) {
    const fs::path file = dir_ / "glass8s" / p.at("file").get<std::string>();
    hulls.push_back(io::load_mesh(file.string()));
    expect_convex(hulls.back(), 1e-9, file.string());
  }
  expect_fragment_loads(dir_ / "glass8s", doc);
  // Every vertex of the glass inside some piece, within the OBJ's printed precision (the pieces
  // are written with 17 significant digits: 1e-12 m at the glass's size).
  std::size_t outside = 0;
  for (const Vec3& v : source.vertices) {
    const bool inside_some = std::any_of(hulls.begin(), hulls.end(), [&](const TriangleMesh& h) {
      for (std::size_t f = 0; f < h.faces.size(); ++f) {
        const Triangle t = h.triangle(f);
        const Vec3 n = (t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]);
        if (n.norm() > 0 && n.normalized().dot(v - t.v[0]) > 1e-12) return false;
      }
      return true;
    });
    if (!inside_some) ++outside;
  }
  EXPECT_EQ(outside, 0u) << "of " << source.vertices.size() << " vertices of the glass";
  // The Hausdorff distance, against the glass, within its size.
  const double h = doc.at("hausdorff").at("distance").get<double>();
  EXPECT_GT(h, 0.0);
  EXPECT_LT(h, 0.2);  // the glass is about 0.12 m across

  // The text output says what was decimated.
  const std::string text = stdout_of("decompose '" + glass.string() + "' --out '" +
                                     (dir_ / "glass8t").string() + "' --pieces 8 --simplify 100");
  EXPECT_NE(text.find("simplify_faces 400 -> "), std::string::npos) << text;
  EXPECT_NE(text.find(" (at most 100) in "), std::string::npos) << text;
}

// A mesh of at most F faces is not decimated, and says so: cube_cup (28 faces) with --simplify
// 100 gives the pieces it gives without --simplify.
TEST_F(DecomposeCommand, SimplifyLeavesASmallMeshAsItIs) {
  const fs::path cup = kModels / "objects/mujoco/cube_cup.obj";
  if (!fs::exists(cup)) GTEST_SKIP() << "real models not found at " << kModels;
  const nlohmann::json plain = decompose(cup, 4, "cup4");
  EXPECT_TRUE(plain.at("simplify").is_null());
  const nlohmann::json doc = decompose(cup, 4, "cup4s", "--simplify 100");
  EXPECT_FALSE(doc.at("simplify").at("decimated").get<bool>());
  EXPECT_EQ(doc.at("simplify").at("faces_before"), 28);
  EXPECT_EQ(doc.at("simplify").at("faces_after"), 28);
  EXPECT_EQ(doc.at("pieces"), plain.at("pieces"));
  for (const auto& p : doc.at("pieces")) {
    const std::string file = p.at("file").get<std::string>();
    EXPECT_EQ(io::load_mesh((dir_ / "cup4s" / file).string()).vertices,
              io::load_mesh((dir_ / "cup4" / file).string()).vertices)
        << file;
  }
  const std::string text = stdout_of("decompose '" + cup.string() + "' --out '" +
                                     (dir_ / "cup4t").string() + "' --pieces 4 --simplify 100");
  EXPECT_NE(text.find("simplify_faces 28 (at most 100: not decimated)\n"), std::string::npos)
      << text;
}

// A bad --simplify (not an integer, or below 4 faces) is one line naming the option, exit code 2,
// and nothing is written.
TEST_F(DecomposeCommand, BadSimplifyIsOneLineAndExitCodeTwo) {
  const std::string tet = write("tet.obj",
                                "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n");
  for (const std::string value : {"0", "-5", "3", "abc", "nan", "3.5", "inf", "''"}) {
    const fs::path out = dir_ / "bad";
    const Outcome r =
        graspcd("decompose '" + tet + "' --out '" + out.string() + "' --simplify " + value);
    EXPECT_EQ(r.exit_code, 2) << value;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << value << ": " << r.err;
    EXPECT_EQ(r.err.rfind("graspcd: --simplify: Value ", 0), 0u) << value << ": " << r.err;
    EXPECT_FALSE(fs::exists(out)) << value;
  }
}

TEST_F(DecomposeCommand, BadInputIsOneLineNamingTheFile) {
  // A missing file.
  const std::string missing = (dir_ / "missing.obj").string();
  Outcome r = graspcd("decompose '" + missing + "' --out '" + (dir_ / "o").string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind(missing + ":", 0), 0u) << r.err;
  // A non-finite vertex, named at its line.
  const std::string nan = write("nan.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\nv 0 0 1\nf 1 2 3\n");
  r = graspcd("decompose '" + nan + "' --out '" + (dir_ / "o").string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind(nan + ":3:", 0), 0u) << r.err;
  // An output folder that is a file.
  const std::string tet = write("tet.obj",
                                "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n");
  const std::string file_as_dir = write("not_a_folder", "x");
  r = graspcd("decompose '" + tet + "' --out '" + file_as_dir + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind(file_as_dir + ":", 0), 0u) << r.err;
  // --pieces 0 is a usage error.
  r = graspcd("decompose '" + tet + "' --out '" + (dir_ / "o").string() + "' --pieces 0");
  EXPECT_EQ(r.exit_code, 2);
}

// The decomposed grasp: example 1's hand grasping cube_cup (28 faces; grasp --object writes the
// scene), the cup decomposed into at most 8 pieces. The grasp runs natively on the pieces, the
// report says so, and the scene written beside the original is gone afterwards.
TEST_F(DecomposeCommand, DecomposedGraspRunsOnThePieces) {
  const fs::path cup = kModels / "objects/mujoco/cube_cup.obj";
  if (!fs::exists(cup)) GTEST_SKIP() << "real models not found at " << kModels;
  const DecomposedRun run = run_decomposed(cup, "grasp", 8, "--judge");
  const fs::path& scene = run.scene;
  const nlohmann::json& d = run.decomposition;
  const nlohmann::json& g = run.output;
  ASSERT_FALSE(g.is_null());
  EXPECT_TRUE(g.at("native").get<bool>());
  EXPECT_EQ(g.at("scene").get<std::string>(), scene.string());
  EXPECT_EQ(g.at("decomposed").at("pieces"), d.at("piece_count"));
  EXPECT_EQ(g.at("decomposed").at("geoms").get<int>(), 1);
  // The fingers met the pieces (the original cup no longer collides): some segment touched.
  int touched = 0;
  for (const auto& [segment, step] : g.at("first_contact").items()) touched += !step.is_null();
  EXPECT_GT(touched, 0);
  // The judge (--judge) saw every closing step, and its counts hold together: a missed contact
  // is a step where CGAL says a hand geom meets the cup, a phantom is one of the judged
  // contacts, and CGAL's first contacts name the hand's mesh geoms (finger segments).
  const nlohmann::json& j = g.at("judge");
  EXPECT_EQ(j.at("steps").get<std::size_t>(), g.at("steps").size());
  EXPECT_LE(j.at("missed").get<int>(), j.at("truth_hits").get<int>());
  EXPECT_LE(j.at("phantom").get<int>(), j.at("contacts").get<int>());
  EXPECT_GT(j.at("contacts").get<int>(), 0);
  EXPECT_NEAR(
      j.at("contact_error_per_step").get<double>(),
      (j.at("phantom").get<double>() + j.at("missed").get<double>()) / j.at("steps").get<double>(),
      1e-12);
  // The per-geom counts add up to the totals.
  for (const char* what : {"phantom", "missed"}) {
    int sum = 0;
    for (const auto& [geom, count] : j.at(std::string(what) + "_by_geom").items()) {
      EXPECT_FALSE(geom.empty());
      EXPECT_GT(count.get<int>(), 0) << geom;
      sum += count.get<int>();
    }
    EXPECT_EQ(sum, j.at(what).get<int>()) << what;
  }
  EXPECT_FALSE(j.at("cgal_first_contact").empty());
  for (const auto& [geom, step] : j.at("cgal_first_contact").items()) {
    EXPECT_EQ(geom.rfind("finger", 0), 0u) << geom;
    EXPECT_GE(step.get<int>(), 1);
  }
  expect_no_written_scene_left();
}

// The race's judge is on the grasp's contacts: the table the object stands on (the pair config's
// "support", a driven body of the Robotiq scenes) is neither judged nor CGAL's, while the pads
// are. On the Robotiq bowl on its hull (the scene's own config), and on 4 pieces of cube_cup in
// the robotiq template (the scene grasp --object wrote, run --decomposed: its config). Before the
// support was left out, the table gave the bowl 9 phantom contacts and the cup 91, and CGAL's
// first contacts named it.
TEST_F(DecomposeCommand, JudgeLeavesOutTheTableTheObjectStandsOn) {
  const fs::path cup = kModels / "objects/mujoco/cube_cup.obj";
  if (!fs::exists(cup) || !fs::exists(kModels / "hands/robotiq_2f85/2f85.xml")) {
    GTEST_SKIP() << "real models not found at " << kModels;
  }
  if (test_scale() < 1) {
    GTEST_SKIP() << "real-hand grasps skipped at GRASPCD_TEST_SCALE < 1 (sanitizer pass)";
  }
  const Outcome w = graspcd("grasp --object '" + cup.string() + "' --hand robotiq --fit " +
                            "--write-scene '" + (dir_ / "scene").string() + "' --max-steps 1");
  ASSERT_EQ(w.exit_code, 0) << w.err;
  decompose(cup, 4, "cup4");
  const std::string bowl = (kMjcf / "real_robotiq_bowl.xml").string();
  const std::string scene = (dir_ / "scene/cube_cup.xml").string();
  for (const std::string& args :
       {"grasp '" + bowl + "' --native",
        "grasp '" + scene + "' --decomposed '" + (dir_ / "cup4").string() + "'"}) {
    const fs::path json = dir_ / "judged.json";
    const Outcome r = run(std::string("{ '") + GRASPCD_EXE + "' " + args + " --judge --json > '" +
                          json.string() + "'; }");
    ASSERT_EQ(r.exit_code, 0) << args << ": " << r.err;
    const nlohmann::json j = load(json).at("judge");
    for (const char* map : {"phantom_by_geom", "missed_by_geom", "cgal_first_contact"}) {
      EXPECT_FALSE(j.at(map).contains("table")) << args << ": " << map << " " << j.at(map);
    }
    EXPECT_FALSE(j.at("cgal_first_contact_body").contains("table")) << args;
    // The pads are still judged: their contacts with the object, and CGAL's verdict on them.
    EXPECT_GT(j.at("contacts").get<int>(), 0) << args;
    EXPECT_TRUE(j.at("cgal_first_contact_body").contains("left_pad") ||
                j.at("cgal_first_contact_body").contains("right_pad"))
        << args << ": " << j.at("cgal_first_contact_body");
  }
}

// The decomposed scene as MuJoCo compiles it: the original geom stays with its mass but without
// collision, each piece collides as the original did, with mass 0, and stands where the mesh
// stood (every piece vertex, in the body frame, inside the original mesh's box there).
TEST_F(DecomposeCommand, DecomposedSceneKeepsMassAndPlace) {
  const fs::path cup = kModels / "objects/mujoco/cube_cup.obj";
  if (!fs::exists(cup)) GTEST_SKIP() << "real models not found at " << kModels;
  const std::string scene = write_cube_cup_scene(cup).string();
  const nlohmann::json d = decompose(cup, 4, "cup4");
  const grasp::DecomposedScene written =
      grasp::write_decomposed_scene(scene, (dir_ / "cup4").string());
  char error[1000] = "";
  const mujoco::ModelPtr original(mj_loadXML(scene.c_str(), nullptr, error, sizeof(error)));
  ASSERT_NE(original, nullptr) << error;
  const mujoco::ModelPtr m(mj_loadXML(written.scene.c_str(), nullptr, error, sizeof(error)));
  fs::remove(written.scene);
  ASSERT_NE(m, nullptr) << error;
  const int pieces = d.at("piece_count").get<int>();
  EXPECT_EQ(written.pieces, pieces);
  EXPECT_EQ(written.replaced_geoms, 1);
  EXPECT_EQ(m->ngeom, original->ngeom + pieces);
  const int body = mj_name2id(m.get(), mjOBJ_BODY, "object");
  ASSERT_GE(body, 0);
  EXPECT_NEAR(m->body_mass[body],
              original->body_mass[mj_name2id(original.get(), mjOBJ_BODY, "object")], 1e-12);
  // The original geom: its own place and mass kept, no collision.
  int cup_geom = -1;
  for (int g = 0; g < original->ngeom; ++g) {
    if (original->geom_bodyid[g] == mj_name2id(original.get(), mjOBJ_BODY, "object")) cup_geom = g;
  }
  ASSERT_GE(cup_geom, 0);
  const int kept =
      mj_name2id(m.get(), mjOBJ_GEOM, mj_id2name(original.get(), mjOBJ_GEOM, cup_geom));
  ASSERT_GE(kept, 0);
  EXPECT_EQ(m->geom_contype[kept], 0);
  EXPECT_EQ(m->geom_conaffinity[kept], 0);
  // The original mesh's box in the body frame.
  const auto body_frame = [](const mjModel* model, int g, int v) {
    const int mesh = model->geom_dataid[g];
    const float* p = model->mesh_vert + 3 * (model->mesh_vertadr[mesh] + v);
    mjtNum local[3] = {p[0], p[1], p[2]}, out[3];
    mju_rotVecQuat(out, local, model->geom_quat + 4 * g);
    return Vec3(out[0] + model->geom_pos[3 * g], out[1] + model->geom_pos[3 * g + 1],
                out[2] + model->geom_pos[3 * g + 2]);
  };
  Vec3 lo = Vec3::Constant(1e9), hi = Vec3::Constant(-1e9);
  const int cup_mesh = original->geom_dataid[cup_geom];
  for (int v = 0; v < original->mesh_vertnum[cup_mesh]; ++v) {
    lo = lo.cwiseMin(body_frame(original.get(), cup_geom, v));
    hi = hi.cwiseMax(body_frame(original.get(), cup_geom, v));
  }
  const double tol = 1e-5 * (hi - lo).norm();  // MuJoCo keeps mesh vertices as floats
  int piece_geoms = 0;
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_bodyid[g] != body || g == kept) continue;
    ++piece_geoms;
    EXPECT_EQ(m->geom_contype[g], original->geom_contype[cup_geom]);
    EXPECT_EQ(m->geom_conaffinity[g], original->geom_conaffinity[cup_geom]);
    for (int v = 0; v < m->mesh_vertnum[m->geom_dataid[g]]; ++v) {
      const Vec3 p = body_frame(m.get(), g, v);
      EXPECT_TRUE((p.array() >= lo.array() - tol).all() && (p.array() <= hi.array() + tol).all())
          << "piece geom " << g << " vertex " << v;
    }
  }
  EXPECT_EQ(piece_geoms, pieces);
}

// validate's truth side on a decomposed scene: the grasp runs natively on the pieces of
// cube_cup, and at its poses every registered pair is checked on the true meshes: the pairs name
// the original cup (no piece), every method agrees with CGAL on them (nothing missed), and the
// written scene is gone afterwards. Bad input (a folder without decomposition.json) is one line.
TEST_F(DecomposeCommand, ValidateDecomposedChecksTheTrueMeshes) {
  const fs::path cup = kModels / "objects/mujoco/cube_cup.obj";
  if (!fs::exists(cup)) GTEST_SKIP() << "real models not found at " << kModels;
  const DecomposedRun run = run_decomposed(cup, "validate", 4, "");
  const fs::path& scene = run.scene;
  const nlohmann::json& d = run.decomposition;
  const nlohmann::json& v = run.output;
  ASSERT_FALSE(v.is_null());
  EXPECT_EQ(v.at("scene").get<std::string>(), scene.string());
  EXPECT_EQ(v.at("grasp_method").get<std::string>(), "native");
  EXPECT_EQ(v.at("decomposed").at("pieces"), d.at("piece_count"));
  EXPECT_EQ(v.at("decomposed").at("geoms").get<int>(), 1);
  EXPECT_FALSE(v.at("missed_any").get<bool>());
  EXPECT_GT(v.at("steps").get<int>(), 0);
  EXPECT_GT(v.at("steps_with_contact").get<int>(), 0);
  // Every state checked: the closing's grasp steps and the squeeze's (validate's default).
  int states = 0;
  for (const auto& c : v.at("checks")) states += c.at("states").get<int>();
  EXPECT_GT(states, v.at("steps").get<int>());
  int object_pairs = 0;
  for (const auto& method : v.at("methods")) {
    for (const auto& pair : method.at("pairs")) {
      const std::string name = pair.at("pair").get<std::string>();
      EXPECT_EQ(name.find("__piece_"), std::string::npos) << name;
      EXPECT_EQ(pair.at("steps").get<int>(), states) << name;
      EXPECT_EQ(pair.at("missed").get<int>(), 0) << name;
      object_pairs += name.find("object") != std::string::npos;
    }
  }
  EXPECT_GT(object_pairs, 0);
  expect_no_written_scene_left();
  fs::create_directories(dir_ / "empty");
  const Outcome bad =
      graspcd("validate '" + scene.string() + "' --decomposed '" + (dir_ / "empty").string() + "'");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  EXPECT_EQ(bad.err.rfind((dir_ / "empty").string() + ":", 0), 0u) << bad.err;
}

// The box, in the body frame of geom `g`'s body, of the vertices of every geom of that body that
// `take` accepts, as MuJoCo compiled them (mesh vertices about the mesh's centre, placed by the
// geom's pos and quat).
std::pair<Vec3, Vec3> body_box(const mjModel* m, int body, const std::function<bool(int)>& take) {
  Vec3 lo = Vec3::Constant(1e9), hi = Vec3::Constant(-1e9);
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_bodyid[g] != body || m->geom_type[g] != mjGEOM_MESH || !take(g)) continue;
    const int mesh = m->geom_dataid[g];
    for (int v = 0; v < m->mesh_vertnum[mesh]; ++v) {
      const float* p = m->mesh_vert + 3 * (m->mesh_vertadr[mesh] + v);
      mjtNum local[3] = {p[0], p[1], p[2]}, out[3];
      mju_rotVecQuat(out, local, m->geom_quat + 4 * g);
      const Vec3 q(out[0] + m->geom_pos[3 * g], out[1] + m->geom_pos[3 * g + 1],
                   out[2] + m->geom_pos[3 * g + 2]);
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
  }
  return {lo, hi};
}

// A scale is applied once: a 30 mm cube in millimetres grasped at --scale 0.001 and decomposed at
// --scale 0.001 (its pieces in metres, decomposition.json "scale": 0.001) is collided by pieces
// that stand where the cube stands, not 1000 times smaller (before 0.5.0 the scene's asset scale
// was applied to the pieces again). A manifest without a scale, as graspcd 0.4 wrote it, is read
// as scale 1 with a warning, and its pieces, 1000 times smaller than the cube at scale 1, are
// refused in one line naming the manifest; pieces written at the file's own units (scale 1) are
// scaled by the scene as the mesh is.
TEST_F(DecomposeCommand, DecomposedScaleIsAppliedOnce) {
  std::string cube;
  for (const char* v : {"-15 -15 -15", "15 -15 -15", "-15 15 -15", "15 15 -15", "-15 -15 15",
                        "15 -15 15", "-15 15 15", "15 15 15"}) {
    cube += std::string("v ") + v + "\n";
  }
  cube +=
      "f 1 3 4\nf 1 4 2\nf 5 6 8\nf 5 8 7\nf 1 2 6\nf 1 6 5\nf 3 7 8\nf 3 8 4\n"
      "f 1 5 7\nf 1 7 3\nf 2 4 8\nf 2 8 6\n";
  const std::string mesh = write("cube_mm.obj", cube);
  const Outcome w = graspcd("grasp --object '" + mesh + "' --scale 0.001 --write-scene '" +
                            (dir_ / "scene").string() + "' --max-steps 1");
  ASSERT_EQ(w.exit_code, 0) << w.err;
  const std::string scene = (dir_ / "scene/cube_mm.xml").string();
  for (const char* scale : {"0.001", "1"}) {
    const std::string out = std::string("cube_at_") + scale;
    const nlohmann::json d = decompose(mesh, 1, out, std::string("--scale ") + scale);
    EXPECT_EQ(d.at("scale").get<double>(), std::stod(scale));
    EXPECT_EQ(d.at("units").get<std::string>(), "m");
    const grasp::DecomposedScene written =
        grasp::write_decomposed_scene(scene, (dir_ / out).string());
    char error[1000] = "";
    const mujoco::ModelPtr m(mj_loadXML(written.scene.c_str(), nullptr, error, sizeof(error)));
    fs::remove(written.scene);
    ASSERT_NE(m, nullptr) << error;
    const int body = mj_name2id(m.get(), mjOBJ_BODY, "object");
    ASSERT_GE(body, 0);
    const auto [cube_lo, cube_hi] =
        body_box(m.get(), body, [&](int g) { return !grasp::is_piece(m.get(), g); });
    const auto [lo, hi] =
        body_box(m.get(), body, [&](int g) { return grasp::is_piece(m.get(), g); });
    EXPECT_NEAR((cube_hi - cube_lo).norm(), std::sqrt(3.0) * 0.03, 1e-6);
    EXPECT_LT((lo - cube_lo).norm(), 1e-6) << scale << ": " << lo.transpose();
    EXPECT_LT((hi - cube_hi).norm(), 1e-6) << scale << ": " << hi.transpose();
  }
  // A decomposition.json as graspcd 0.4 wrote it: no "scale", no "units".
  const auto written_by_0_4 = [&](const std::string& folder) {
    nlohmann::json manifest = load(dir_ / folder / "decomposition.json");
    manifest.erase("scale");
    manifest.erase("units");
    std::ofstream(dir_ / folder / "decomposition.json") << manifest.dump(2);
  };
  // Pieces in metres.
  written_by_0_4("cube_at_0.001");
  const Outcome r = graspcd("grasp '" + scene + "' --decomposed '" +
                            (dir_ / "cube_at_0.001").string() + "' --max-steps 1");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  const std::vector<std::string> err_lines = [&] {
    std::vector<std::string> out;
    std::istringstream in(r.err);
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
  }();
  ASSERT_FALSE(err_lines.empty());
  const std::string manifest = (dir_ / "cube_at_0.001/decomposition.json").string();
  EXPECT_EQ(err_lines[0].rfind(manifest + ": not a decomposition of ", 0), 0u) << r.err;
  EXPECT_NE(err_lines[0].find(": no \"scale\" (written before graspcd 0.5), read as 1: its "
                              "pieces are 0.001 times the size of the mesh at scale 1"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(err_lines.size(), 1u) << r.err;
  // Pieces written in the file's own units (scale 1) without a scale: read as 1, with a warning.
  written_by_0_4("cube_at_1");
  const Outcome ok = graspcd("grasp '" + scene + "' --decomposed '" +
                             (dir_ / "cube_at_1").string() + "' --max-steps 1");
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_NE(ok.err.find("warning: " + (dir_ / "cube_at_1/decomposition.json").string() +
                        ": no \"scale\" (written before graspcd 0.5): read as 1"),
            std::string::npos)
      << ok.err;
}

// A published decomposition (a folder of convex pieces in the mesh's coordinates) described as a
// decomposition: two halves of a 30 mm box in millimetres, described at --scale 0.001, are the
// manifest's pieces in metres (engine "given", in the order of their names), and the same halves
// in metres are refused against the box in millimetres (another unit). With the real models, the
// YCB can's published pieces are described as they are (metres, scale 1).
TEST_F(DecomposeCommand, DescribeTakesPublishedPieces) {
  const auto box = [](double x0, double x1, double s) {
    std::ostringstream out;
    for (double x : {x0, x1}) {
      for (double y : {-15.0, 15.0}) {
        for (double z : {-15.0, 15.0}) out << "v " << s * x << ' ' << s * y << ' ' << s * z << '\n';
      }
    }
    out << "f 1 2 4\nf 1 4 3\nf 5 7 8\nf 5 8 6\nf 1 5 6\nf 1 6 2\nf 3 4 8\nf 3 8 7\n"
           "f 1 3 7\nf 1 7 5\nf 2 6 8\nf 2 8 4\n";
    return out.str();
  };
  const std::string mesh = write("block.obj", box(-15, 15, 1));
  fs::create_directories(dir_ / "mm");
  fs::create_directories(dir_ / "m");
  write("mm/contact10.obj", box(0, 15, 1));  // named so that a plain sort would put it first
  write("mm/contact2.obj", box(-15, 0, 1));
  write("m/contact0.obj", box(-15, 0, 0.001));
  write("m/contact1.obj", box(0, 15, 0.001));
  const fs::path json = dir_ / "described.json";
  const Outcome r = run(std::string("{ '") + GRASPCD_EXE + "' decompose '" + mesh + "' --out '" +
                        (dir_ / "described").string() + "' --describe '" + (dir_ / "mm").string() +
                        "' --scale 0.001 --json > '" + json.string() + "'; }");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json g = load(json);
  EXPECT_EQ(g.at("engine").get<std::string>(), "given");
  EXPECT_EQ(g.at("scale").get<double>(), 0.001);
  EXPECT_EQ(g.at("units").get<std::string>(), "m");
  EXPECT_EQ(g.at("pieces_from").get<std::string>(), fs::absolute(dir_ / "mm").string());
  ASSERT_EQ(g.at("piece_count").get<int>(), 2);
  // contact2 (x < 0) before contact10, each in metres.
  const TriangleMesh first = io::load_mesh(
      (dir_ / "described" / g.at("pieces")[0].at("file").get<std::string>()).string());
  for (const Vec3& v : first.vertices) {
    EXPECT_LE(v.x(), 1e-12);
    EXPECT_LE(std::abs(v.y()), 0.015 + 1e-12);
  }
  // The pieces' surfaces lie on the block's but for the face they share, 15 mm inside at its
  // centre.
  EXPECT_NEAR(g.at("hausdorff").at("distance").get<double>(), 0.015,
              g.at("hausdorff").at("error_bound").get<double>() + 1e-9);
  // Pieces in metres against the block in millimetres: refused, one line naming the pieces.
  const Outcome bad = graspcd("decompose '" + mesh + "' --out '" + (dir_ / "wrong").string() +
                              "' --describe '" + (dir_ / "m").string() + "'");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  EXPECT_EQ(bad.err.rfind((dir_ / "m").string() + ": not pieces of " + mesh, 0), 0u) << bad.err;
  EXPECT_NE(bad.err.find("its pieces are 0.001 times the size of the mesh"), std::string::npos)
      << bad.err;
  EXPECT_FALSE(fs::exists(dir_ / "wrong"));
  // An engine's option with --describe is a usage error.
  EXPECT_EQ(graspcd("decompose '" + mesh + "' --out '" + (dir_ / "wrong").string() +
                    "' --describe '" + (dir_ / "mm").string() + "' --pieces 4")
                .exit_code,
            2);

  const fs::path can = kModels / "objects/ycb/005_tomato_soup_can";
  if (!fs::exists(can / "pieces")) GTEST_SKIP() << "real models not found at " << kModels;
  // CGAL's Hausdorff distance on the can's 16,000 faces: the Release pass only.
  if (test_scale() < 1) GTEST_SKIP() << "the YCB can skipped at GRASPCD_TEST_SCALE < 1";
  const Outcome y =
      run(std::string("{ '") + GRASPCD_EXE + "' decompose '" + (can / "textured.obj").string() +
          "' --out '" + (dir_ / "can").string() + "' --describe '" + (can / "pieces").string() +
          "' --json > '" + (dir_ / "can.json").string() + "'; }");
  ASSERT_EQ(y.exit_code, 0) << y.err;
  const nlohmann::json c = load(dir_ / "can.json");
  std::size_t files = 0;
  for (const auto& e : fs::directory_iterator(can / "pieces"))
    files += e.path().extension() == ".stl";
  EXPECT_EQ(c.at("piece_count").get<std::size_t>(), files);
  EXPECT_EQ(c.at("scale").get<double>(), 1.0);
}

TEST_F(DecomposeCommand, DecomposedGraspBadInput) {
  const std::string scene = (kMjcf / "example1.xml").string();
  // A folder without decomposition.json.
  fs::create_directories(dir_ / "empty");
  Outcome r = graspcd("grasp '" + scene + "' --decomposed '" + (dir_ / "empty").string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind((dir_ / "empty").string() + ":", 0), 0u) << r.err;
  // A decomposition of a mesh the scene does not hold (example 1 holds the cup, not a tet).
  const std::string tet = write("tet.obj",
                                "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n");
  ASSERT_EQ(graspcd("decompose '" + tet + "' --out '" + (dir_ / "tet").string() + "'").exit_code,
            0);
  r = graspcd("grasp '" + scene + "' --decomposed '" + (dir_ / "tet").string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind(scene + ":", 0), 0u) << r.err;
}

}  // namespace
}  // namespace graspcd::testing
