// The manifest of a convex decomposition, DIR/decomposition.json: what `graspcd decompose`
// (mesh_decomposition.h) made, written beside the pieces and read back by the decomposed grasp
// (graspcd/grasp/decomposed_scene.h). Manifest is its one description, and its keys are written
// and read here alone.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "graspcd/core/geometry.h"

namespace graspcd::decompose {

// The manifest's file name in the decomposition's folder.
inline constexpr const char* kManifestFile = "decomposition.json";

// decomposition.json; each field under its JSON key.
struct Manifest {
  struct Simplify {  // "simplify", null without --simplify
    int max_faces = 0;
    std::size_t faces_before = 0;
    std::size_t faces_after = 0;
    bool decimated = false;
    double seconds = 0;
  };
  struct Hausdorff {  // "hausdorff": from the pieces' surfaces to the mesh's, m
    double distance = 0;
    double error_bound = 0;
    double seconds = 0;
  };
  struct Volume {  // "volume", null for an open mesh, m^3
    double original = 0;
    double pieces = 0;
    double added = 0;
    double added_fraction = 0;
  };
  struct Piece {       // "pieces"
    std::string file;  // relative to the manifest's folder
    std::size_t vertices = 0;
    std::size_t faces = 0;
  };
  std::string source;           // the mesh, absolute
  std::string engine = "hacd";  // "hacd", "vhacd" or "given"; a manifest without it is HACD's
  // "scale": the pieces' coordinates are the source file's times this (decompose --scale), so a
  // scene whose <mesh> of the source has the scale A collides piece files scaled by A / scale
  // (grasp/decomposed_scene.h). A manifest without it (written before graspcd 0.5) is read as 1,
  // with `scale_recorded` false.
  double scale = 1;
  bool scale_recorded = true;
  // "units": "m" when the pieces are in metres (a --scale was given, or the source's format is in
  // metres: glTF, COLLADA), "source" when they are in the source file's own units.
  std::string units = "source";
  // "pieces_from": for engine "given" (decompose --describe), the folder the pieces were read
  // from, absolute; empty otherwise.
  std::string pieces_from;
  // "engine_parameters": the engine's settings, each under its name (an object of numbers; an
  // integral value is written as an integer).
  std::vector<std::pair<std::string, double>> engine_parameters;
  std::size_t source_faces = 0;
  bool closed = false;
  int max_pieces = 0;
  std::optional<Simplify> simplify;
  std::size_t piece_count = 0;
  std::size_t slabs = 0;
  std::size_t flat_clusters = 0;
  double seconds = 0;  // the engine and the hulls (with --simplify, after the decimation), s
  Hausdorff hausdorff;
  std::optional<Volume> volume;
  std::string fragment;  // the MJCF fragment's file name
  std::vector<Piece> pieces;
};

// Writes DIR/decomposition.json: the manifest with graspcd's envelope (graspcd/version/envelope.h:
// provenance and the process's warnings), indented by 2. Returns the document as written, without
// its final line break.
std::string write_manifest(const std::string& dir, const Manifest& manifest);

// Reads DIR/decomposition.json: "source" and "pieces" (each with "file") are required, the rest is
// read when present; a missing "scale" is 1, with Manifest::scale_recorded false (the caller
// warns), and one that is not a finite number > 0 is refused. Throws io::InputError naming DIR when
// the manifest is missing, naming the manifest when it is not a decomposition or has no pieces.
Manifest read_manifest(const std::string& dir);

// An axis-aligned bounding box.
struct Box {
  Vec3 lo = Vec3::Zero();
  Vec3 hi = Vec3::Zero();
  double diagonal() const { return (hi - lo).norm(); }
};

// The bounding box of a mesh's vertices (at least one).
Box bounding_box(const TriangleMesh& mesh);

// The bounding box of every piece of `manifest` (the files under `dir`, read by io::load_mesh), in
// their own coordinates. Throws io::InputError naming a piece that cannot be read.
Box pieces_box(const std::string& dir, const Manifest& manifest);

// Pieces belong to a mesh at a scale when their box matches the mesh's box times that scale: its
// diagonal within this factor either way, its centre within kPlacementOffset of that diagonal.
// Pieces approximate the surface (hulls stand out of a concavity; a flat cluster left out shrinks
// them a little), while a scale applied twice or forgotten is a factor of 10 or more (0.001,
// 0.01, 0.0254).
inline constexpr double kPlacementRatio = 1.5;
inline constexpr double kPlacementOffset = 0.25;

// Whether pieces whose box is `pieces` are pieces of the mesh whose box is `source` (in its file's
// coordinates) at `scale`: "" when they are (above), else one line saying how they differ, e.g.
// "its pieces are 0.01 times the size of the mesh at scale 1 (0.0812 against 8.12 across):
// written at scale 0.01?".
std::string placement_mismatch(const Box& source, double scale, const Box& pieces);

}  // namespace graspcd::decompose
