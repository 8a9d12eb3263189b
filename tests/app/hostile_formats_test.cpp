// Files read wrongly without a word, silent answers and unclear messages (docs/bad-input.md): each
// is now one line naming the file or the option and what is wrong, exit 2, or the answer the user
// meant. Each test runs the graspcd executable on inputs of a few hundred bytes; ctest gives each
// a timeout (tests/CMakeLists.txt), so a hang fails.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "helpers/command_test.h"

namespace fs = std::filesystem;

namespace {

std::string mjcf_dir() { return (fs::path(GRASPCD_DATA_DIR).parent_path() / "mjcf").string(); }

// A tetrahedron's faces (outward), on the vertices (0,0,0), (1,0,0), (0,1,0), (0,0,1).
const char* const kTetraFaces = "0 2 1\n0 1 3\n0 3 2\n1 2 3\n";

// An ASCII PLY of the tetrahedron whose header declares `faces` faces (4 are there).
std::string tetra_ply(int faces) {
  std::ostringstream out;
  out << "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
         "property float z\nelement face "
      << faces << "\nproperty list uchar int vertex_indices\nend_header\n"
      << "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  std::istringstream in(kTetraFaces);
  for (std::string line; std::getline(in, line);) out << "3 " << line << '\n';
  return out.str();
}

// The buffer of the glTF tests: the tetrahedron's 4 positions (48 bytes of floats) and 12 indices
// (24 bytes of unsigned shorts), two of which (7) name no vertex.
std::string gltf_buffer() {
  const float positions[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const std::uint16_t indices[12] = {0, 2, 1, 0, 1, 3, 0, 3, 7, 1, 2, 7};
  std::string out(72, '\0');
  std::memcpy(&out[0], positions, 48);
  std::memcpy(&out[48], indices, 24);
  return out;
}

// A glTF of one primitive on t.bin: POSITION of `type` and `count`, 12 indices.
std::string gltf(const std::string& type, int count) {
  const nlohmann::json doc = {
      {"asset", {{"version", "2.0"}}},
      {"buffers", {{{"uri", "t.bin"}, {"byteLength", 72}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
        {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 24}}}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", count}, {"type", type}},
        {{"bufferView", 1}, {"componentType", 5123}, {"count", 12}, {"type", "SCALAR"}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"scenes", {{{"nodes", {0}}}}},
      {"scene", 0}};
  return doc.dump(1);
}

// A COLLADA file of the tetrahedron with <unit meter="METER">.
std::string collada(const std::string& meter) {
  return "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
         "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n"
         "  <asset><unit meter=\"" +
         meter +
         "\"/><up_axis>Z_UP</up_axis></asset>\n"
         "  <library_geometries><geometry id=\"g\"><mesh>\n"
         "    <source id=\"p\"><float_array id=\"pa\" count=\"12\">0 0 0 1 0 0 0 1 0 0 0 1"
         "</float_array><technique_common><accessor source=\"#pa\" count=\"4\" stride=\"3\">"
         "<param name=\"X\" type=\"float\"/><param name=\"Y\" type=\"float\"/>"
         "<param name=\"Z\" type=\"float\"/></accessor></technique_common></source>\n"
         "    <vertices id=\"v\"><input semantic=\"POSITION\" source=\"#p\"/></vertices>\n"
         "    <triangles count=\"4\"><input semantic=\"VERTEX\" source=\"#v\" offset=\"0\"/>"
         "<p>0 2 1 0 1 3 0 3 2 1 2 3</p></triangles>\n"
         "  </mesh></geometry></library_geometries>\n"
         "  <library_visual_scenes><visual_scene id=\"s\"><node id=\"n\">"
         "<instance_geometry url=\"#g\"/></node></visual_scene></library_visual_scenes>\n"
         "  <scene><instance_visual_scene url=\"#s\"/></scene>\n</COLLADA>\n";
}

// A binary STL of `copies` copies of the tetrahedron, its coordinates times `scale`.
std::string tetra_stl(std::size_t copies, float scale) {
  const float v[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const int f[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  std::string one;
  for (const auto& face : f) {
    float facet[12] = {};
    for (int k = 0; k < 3; ++k) {
      for (int c = 0; c < 3; ++c) facet[3 + 3 * k + c] = v[face[k]][c] * scale;
    }
    one.append(reinterpret_cast<const char*>(facet), 48);
    one.append(2, '\0');
  }
  const auto count = static_cast<std::uint32_t>(4 * copies);
  std::string out(80, '\0');
  out.append(reinterpret_cast<const char*>(&count), 4);
  out.reserve(out.size() + one.size() * copies);
  for (std::size_t i = 0; i < copies; ++i) out += one;
  return out;
}

// Example 1 as a file in `dir`, its meshes named where they are installed, with `extra` before
// </mujoco>; its pair config beside it.
std::string example1_with(const fs::path& dir, const std::string& extra) {
  std::string xml = graspcd::testing::read_file(fs::path(mjcf_dir()) / "example1.xml");
  const std::string meshdir = "meshdir=\"meshes\"";
  const std::size_t at = xml.find(meshdir);
  EXPECT_NE(at, std::string::npos);
  xml.replace(at, meshdir.size(), "meshdir=\"" + mjcf_dir() + "/meshes\"");
  const std::size_t end = xml.rfind("</mujoco>");
  EXPECT_NE(end, std::string::npos);
  xml.insert(end, extra);
  const fs::path path = dir / "example1.xml";
  std::ofstream(path, std::ios::binary) << xml;
  fs::copy_file(fs::path(mjcf_dir()) / "example1.pairs.json", dir / "example1.pairs.json");
  return path.string();
}

class HostileFormatsTest : public graspcd::testing::CommandTest {
 protected:
  // Refused: exit 2 and one line on stderr.
  static std::string refusal(const graspcd::testing::Outcome& r) {
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
    return r.err;
  }
  // What graspcd `args` prints on stdout, exit code 0 expected.
  std::string stdout_of(const std::string& args) {
    const fs::path out = dir_ / "stdout.txt";
    const auto r =
        run("('" + std::string(GRASPCD_EXE) + "' " + args + " > '" + out.string() + "')");
    EXPECT_EQ(r.exit_code, 0) << args << ": " << r.err;
    return graspcd::testing::read_file(out);
  }
  // meshpair on the mesh with itself and no pose: the mesh is read, nothing is tested.
  graspcd::testing::Outcome read(const std::string& mesh) {
    return graspcd("meshpair " + mesh + " " + mesh + " --poses - < /dev/null");
  }
};

// --- Formats read wrongly ---

// Assimp reads past an ASCII PLY's data, repeating the last face, so the header's counts are
// checked against the lines that follow it.
TEST_F(HostileFormatsTest, PlyDeclaringMoreFacesThanItHoldsIsRefused) {
  const std::string ply = write("t.ply", tetra_ply(100));
  EXPECT_EQ(refusal(read(ply)), ply +
                                    ": the header declares 104 elements (4 vertex, 100 face), "
                                    "one line each in an ASCII PLY, but 8 lines of data follow "
                                    "end_header\n");
  const std::string exact = write("exact.ply", tetra_ply(4));
  const auto r = read(exact);
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST_F(HostileFormatsTest, GltfIndicesBeyondPositionsVec2PositionsAndBadJsonAreRefused) {
  write("t.bin", gltf_buffer());
  const std::string beyond = write("beyond.gltf", gltf("VEC3", 4));
  EXPECT_EQ(refusal(read(beyond)),
            beyond +
                ": meshes[0].primitives[0]: 2 of its 4 triangles (indices accessor 1) name a "
                "vertex beyond the 4 of its POSITION accessor 0\n");
  const std::string vec2 = write("vec2.gltf", gltf("VEC2", 6));
  EXPECT_EQ(refusal(read(vec2)), vec2 +
                                     ": meshes[0].primitives[0]: its POSITION accessor 0 holds "
                                     "VEC2 of FLOAT; a glTF position is a VEC3 of FLOAT "
                                     "(componentType 5126)\n");
  const std::string bad =
      write("bad.gltf", "{\n  \"asset\": {\"version\": \"2.0\"},\n  \"meshes\": [\n");
  const std::string message = refusal(read(bad));
  EXPECT_EQ(message.rfind(bad + ":4: bad JSON: ", 0), 0u) << message;
  EXPECT_EQ(message.find("No suitable reader"), std::string::npos) << message;
}

TEST_F(HostileFormatsTest, ColladaUnitThatIsNoPositiveNumberIsRefused) {
  for (const char* meter : {"-1", "abc"}) {
    const std::string dae = write("t.dae", collada(meter));
    EXPECT_EQ(refusal(read(dae)), dae + ":3: <unit meter=\"" + meter +
                                      "\">: the metres per unit of the file must be a finite "
                                      "number > 0 (COLLADA scales the mesh by it)\n")
        << meter;
  }
  // A positive unit is read, the mesh in metres.
  const std::string cm = write("cm.dae", collada("0.01"));
  const auto r = read(cm);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("inward"), std::string::npos) << r.err;
}

// --- Other silent answers ---

TEST_F(HostileFormatsTest, TemplateWithAKeyframeInAnIncludedFileIsRefused) {
  const std::string keys = write("keys.xml",
                                 "<mujoco>\n  <keyframe>\n    <key time=\"0\"/>\n"
                                 "  </keyframe>\n</mujoco>\n");
  const std::string hand = example1_with(dir_, "  <include file=\"keys.xml\"/>\n");
  const std::string box = write("box.obj",
                                "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  EXPECT_EQ(
      refusal(graspcd("grasp --object " + box + " --scale 0.02 --hand " + hand + " --max-steps 1")),
      keys + ":2: template scene (included by " + hand +
          "): a template with a <keyframe> cannot take a new object (the keyframe starts "
          "the grasp with the template object's pose)\n");
}

TEST_F(HostileFormatsTest, KeyframeTimeBeforeZeroIsRefused) {
  const std::string scene =
      example1_with(dir_, "  <keyframe>\n    <key name=\"early\" time=\"-5\"/>\n  </keyframe>\n");
  EXPECT_EQ(refusal(graspcd("grasp " + scene + " --config " + mjcf_dir() +
                            "/example1.pairs.json --max-steps 1")),
            scene +
                ": the first keyframe 'early', where the grasp starts, has time=\"-5\": the "
                "grasp's clock starts at the keyframe's time and cannot start before 0 (give "
                "time=\"0\" or leave it out)\n");
}

// CLI11 reads integers with strtoll's base 0: "010" was octal 8 and "08" no number. Every integer
// option of every subcommand (found in the help by its type) refuses a hexadecimal number.
TEST_F(HostileFormatsTest, EveryIntegerOptionIsReadInDecimal) {
  const std::regex option(
      R"(^\s+(--[a-z-]+)(?:,--[a-z-]+)?\s+(?:INT|UINT|POSITIVE|NONNEGATIVE|F|R)\b)");
  std::set<std::string> checked;
  for (const char* command : {"tritri", "boxbox", "meshpair", "grasp", "validate", "trajectory",
                              "study", "stress", "decompose"}) {
    std::istringstream in(stdout_of(std::string(command) + " --help"));
    for (std::string line; std::getline(in, line);) {
      std::smatch m;
      if (!std::regex_search(line, m, option)) continue;
      const std::string name = m[1];
      const auto r = graspcd(std::string(command) + " " + name + " 0x10");
      EXPECT_EQ(refusal(r), "graspcd: " + name +
                                ": Value 0x10 is not a decimal integer (run with "
                                "--help for usage)\n")
          << command << " " << name;
      checked.insert(std::string(command) + " " + name);
    }
  }
  for (const char* expected : {"decompose --pieces", "grasp --noslip", "grasp --max-steps",
                               "study --jobs", "stress --seed", "meshpair --leaf-size"}) {
    EXPECT_EQ(checked.count(expected), 1u) << expected;
  }
  // "08" is 8, and within the range.
  const std::string mesh = write("t.ply", tetra_ply(4));
  const auto r = graspcd("decompose " + mesh + " --pieces 08 --hausdorff-bound 1e308 --out " +
                         (dir_ / "out").string());
  // The bound is refused after the options are read: --pieces 08 passed.
  EXPECT_EQ(refusal(r).rfind("graspcd: --hausdorff-bound: the bound 1e+308 m is coarser than ", 0),
            0u)
      << r.err;
}

TEST_F(HostileFormatsTest, OptionErrorsSayWhatIsWrong) {
  EXPECT_EQ(refusal(graspcd("grasp --noslip abc")),
            "graspcd: --noslip: Value abc is not a decimal integer (run with --help for usage)\n");
  EXPECT_EQ(refusal(graspcd("grasp --noslip 1001")),
            "graspcd: --noslip: Value 1001 is not in 0 .. 1000 (run with --help for usage)\n");
  // An unknown option is named before a missing argument.
  EXPECT_EQ(refusal(graspcd("meshpair --bogus")),
            "graspcd: The following argument was not expected: --bogus (run with --help for "
            "usage)\n");
  // A misspelled subcommand is an error even beside --help.
  const std::string tritr = refusal(graspcd("tritr --help"));
  EXPECT_EQ(tritr.rfind("graspcd: unknown subcommand 'tritr' (expected one of: ", 0), 0u) << tritr;
  // validate's help names every format it reads.
  const std::string text = stdout_of("validate --help");
  EXPECT_EQ(text.find("every OBJ and STL"), std::string::npos);
  EXPECT_NE(text.find(".ply, .gltf, .glb,"), std::string::npos);
}

#if GRASPCD_HAS_HACD
TEST_F(HostileFormatsTest, DecomposeRefusesAHausdorffBoundCoarserThanTheMesh) {
  const std::string mesh = write("t.ply", tetra_ply(4));
  const auto r =
      graspcd("decompose " + mesh + " --hausdorff-bound 2 --out " + (dir_ / "out").string());
  EXPECT_EQ(refusal(r), "graspcd: --hausdorff-bound: the bound 2 m is coarser than " + mesh +
                            "'s bounding box diagonal (1.73205 m): a distance known only to "
                            "within the mesh's size says nothing\n");
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}
#endif

// --- Messages ---

// MuJoCo's errors quote the file it read: the object's temporary copy is named by the user's file.
TEST_F(HostileFormatsTest, MessagesNameTheUsersFileNeverATemporaryCopy) {
  const fs::path tmp = dir_ / "tmp";
  fs::create_directories(tmp);
  const std::string huge = write("huge.stl", tetra_stl(1, 1e20F));
  const auto r = run("TMPDIR='" + tmp.string() + "' '" + GRASPCD_EXE + "' grasp --object " + huge +
                     " --max-steps 1");
  const std::string message = refusal(r);
  EXPECT_EQ(message.find(tmp.string()), std::string::npos) << message;
  EXPECT_NE(message.find("in STL file '" + huge + "' exceed maximum bounds"), std::string::npos)
      << message;
  // A scene naming a binary STL beyond MuJoCo 2.2's 200,000 triangles: graspcd's words, not
  // MuJoCo's "perhaps this is an ASCII file?".
  const std::string many = write("many.stl", tetra_stl(50001, 0.05F));
  const std::string scene =
      write("s.xml",
            "<mujoco>\n  <asset><mesh name=\"m\" file=\"many.stl\"/></asset>\n"
            "  <worldbody><geom name=\"a\" type=\"mesh\" mesh=\"m\"/>"
            "<geom name=\"b\" type=\"box\" size=\"1 1 1\"/></worldbody>\n</mujoco>\n");
  const std::string pairs = write("s.pairs.json", R"({"pairs": [{"a": "a", "b": "b"}]})");
  EXPECT_EQ(refusal(graspcd("grasp " + scene + " --config " + pairs)),
            many +
                ": a binary STL of 200004 triangles, which MuJoCo 2.2 cannot read (at most "
                "200000 per STL file; an OBJ has no such limit)\n");
}

// Bytes of a file quoted in a message reach the terminal escaped, once.
TEST_F(HostileFormatsTest, ControlBytesQuotedFromAFileAreEscaped) {
  const std::string off = write("e.off", "\x1b]0;pwned\x07OFF\n4 4 0\n");
  const std::string message = refusal(read(off));
  EXPECT_EQ(message.find('\x1b'), std::string::npos) << message;
  EXPECT_EQ(message.find('\x07'), std::string::npos) << message;
  EXPECT_NE(message.find("\\x1b]0;pwned\\x07OFF"), std::string::npos) << message;
  EXPECT_EQ(message.find("\\\\x1b"), std::string::npos) << message;  // escaped once
}

// --- Still open from the third pass ---

// Zero-area faces are dropped with a warning, as meshpair does, and the grasp runs; the integer
// options read in decimal ("010" is 10, not octal 8).
TEST_F(HostileFormatsTest, GraspObjectDropsZeroAreaFacesAsMeshpairDoes) {
  const std::string box =
      write("box.obj",
            "v 100 -20 10\nv 150 -20 10\nv 150 20 10\nv 100 20 10\n"
            "v 100 -20 70\nv 150 -20 70\nv 150 20 70\nv 100 20 70\n"
            "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
            "f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\nf 1 2 2\nf 3 3 3\n");
  const fs::path out = dir_ / "out.json";
  const auto r = run("('" + std::string(GRASPCD_EXE) + "' grasp --object " + box +
                     " --scale 0.001 --max-steps 1 --noslip 010 --json > '" + out.string() + "')");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("zero-area"), std::string::npos) << r.err;
  const nlohmann::json doc = load(out);
  EXPECT_EQ(doc["noslip_iterations"], 10) << doc.dump();
}

}  // namespace
