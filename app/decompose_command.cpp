// graspcd decompose MESH --out DIR [--pieces N] [--simplify F] [--hausdorff-bound B] [--json]: an
// approximate convex decomposition with HACD (Mamou and Ghorbel, ICIP 2009), written as one OBJ
// per convex piece and an MJCF fragment, with how far the pieces' hulls lie from the original
// surface (CGAL's bounded-error one-sided Hausdorff distance) and, for a closed mesh, the volume
// they add. --simplify F: HACD partitions a copy decimated to at most F faces (CGAL's edge
// collapse), each original face joins the cluster of its nearest decimated face, and the pieces
// are the hulls of the original vertices.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "command.h"
#include "graspcd/core/clock.h"
#include "graspcd/core/geometry.h"
#include "graspcd/core/warnings.h"
#include "graspcd/decompose/decomposition_files.h"
#include "graspcd/decompose/hacd.h"
#include "graspcd/exact/hausdorff.h"
#include "graspcd/exact/simplify.h"
#include "graspcd/exact/surface_distance.h"
#include "graspcd/io/mesh_io.h"
#include "graspcd/io/text_input.h"
#include "graspcd/version/envelope.h"

namespace graspcd::cli {

namespace {

namespace fs = std::filesystem;

// The Hausdorff distance's error bound when --hausdorff-bound is not given: this fraction of the
// mesh's bounding box diagonal (0.1 mm for a 10 cm object).
constexpr double kDefaultBoundFraction = 1e-3;

// The manifest `decompose` leaves in DIR beside the pieces (read by grasp --decomposed).
constexpr const char* kManifest = "decomposition.json";

struct DecomposeOptions {
  std::string mesh;
  std::string out;
  int pieces = 16;
  int simplify = 0;            // 0: HACD on the mesh itself; F: on a copy of at most F faces
  double hausdorff_bound = 0;  // 0: kDefaultBoundFraction of the diagonal
  bool json = false;
};

double bounding_diagonal(const TriangleMesh& mesh) {
  Vec3 lo = mesh.vertices.front(), hi = lo;
  for (const Vec3& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  return (hi - lo).norm();
}

// HACD's partition of `coarse` (the decimated copy) carried over to `mesh`: every face of `mesh`
// joins the cluster of the face of `coarse` nearest its centroid (CGAL's AABB tree).
decompose::Partition transfer_partition(const decompose::Partition& coarse_partition,
                                        const TriangleMesh& coarse, const TriangleMesh& mesh) {
  const exact::SurfaceDistance nearest(coarse);
  decompose::Partition out;
  out.clusters = coarse_partition.clusters;
  out.cluster_of_face.reserve(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Triangle t = mesh.triangle(f);
    const Vec3 centroid = (t.v[0] + t.v[1] + t.v[2]) / 3.0;
    out.cluster_of_face.push_back(coarse_partition.cluster_of_face[nearest.nearest_face(centroid)]);
  }
  return out;
}

void run_decompose(const DecomposeOptions& o) {
  // The mesh as graspcd reads it: a bad file is one line naming it, exit code 2.
  io::MeshStats stats;
  const TriangleMesh mesh = io::load_mesh(o.mesh, &stats);
  for (const std::string& w : io::mesh_warnings(o.mesh, stats, true)) {
    warnings().add("mesh_hygiene", w);
  }
  std::error_code ec;
  fs::create_directories(o.out, ec);
  if (ec || !fs::is_directory(o.out)) {
    throw io::InputError(o.out, 0, "cannot create the output folder: " + ec.message());
  }

  // --simplify: the copy HACD partitions, decimated by CGAL's edge collapse when the mesh has more
  // than F faces, timed alone.
  nlohmann::json simplify = nullptr;
  TriangleMesh coarse;
  const bool decimate = o.simplify > 0 && mesh.faces.size() > static_cast<std::size_t>(o.simplify);
  if (o.simplify > 0) {
    const Clock::time_point s_start = Clock::now();
    if (decimate) {
      try {
        coarse = exact::simplify_edge_collapse(mesh, static_cast<std::size_t>(o.simplify));
      } catch (const std::invalid_argument& e) {
        throw io::InputError(o.mesh, 0, e.what());
      }
    }
    simplify = {{"max_faces", o.simplify},
                {"faces_before", mesh.faces.size()},
                {"faces_after", decimate ? coarse.faces.size() : mesh.faces.size()},
                {"decimated", decimate},
                {"seconds", seconds_since(s_start)}};
  }

  // HACD, timed with the pieces' hulls (and with --simplify, the transfer of the decimated copy's
  // partition to the mesh's faces).
  decompose::HacdOptions hacd;
  hacd.max_pieces = static_cast<std::size_t>(o.pieces);
  const Clock::time_point start = Clock::now();
  decompose::Decomposition d;
  try {
    if (decimate) {
      const decompose::Partition partition =
          transfer_partition(decompose::hacd_partition(coarse, hacd), coarse, mesh);
      d = decompose::pieces_of_partition(mesh, partition);
    } else {
      d = decompose::hacd_decompose(mesh, hacd);
    }
  } catch (const std::runtime_error& e) {
    throw io::InputError(o.mesh, 0, e.what());
  }
  const double seconds = seconds_since(start);
  if (d.flat_clusters > 0) {
    warnings().add("decompose_flat_pieces",
                   o.mesh + ": " + std::to_string(d.flat_clusters) +
                       " of HACD's clusters have no hull even as a slab and were left out");
  }

  // How far the pieces' hulls lie from the original surface, and the volume they add.
  std::vector<TriangleMesh> hulls;
  for (const decompose::ConvexPiece& p : d.pieces) hulls.push_back(p.hull);
  const double bound =
      o.hausdorff_bound > 0 ? o.hausdorff_bound : kDefaultBoundFraction * bounding_diagonal(mesh);
  const Clock::time_point h_start = Clock::now();
  const exact::BoundedHausdorff h = exact::one_sided_hausdorff(hulls, mesh, bound);
  const double h_seconds = seconds_since(h_start);
  nlohmann::json volume = nullptr;
  if (stats.closedness.closed()) {
    try {
      double pieces_volume = 0;
      for (const TriangleMesh& hull : hulls) pieces_volume += exact::closed_mesh_volume(hull);
      const double original = exact::closed_mesh_volume(mesh);
      volume = {{"original", original},
                {"pieces", pieces_volume},
                {"added", pieces_volume - original},
                {"added_fraction", original > 0 ? (pieces_volume - original) / original : 0.0}};
    } catch (const std::invalid_argument&) {
      // Closed for graspcd's check (welded by exact coordinates) but not a closed triangle mesh
      // for CGAL's polygon-soup conversion: no volume rather than a wrong one.
      warnings().add("decompose_no_volume", o.mesh + ": CGAL cannot close the mesh; no volume");
    }
  }

  const std::string stem = fs::path(o.mesh).stem().string();
  decompose::DecompositionFiles files;
  try {
    files = decompose::write_decomposition_files(
        d.pieces, o.out, stem,
        "graspcd decompose: " + std::to_string(d.pieces.size()) + " convex pieces (HACD) of " +
            fs::path(o.mesh).filename().string() + ", in its own coordinates and scale");
  } catch (const std::runtime_error& e) {
    throw io::InputError(o.out, 0, e.what());
  }

  nlohmann::json pieces = nlohmann::json::array();
  for (std::size_t k = 0; k < d.pieces.size(); ++k) {
    pieces.push_back({{"file", files.pieces[k]},
                      {"vertices", d.pieces[k].hull.vertices.size()},
                      {"faces", d.pieces[k].hull.faces.size()}});
  }
  nlohmann::json doc = {
      {"source", fs::absolute(o.mesh).lexically_normal().string()},
      {"source_faces", mesh.faces.size()},
      {"closed", stats.closedness.closed()},
      {"max_pieces", o.pieces},
      {"simplify", simplify},
      {"piece_count", d.pieces.size()},
      {"slabs", d.slabs},
      {"flat_clusters", d.flat_clusters},
      {"seconds", seconds},
      {"hausdorff",
       {{"distance", h.distance}, {"error_bound", h.error_bound}, {"seconds", h_seconds}}},
      {"volume", volume},
      {"fragment", files.fragment},
      {"pieces", pieces}};
  add_envelope(doc);
  const std::string manifest = (fs::path(o.out) / kManifest).string();
  std::ofstream(manifest, std::ios::binary) << doc.dump(2) << '\n';
  if (o.json) {
    std::cout << doc.dump(2) << '\n';
    return;
  }
  std::ostringstream out;
  out << std::setprecision(4);
  out << "pieces " << d.pieces.size() << " (at most " << o.pieces << ")\n";
  if (!simplify.is_null()) {
    out << "simplify_faces " << mesh.faces.size();
    if (decimate) {
      out << " -> " << coarse.faces.size() << " (at most " << o.simplify << ") in "
          << simplify["seconds"].get<double>() << " s\n";
    } else {
      out << " (at most " << o.simplify << ": not decimated)\n";
    }
  }
  out << "seconds " << seconds << "\n";
  out << "hausdorff_m " << h.distance << " +- " << h.error_bound << "\n";
  if (!volume.is_null()) {
    out << "volume_added_m3 " << volume["added"].get<double>() << " ("
        << 100 * volume["added_fraction"].get<double>() << "% of "
        << volume["original"].get<double>() << ")\n";
  } else {
    out << "volume_added_m3 - (open mesh)\n";
  }
  out << "fragment " << (fs::path(o.out) / files.fragment).string() << "\n";
  std::cout << out.str();
}

}  // namespace

Command add_decompose_command(CLI::App& parent) {
  auto options = std::make_shared<DecomposeOptions>();
  CLI::App* app = parent.add_subcommand(
      "decompose", "Approximate convex decomposition (HACD) of a mesh, as OBJ pieces and MJCF");
  app->add_option("MESH", options->mesh, "The mesh: OBJ or binary STL")->required();
  app->add_option("--out", options->out, "The folder for the pieces and the fragment")->required();
  app->add_option("--pieces", options->pieces, "At most this many convex pieces")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  app->add_option("--simplify", options->simplify,
                  "HACD partitions a copy decimated to at most F faces (CGAL's edge collapse); "
                  "the pieces are hulls of the original vertices")
      ->type_name("F")
      ->check(integer_in_range(4, 100000000));
  app->add_option("--hausdorff-bound", options->hausdorff_bound,
                  "Error bound of the Hausdorff distance in m (default 0.001 of the bounding box "
                  "diagonal)")
      ->check(positive_number());
  app->add_flag("--json", options->json, "Print one JSON document instead of text");
  app->footer(wrap_help(
      "HACD (Mamou and Ghorbel, ICIP 2009; Debian's libHACD) clusters the mesh's faces along "
      "their adjacency, the least concave merge first, down to --pieces clusters; each piece is "
      "the convex hull of its cluster's vertices (qhull). The count obtained is reported: fewer "
      "for a mesh of fewer faces, more for a mesh of more separate components (each gives at "
      "least one piece). A flat cluster (e.g. a flat bottom) becomes a slab 0.5% of the "
      "bounding box diagonal thick, extruded against its outward normal (counted as 'slabs').\n"
      "--simplify F (4 or more) for a large mesh, where HACD takes minutes to hours (its time "
      "grows faster than the faces' count): a copy of MESH is decimated to at most F faces by "
      "CGAL 5.5's edge collapse (Lindstrom-Turk cost and placement), HACD partitions the copy, "
      "each face of MESH joins the cluster of the copy's face nearest its centroid, and each "
      "piece is the hull of its cluster's vertices of MESH, so the pieces follow MESH's surface "
      "(the Hausdorff distance is against MESH). A cluster no face of MESH joins gives no piece. "
      "A mesh of at most F faces is not decimated (reported).\n"
      "Written into DIR: STEM_piece_K.obj (K = 0, 1, ...; in MESH's own coordinates and scale), "
      "STEM.xml (an MJCF fragment MuJoCo 2.2 includes: <mujocoinclude> with the <mesh> assets, "
      "files relative to DIR, and a <body name=\"STEM\"> with one <geom> per piece) and "
      "decomposition.json (the JSON document below; graspcd grasp --decomposed DIR reads it).\n"
      "Reported: the pieces' count, HACD's time in s, the one-sided Hausdorff distance from the "
      "pieces' surfaces to MESH's surface with its error bound (CGAL 5.5's "
      "bounded_error_Hausdorff_distance; faces of a piece inside the object count too), and for "
      "a closed mesh the volume the pieces add (the sum of their volumes minus MESH's; overlaps "
      "between pieces count twice).\n"
      "Text output: lines 'pieces N (at most M)', with --simplify 'simplify_faces F0 -> F1 (at "
      "most F) in S s' or 'simplify_faces F0 (at most F: not decimated)', 'seconds S' (HACD "
      "and the hulls; with --simplify after the decimation), 'hausdorff_m D +- B', "
      "'volume_added_m3 V (P% of V0)' or '- (open mesh)', 'fragment PATH'. --json: one "
      "document: source, source_faces, closed, max_pieces, simplify (max_faces, faces_before, "
      "faces_after, decimated, seconds; null without --simplify), piece_count, slabs, "
      "flat_clusters, "
      "seconds, "
      "hausdorff (distance, error_bound, seconds), volume (original, pieces, added, "
      "added_fraction; null for an open mesh), fragment, pieces (file, vertices, faces), "
      "graspcd, warnings.\n"
      "Errors: a missing or bad mesh (docs/bad-input.md) or a folder that cannot be written is "
      "one line 'FILE: message' on stderr, exit code 2.\n"
      "Example:\n"
      "  graspcd decompose ../shared/models/objects/mujoco/cube_cup.obj --out /tmp/cup8 "
      "--pieces 8\n"
      "  graspcd decompose ../shared/models/objects/mujoco/mug.obj --out /tmp/mug16 --pieces 16 "
      "--simplify 3000"));
  return Command{app, [options] { run_decompose(*options); }};
}

}  // namespace graspcd::cli
