// The files of a convex decomposition: one Wavefront OBJ per convex piece and an MJCF fragment
// that MuJoCo 2.2 includes (docs/design.md, "Convex decomposition").
#pragma once

#include <string>
#include <vector>

#include "graspcd/decompose/hacd.h"

namespace graspcd::decompose {

struct DecompositionFiles {
  std::vector<std::string> pieces;  // file names (no folder): STEM_piece_K.obj, K = 0, 1, ...
  std::string fragment;             // file name of the MJCF fragment: STEM.xml
};

// Writes into the folder `dir` (which must exist) one OBJ per piece, vertices printed with 17
// significant digits (the doubles read back unchanged), and the fragment, written with tinyxml2:
//
//   <mujocoinclude>
//     <asset> <mesh name="STEM_piece_K" file="STEM_piece_K.obj"/> ... </asset>
//     <worldbody> <body name="STEM"> <geom name="STEM_piece_K" type="mesh"
//                                          mesh="STEM_piece_K"/> ... </body> </worldbody>
//   </mujocoinclude>
//
// The mesh files are named relative to `dir`: a model that includes the fragment sets
// <compiler meshdir="DIR"/> (or copies the <mesh> lines with its own paths). `comment` (one line,
// e.g. the source mesh and the command) opens the fragment as an XML comment. Throws
// std::runtime_error naming the file that cannot be written, in the folder `named` (default
// `dir`: the folder the user knows, when `dir` is a private one renamed to it later).
DecompositionFiles write_decomposition_files(const std::vector<ConvexPiece>& pieces,
                                             const std::string& dir, const std::string& stem,
                                             const std::string& comment,
                                             const std::string& named = "");

}  // namespace graspcd::decompose
