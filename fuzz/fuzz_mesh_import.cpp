// libFuzzer target: the formats load_mesh (io/mesh_io.h) reads besides OBJ and binary STL. The
// first byte picks the format (PLY, GLB, glTF, COLLADA through Assimp in its child process; OFF and
// ASCII STL read by graspcd), the rest is the file. Bad input must end in io::InputError (a crash
// or a hang of Assimp included: the child's signal or its timeout, shortened here to 2 s); a mesh
// that loads must hold finite coordinates in the exact range, faces naming its vertices and no
// zero-area face. With GRASPCD_FUZZ_IN_PROCESS=1 in the environment, Assimp reads in this process
// instead (mesh_import.h, isolated = false): how the crashes the child turns into errors are found.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "fuzz_support.h"
#include "graspcd/core/mesh_hygiene.h"
#include "graspcd/core/tolerances.h"
#include "graspcd/io/mesh_import.h"
#include "graspcd/io/mesh_io.h"

namespace {

const char* const kFormats[] = {"ply", "glb", "gltf", "dae", "off", "stl"};

bool in_process() {
  static const bool yes = [] {
    const char* v = std::getenv("GRASPCD_FUZZ_IN_PROCESS");
    return v != nullptr && std::string(v) == "1";
  }();
  return yes;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static graspcd::fuzz::InputFile files[] = {
      graspcd::fuzz::InputFile("input.ply"),  graspcd::fuzz::InputFile("input.glb"),
      graspcd::fuzz::InputFile("input.gltf"), graspcd::fuzz::InputFile("input.dae"),
      graspcd::fuzz::InputFile("input.off"),  graspcd::fuzz::InputFile("input.stl")};
  static const bool timeout_set = [] {
    graspcd::io::set_import_timeout(2);
    return true;
  }();
  (void)timeout_set;
  const std::size_t k = data[0] % (sizeof(kFormats) / sizeof(kFormats[0]));
  const std::string& path = files[k].write(data + 1, size - 1);
  if (in_process() && k < 4) {
    // Only what load_mesh hands to Assimp: a file that starts as its extension says.
    const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
    const bool looks_right = k == 0   ? text.rfind("ply", 0) == 0
                             : k == 1 ? text.rfind("glTF", 0) == 0
                             : k == 2 ? text.find_first_not_of(" \t\r\n") != std::string::npos &&
                                            text[text.find_first_not_of(" \t\r\n")] == '{'
                                      : text.substr(0, 4096).find("<COLLADA") != std::string::npos;
    if (looks_right) graspcd::io::import_with_assimp(path, kFormats[k], false);
    return 0;
  }
  graspcd::TriangleMesh mesh;
  try {
    mesh = graspcd::io::load_mesh(path);
  } catch (const graspcd::io::InputError& e) {
    if (std::string(e.what()).find('\n') != std::string::npos) {
      graspcd::fuzz::disagreement("an error of more than one line");
    }
    return 0;
  }
  for (const graspcd::Vec3& v : mesh.vertices) {
    for (int i = 0; i < 3; ++i) {
      const double m = std::fabs(v[i]);
      if (!(v[i] == 0 || (m >= graspcd::tol::kMinCoordinate && m <= graspcd::tol::kMaxCoordinate)))
        graspcd::fuzz::disagreement("a loaded coordinate outside the exact range");
    }
  }
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    for (const std::int32_t i : mesh.faces[f]) {
      if (i < 0 || static_cast<std::size_t>(i) >= mesh.vertices.size())
        graspcd::fuzz::disagreement("a loaded face names no vertex");
    }
    if (graspcd::is_zero_area(mesh.triangle(f)))
      graspcd::fuzz::disagreement("a zero-area face was kept");
  }
  return 0;
}
