// `graspcd decompose` as a library: an approximate convex decomposition of a mesh with HACD (Mamou
// and Ghorbel, ICIP 2009; hacd.h) or V-HACD 4 (Mamou 2016, run by node; vhacd.h), written as one
// OBJ per convex piece and an MJCF fragment (decomposition_files.h), with how far the pieces' hulls
// lie from the original surface (CGAL's bounded-error one-sided Hausdorff distance) and, for a
// closed mesh, the volume they add. Beside the pieces it writes the manifest,
// DIR/decomposition.json (manifest.h).
#pragma once

#include <functional>
#include <stdexcept>
#include <string>

#include "graspcd/decompose/manifest.h"

namespace graspcd::decompose {

// kGiven: no engine; the pieces are read from a folder (decompose --describe: a published
// decomposition, e.g. the convex pieces a model set ships beside its meshes).
enum class Engine { kHacd, kVhacd, kGiven };

// The engine's name as the command line and the manifest write it: "hacd", "vhacd", "given".
const char* engine_name(Engine engine);

struct DecomposeOptions {
  std::string mesh;  // any format io::load_mesh reads
  double scale = 1;  // its coordinates multiplied by this (file units to metres)
  // The scale was given (--scale): the pieces are in metres (Manifest::units "m").
  bool scale_given = false;
  std::string out;  // the folder of the pieces, the fragment and the manifest (created)
  Engine engine = Engine::kHacd;
  int pieces = 16;             // at most this many pieces (HACD's clusters, V-HACD's hulls)
  int simplify = 0;            // HACD only. 0: HACD on the mesh itself; F: on a copy of <= F faces
  int resolution = 400000;     // V-HACD only: its voxels in the mesh's bounding box
  double timeout = 600;        // V-HACD only: node is stopped after this many s
  std::string vhacd_script;    // V-HACD only: empty for default_vhacd_script() (vhacd.h)
  double hausdorff_bound = 0;  // 0: kDefaultBoundFraction of the bounding box diagonal
  // Engine::kGiven: the folder of the pieces, each a mesh file (any format io::load_mesh reads)
  // in `mesh`'s coordinates and units, taken in the order of their names (numbers by value:
  // contact2 before contact10). Each is written as its convex hull (qhull), which is what
  // MuJoCo collides, scaled as `mesh` is.
  std::string describe;
  // Called as the work goes (e.g. for progress lines): what is being done and, when known, the
  // share of that stage done (0 to 1; negative: unknown). HACD reports its merges.
  std::function<void(const std::string&, double)> progress;
};

// The Hausdorff distance's error bound when DecomposeOptions::hausdorff_bound is 0: this fraction
// of the mesh's bounding box diagonal (0.1 mm for a 10 cm object).
inline constexpr double kDefaultBoundFraction = 1e-3;

// The finest Hausdorff bound accepted: this fraction of the bounding box diagonal. A finer bound
// (down to the coordinates' floating-point resolution and below) refines the distance without
// end; DecomposeOptions::hausdorff_bound below it is refused before anything runs.
inline constexpr double kMinBoundFraction = 1e-6;

// The coarsest Hausdorff bound accepted: the bounding box diagonal itself. A distance known only to
// within the mesh's size says nothing (CGAL then answers the bound itself, and a bound of 1e308
// overflows to an infinite distance); a coarser DecomposeOptions::hausdorff_bound is refused
// before anything runs.
inline constexpr double kMaxBoundFraction = 1;

// Thrown by decompose_mesh for a DecomposeOptions::hausdorff_bound below kMinBoundFraction or
// above kMaxBoundFraction of the mesh's bounding box diagonal (the command line names its option
// before the message).
class BoundError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// The pieces may hold less volume than the closed mesh they come from (e.g. a cube cut into thin
// slabs along its faces): more than this fraction lost is warned about ("decompose_volume_lost").
// A gain is reported, not warned: pieces that close a cavity (a cup's) gain by design.
inline constexpr double kMaxVolumeLoss = 0.1;

// Every piece lies in the mesh's bounding box (a hull of its points; V-HACD's shrink-wrapped onto
// it), so no point of a piece is farther from the surface than the box's diagonal: a Hausdorff
// distance beyond this many diagonals (by more than its error bound) is an engine's answer that
// does not fit the mesh, warned about ("decompose_far_pieces").
inline constexpr double kFarPiecesDiagonals = 1.0;

struct DecomposeRun {
  Manifest manifest;
  std::string document;  // decomposition.json as written (with graspcd's envelope), no final '\n'
};

// Decomposes `options.mesh` into `options.out` (Engine::kGiven: describes the pieces of
// `options.describe` as its decomposition, refusing pieces that do not lie where the mesh lies,
// decompose::placement_mismatch) and writes the manifest there. The folder is
// written whole or not at all: in a private folder beside it (.NAME.graspcd-XXXXXX, removed on
// errors and on INT, TERM and HUP), renamed to it at the end. A folder that holds nothing, or
// only an earlier decomposition (decomposition.json and the files it lists), is replaced whole
// and keeps its mode; one that holds the mesh the run reads or any file the earlier
// decomposition did not write, or that is read-only (io::writable_folder), is refused before the
// work. Warnings (the mesh's hygiene, flat clusters left out, a volume CGAL
// cannot measure) go to the process's sink. Throws io::InputError naming the mesh for a missing
// or bad mesh or a failed decomposition, naming `options.out` when it cannot be used or written;
// VhacdUnavailable (vhacd.h) for Engine::kVhacd where node or the vhacd-js package is missing;
// std::invalid_argument for simplify with Engine::kVhacd.
DecomposeRun decompose_mesh(const DecomposeOptions& options);

// The text of `graspcd decompose` (its --help, "Text output"): the engine, the pieces, the
// simplification, the time, the Hausdorff distance, the volume added and the fragment's path.
std::string decomposition_text(const Manifest& manifest, const DecomposeOptions& options);

}  // namespace graspcd::decompose
