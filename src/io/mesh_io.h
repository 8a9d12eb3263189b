// Mesh files: Wavefront OBJ (tinyobjloader, double precision) and binary STL, read in their own
// file coordinates into a TriangleMesh.
#pragma once

#include <cstddef>
#include <string>

#include "core/geometry.h"
#include "io/text_input.h"

namespace graspcd::io {

// Facts about a loaded mesh that the caller may want to report.
struct MeshStats {
  // Faces whose three vertices are exactly collinear or coincident (decided with exact
  // predicates). They are kept: the tree and the triangle tests answer them as segments or points.
  std::size_t zero_area_faces = 0;
};

// Loads an OBJ (".obj") or binary STL (".stl") file; the format comes from the extension, case
// insensitive.
//  - OBJ: every object and group is concatenated into one mesh; polygons are triangulated
//    (tinyobjloader's triangulation); normals, texture coordinates and materials are ignored.
//    Coordinates are the doubles tinyobjloader's own number parser gives (its double build). That
//    parser reads a word such as "nan" as 0 and "1e999" as inf, so every vertex line ('v' then a
//    blank) is first read with the command line's number grammar (text_input.h, parse_number):
//    3, 4 (x y z w) or 6 (x y z r g b) numbers, no hexadecimal floats (tinyobjloader cannot read
//    them); a bad one is reported at its line, "FILE:LINE: vertex N: <parse_number's message>".
//    tinyobjloader's values must then equal those to within its rounding (relative 1e-12), or
//    the line is reported.
//  - STL: binary only (80-byte header, uint32 count, 50-byte records; the file size must be
//    84 + 50 * count). An ASCII STL is rejected. Bit-identical vertices are shared.
// Throws InputError, "FILE: message" (or "FILE:LINE: message" when the line is known), on: a file
// that cannot be opened, an unknown extension, a parse error, a face with fewer than three
// vertices or a vertex index out of range, a non-finite coordinate (nan, inf, an overflowing
// literal, a NaN or infinite STL float) or one outside the exact-arithmetic range of
// tolerances.h, and a mesh without faces.
TriangleMesh load_mesh(const std::string& path, MeshStats* stats = nullptr);

}  // namespace graspcd::io
