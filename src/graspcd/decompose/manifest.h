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
  std::string engine = "hacd";  // "hacd" or "vhacd"; a manifest without it is HACD's
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
// read when present. Throws io::InputError naming DIR when the manifest is missing, naming the
// manifest when it is not a decomposition or has no pieces.
Manifest read_manifest(const std::string& dir);

}  // namespace graspcd::decompose
