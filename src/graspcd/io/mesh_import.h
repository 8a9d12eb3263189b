// The reader of the mesh formats that graspcd reads through Assimp 5.2 (Debian's libassimp): PLY
// (ASCII and binary), glTF 2.0 (.gltf with its buffers, .glb) and COLLADA (.dae). Used by
// load_mesh (mesh_io.h), which applies the checks and the hygiene every format gets; no Assimp
// header leaks out of it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "graspcd/core/geometry.h"

namespace graspcd::io {

// What Assimp read, every mesh of the file concatenated in the scene's order, each placed by its
// nodes' transforms (aiProcess_PreTransformVertices: a glTF node's matrix or TRS, a COLLADA
// node's transform), polygons triangulated (aiProcess_Triangulate). COLLADA keeps the file's
// axes (its up_axis is not turned to Y-up) and is scaled to metres by its <unit meter>, as
// Assimp does; glTF is in metres by definition.
struct ImportedMesh {
  TriangleMesh mesh;
  std::vector<std::string> parts;  // the meshes' names, in order ("" when unnamed)
  // The faces of each mesh as the format's reader made them, before the post-processing joins
  // and places them: for glTF, one mesh per primitive, in the file's order (meshes, then their
  // primitives), so that they can be checked against what the file declares (mesh_declared.h).
  std::vector<std::uint64_t> read_faces;
  // On failure: Assimp's message (on one line), and where it was found when the reader knows:
  // the mesh (1-based) and its face (1-based) or vertex; 0 when not known.
  std::string error;
  std::size_t error_mesh = 0;
  std::size_t error_face = 0;
};

// The file read by Assimp. `format` is the lower-case extension ("ply", "gltf", "glb", "dae").
// A file Assimp cannot read, a point or a line primitive (a face of fewer than three vertices)
// or a file without any triangle come back with `error` set; the caller words it.
// In a process of its own when `isolated` (this program run again, /proc/self/exe, which reads
// the file before its main and ends): a crash or a hang of the reader (killed after
// `timeout_seconds`) is then an error, not the caller's end. Where graspcd is linked into a shared
// library that another program loaded (a plugin, a Python module), that program run again would
// not read: the reader is then a forked child that reads the file itself, and it can block when
// another thread of the program held a lock at the fork (the allocator's, under a sanitizer).
// A negative timeout: the process-wide one (import_timeout).
ImportedMesh import_with_assimp(const std::string& path, const std::string& format,
                                bool isolated = true, double timeout_seconds = -1);

// The time load_mesh gives the process that reads a file through Assimp before it is killed
// and the file refused ("FILE: the import library did not finish reading it in N s"); default
// kImportTimeout. Process-wide (the fuzz target shortens it).
inline constexpr double kImportTimeout = 60;
void set_import_timeout(double seconds);
double import_timeout();

}  // namespace graspcd::io
