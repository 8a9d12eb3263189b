// Approximate convex decomposition of a triangle mesh with V-HACD 4, volumetric hierarchical
// approximate convex decomposition (K. Mamou, "Volumetric hierarchical approximate convex
// decomposition", Game Engine Gems 3, 2016; github.com/kmammou/v-hacd, version 4), as the npm
// package vhacd-js compiles it to WebAssembly. graspcd runs it in a child process: node with the
// script tools/vhacd/vhacd.mjs, whose folder holds the package (`npm ci` there; ./run build does
// it). The mesh and the hulls cross through JSON files in a temporary folder.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

#include "graspcd/core/geometry.h"
#include "graspcd/decompose/hacd.h"

namespace graspcd::decompose {

// The knobs of V-HACD that graspcd sets; the others are V-HACD 4's defaults, given explicitly:
// the voxels filled by flood fill, the hulls' points shrink-wrapped onto the mesh, a hull kept
// when it is within 1% of its voxels' volume, at most 10 levels of splitting.
struct VhacdOptions {
  std::size_t max_hulls = 16;             // V-HACD's maxHulls, >= 1
  std::size_t voxel_resolution = 400000;  // voxels of the mesh's bounding box (V-HACD's default)
  std::size_t max_vertices_per_hull = 64;
  double timeout_seconds = 600;  // node is killed after this long
  std::string script;            // tools/vhacd/vhacd.mjs; empty: default_vhacd_script()
};

// Thrown when the engine cannot run here: node is not on PATH, or the script or its vhacd-js
// package (the script's folder's node_modules) is missing. what(): which of them, one line.
class VhacdUnavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The script: the environment variable GRASPCD_VHACD_SCRIPT when set, else tools/vhacd/vhacd.mjs
// of the source tree graspcd was built from.
std::string default_vhacd_script();

// Empty when node and the script with its package are there; else what is missing (one line).
std::string vhacd_missing(const VhacdOptions& options);

// V-HACD's hulls of `mesh` (at least one face), each made again by qhull from the hull's points
// (convex_hull: faces outward, as HACD's pieces); a hull without volume is left out and counted in
// flat_clusters; no slabs. At most options.max_hulls pieces. node runs as a child tied to the run
// and the files cross through a temporary folder guarded as the run's (io/output_files.h: both
// go on INT, TERM and HUP). Throws VhacdUnavailable (see above), io::InputError for a missing
// TMPDIR, std::runtime_error when node fails (the error vhacd.mjs or node reports, never node's
// version banner or a stack frame), runs past the timeout (it is killed), answers with something
// that is not hulls, or gives no hull with a volume.
Decomposition vhacd_decompose(const TriangleMesh& mesh, const VhacdOptions& options);

}  // namespace graspcd::decompose
