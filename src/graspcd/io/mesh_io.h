// Mesh files, read in their own file coordinates into a TriangleMesh: Wavefront OBJ
// (tinyobjloader, double precision), STL (binary and ASCII), OFF, and through Assimp 5.2 (in a
// child process: mesh_import.h) PLY, glTF 2.0 (.gltf, .glb) and COLLADA (.dae).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "graspcd/core/containment.h"
#include "graspcd/core/geometry.h"
#include "graspcd/io/text_input.h"

namespace graspcd::io {

// The formats load_mesh reads, as an error message names them.
inline constexpr const char* kMeshFormats = "expected .obj, .stl, .ply, .off, .gltf, .glb or .dae";

// The most triangles MuJoCo 2.2 reads from a binary STL file (it refuses more, asking whether the
// file is ASCII).
inline constexpr std::uint64_t kMujocoStlFaces = 200000;

// Facts about a loaded mesh that the caller may want to report (mesh_warnings() words them).
struct MeshStats {
  // Zero-area faces (three vertices exactly collinear or coincident, after welding) dropped on
  // load: their count, and their 0-based face ids in the file's face order (triangulated).
  std::size_t zero_area_faces = 0;
  std::vector<std::int32_t> dropped_faces;
  // For each face of the loaded mesh, its 0-based face id in the file: loaded faces map back.
  std::vector<std::int32_t> source_face;
  // Vertices merged into an equal earlier vertex (core/mesh_hygiene.h), of `file_vertices`.
  std::size_t welded_vertices = 0;
  std::size_t file_vertices = 0;
  // The surface after welding (core/containment.h): the containment check needs a closed mesh.
  Closedness closedness;
  // OBJ: the names of the file's objects ('o' lines), in order. MuJoCo 2.2 loads only the first.
  std::vector<std::string> obj_objects;
  // The format read ("OBJ", "binary STL", "ASCII STL", "OFF", "PLY", "glTF", "COLLADA").
  std::string format;
  // True when the format fixes the unit as the metre (glTF by definition; COLLADA, scaled to
  // metres by its <unit meter>): a size in it is a size in metres, whatever the user expects.
  bool in_metres = false;
  // The meshes of a file read through Assimp (their names, "" when unnamed), concatenated in
  // this order as an OBJ's objects are.
  std::vector<std::string> parts;
};

// One line per finding of a load, each starting with "PATH: ": vertices welded, zero-area faces
// dropped, an open mesh, an OBJ file with more than one object. Empty for a clean, closed mesh.
// `changes_only`: only the findings that change what a surface query answers or what MuJoCo
// loads (dropped faces, several objects), for commands without a containment check.
std::vector<std::string> mesh_warnings(const std::string& path, const MeshStats& stats,
                                       bool changes_only = false);

// The signed volume enclosed by a mesh's faces (file units cubed): positive when they point
// outward (counter-clockwise seen from outside), negative when every face is reversed. Meaningful
// for a closed mesh only.
double signed_volume(const TriangleMesh& mesh);

// A closed mesh (stats.closedness) with a negative signed volume, its faces pointing inward,
// turned right way out by reversing every face; `unit` (m per file unit) words the volume in the
// returned warning, "PATH: the faces point inward (signed volume -V m^3): flipped". An open mesh
// or one with a positive volume is left as it is, and the warning is empty.
std::string turn_right_way_out(const std::string& path, const MeshStats& stats, TriangleMesh* mesh,
                               double unit = 1);

// Writes a mesh as a Wavefront OBJ ('v' and 'f' lines, 17 significant digits: it reads back
// exactly). Throws std::runtime_error when the file cannot be written.
void write_obj(const std::string& path, const TriangleMesh& mesh);

// Loads a mesh file; the format comes from the extension, case insensitive: ".obj", ".stl"
// (binary, or ASCII when the file starts with "solid" and its size is not a binary STL's),
// ".off", ".ply", ".gltf", ".glb", ".dae". Every format gets the same checks (finite
// coordinates in the exact-arithmetic range, faces of at least 3 vertices naming vertices of the
// file) and the same hygiene (below); a file of several meshes or objects is one mesh, all of
// them concatenated.
//  - OBJ (tinyobjloader, double precision): every object and group concatenated, polygons
//    triangulated; normals, texture coordinates and materials ignored. Every vertex line is read
//    with the command line's number grammar (text_input.h, parse_number), every face line
//    checked, each error at its line ("FILE:LINE: vertex N: ...", "FILE:LINE: face N: ..."); a
//    UTF-8 byte-order mark is refused.
//  - binary STL; ASCII STL and OFF (read here, double precision, errors at their line; OFF
//    polygons triangulated as fans).
//  - PLY, glTF 2.0 and GLB, COLLADA: Assimp 5.2 in a child process (mesh_import.h): a crash or a
//    hang of Assimp on a hostile file is one error; errors name the mesh and face, not a line.
// Hygiene (core/mesh_hygiene.h), after reading either format: equal vertices are welded, and
// zero-area faces are dropped (docs/design.md "Semantics"); `stats` says what was done, and maps
// every loaded face to its face id in the file. A mesh whose faces all have zero area is an error.
// Throws InputError, "FILE: message" (or "FILE:LINE: message" when the line is known), on: a file
// that cannot be opened, an unknown extension, a parse error, a face with fewer than three
// vertices or a vertex index out of range, a non-finite coordinate (nan, inf, an overflowing
// literal, a NaN or infinite STL float) or one outside the exact-arithmetic range of
// tolerances.h, and a mesh without faces.
TriangleMesh load_mesh(const std::string& path, MeshStats* stats = nullptr);

// The mesh multiplied by `scale` (--scale: file units to metres), every coordinate checked again
// for the exact-arithmetic range: "FILE: at --scale S vertex N has coordinate ...". A scale of 1
// leaves the mesh as it is.
void scale_mesh(const std::string& path, double scale, TriangleMesh* mesh);

// The checks of load_mesh that come before any mesh is built, for a mesh file another reader
// (MuJoCo's, for the meshes a scene names) will read: an OBJ's byte-order mark, vertex lines
// (the number grammar: no nan, inf or out-of-range coordinate, which MuJoCo would read as 0 or
// inf) and face lines (at least 3 vertices, every index naming a vertex); a binary STL's size and
// its coordinates, its triangles (at most kMujocoStlFaces), and an ASCII STL refused (MuJoCo 2.2
// reads binary STL only). Other formats are left to their reader. Throws InputError as load_mesh
// does.
void check_mesh_file(const std::string& path);

}  // namespace graspcd::io
