// What a file of the formats read through Assimp (mesh_import.h) declares about itself, and the
// checks of it that Assimp does not make: it reads past a PLY header's counts, drops the glTF
// triangles that name vertices its POSITION accessor does not hold, reads a glTF POSITION of any
// type into three floats, and scales a COLLADA mesh by any <unit meter> (a negative one mirrors it,
// a word reads as 1). The declared structure is read with the project's parsers (the PLY header is
// text, a glTF's JSON goes to nlohmann, a COLLADA file to tinyxml2), never with a reader of the
// meshes themselves. Used by load_mesh (mesh_io.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace graspcd::io {

// A glTF primitive as its JSON declares it.
struct DeclaredPrimitive {
  std::size_t mesh = 0;               // its index in "meshes" (0-based, as the JSON counts)
  std::size_t primitive = 0;          // its index in that mesh's "primitives"
  std::uint64_t triangles = 0;        // the triangles its indices (or vertices) make
  bool triangle_mode = false;         // mode 4, 5 or 6 (points and lines are refused later)
  std::size_t position_accessor = 0;  // its POSITION accessor
  std::uint64_t positions = 0;        // that accessor's count
  long long indices_accessor = -1;    // its indices accessor, -1 without one
};

// What load_mesh checks after Assimp read the file (empty for PLY and COLLADA, and for a glTF
// whose structure is not glTF 2.0's).
struct DeclaredMesh {
  std::vector<DeclaredPrimitive> primitives;  // glTF: every primitive, in the file's order
};

// The checks made before Assimp reads `path` (`format`: "ply", "gltf", "glb", "dae"), each an
// InputError naming the file and what is inconsistent:
//  - PLY in ASCII: the elements the header declares (one line each) against the lines that
//    follow end_header ("the header declares 104 elements (4 vertex, 100 face), one line each in
//    an ASCII PLY, but 8 lines of data follow end_header"); in binary, the bytes its counts need
//    at least against the bytes that follow;
//  - glTF and GLB: JSON that nlohmann cannot parse ("FILE:LINE: bad JSON: ..."), a POSITION
//    accessor that is not VEC3 of 32-bit floats;
//  - COLLADA: XML that tinyxml2 cannot parse, a <unit meter> that is not a finite positive number.
// Returns what is checked after the import (check_read_faces).
DeclaredMesh check_declared(const std::string& path, const std::string& format);

// The faces Assimp's reader made of each mesh (ImportedMesh::read_faces) against the triangles
// each glTF primitive declares: fewer are triangles that named a vertex beyond the POSITION
// accessor, which Assimp drops ("meshes[0].primitives[0]: 2 of its 4 triangles (indices accessor
// 1) name a vertex beyond the 4 of its POSITION accessor 0"). Nothing is checked when the counts
// of meshes differ.
void check_read_faces(const std::string& path, const DeclaredMesh& declared,
                      const std::vector<std::uint64_t>& read_faces);

}  // namespace graspcd::io
