// graspcd decompose MESH --out DIR [--engine hacd|vhacd] [--pieces N] [--simplify F]
// [--resolution R] [--timeout S] [--hausdorff-bound B] [--describe PIECES] [--json]: an
// approximate convex decomposition with HACD (Mamou and Ghorbel, ICIP 2009) or V-HACD 4 (Mamou,
// Game Engine Gems 3, 2016; run by node from the npm package vhacd-js), or the pieces of PIECES
// (--describe), written as one OBJ per convex piece and an MJCF fragment, with how far the
// pieces' hulls lie from the original surface (CGAL's bounded-error one-sided Hausdorff
// distance) and, for a closed mesh, the volume they add. --simplify F: HACD partitions a copy
// decimated to at most F faces (CGAL's edge collapse), each original face joins the cluster of its
// nearest decimated face, and the pieces are the hulls of the original vertices.
#include <chrono>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include "command.h"
#include "graspcd/decompose/mesh_decomposition.h"
#include "graspcd/decompose/vhacd.h"
#include "object_placement.h"
#include "progress.h"

namespace graspcd::cli {

namespace {

struct DecomposeOptions {
  decompose::DecomposeOptions run;
  std::string engine = "hacd";
  bool json = false;
};

void run_decompose(DecomposeOptions& o, const CLI::App& app) {
  const bool vhacd = o.engine == "vhacd";
  o.run.engine = vhacd ? decompose::Engine::kVhacd : decompose::Engine::kHacd;
  o.run.scale_given = app.count("--scale") > 0;
  if (!o.run.describe.empty()) {
    for (const char* option : {"--engine", "--pieces", "--simplify", "--resolution", "--timeout"}) {
      if (app.count(option) > 0) {
        throw UsageError(std::string("decompose: ") + option +
                         " runs an engine; --describe takes the pieces as they are");
      }
    }
    o.run.engine = decompose::Engine::kGiven;
  }
  if (vhacd && app.count("--simplify") > 0) {
    throw UsageError("decompose: --simplify is for --engine hacd (V-HACD voxelizes the mesh)");
  }
  for (const char* option : {"--resolution", "--timeout"}) {
    if (!vhacd && app.count(option) > 0) {
      throw UsageError(std::string("decompose: ") + option + " is for --engine vhacd");
    }
  }
  const auto started = std::chrono::steady_clock::now();
  Progress progress("decompose");
  o.run.progress = [&progress, &o](const std::string& stage, double share) {
    progress.update(o.run.mesh + ": " + stage, share);
  };
  const decompose::DecomposeRun run = [&] {
    try {
      return decompose::decompose_mesh(o.run);
    } catch (const decompose::BoundError& e) {
      throw UsageError(std::string("--hausdorff-bound: ") + e.what());
    } catch (const decompose::VhacdUnavailable& e) {
      throw UsageError(std::string("decompose: the V-HACD engine needs node and the vhacd-js "
                                   "package (") +
                       e.what() + "): run ./run build");
    }
  }();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  std::ostringstream done;
  done << (o.run.engine == decompose::Engine::kGiven ? "described " : "wrote ")
       << run.manifest.piece_count << " pieces of " << o.run.mesh << " to " << o.run.out << " in "
       << std::setprecision(3) << seconds << " s";
  progress.done(done.str());
  if (o.json) {
    std::cout << run.document << '\n';
    return;
  }
  std::cout << decompose::decomposition_text(run.manifest, o.run);
}

}  // namespace

Command add_decompose_command(CLI::App& parent) {
  auto options = std::make_shared<DecomposeOptions>();
  CLI::App* app = parent.add_subcommand(
      "decompose",
      "Approximate convex decomposition (HACD or V-HACD 4) of a mesh, as OBJ pieces and MJCF");
  app->add_option("MESH", options->run.mesh,
                  "The mesh: OBJ, STL, OFF, PLY, glTF/GLB or COLLADA (docs/objects.md)")
      ->required();
  app->add_option("--scale", options->run.scale,
                  "Multiply MESH's coordinates by S (file units to metres: 0.001 for "
                  "millimetres); the pieces and every length reported are then in metres")
      ->type_name("S")
      ->check(number_in_range(kMinScale, kMaxScale));
  app->add_option("--out", options->run.out, "The folder for the pieces and the fragment")
      ->required();
  app->add_option("--describe", options->run.describe,
                  "No engine: take the convex pieces in this folder (mesh files in MESH's "
                  "coordinates and units, e.g. a model set's published decomposition) as "
                  "MESH's decomposition")
      ->type_name("PIECES");
  app->add_option("--engine", options->engine,
                  "hacd: HACD (Debian's libHACD); vhacd: V-HACD 4 (node and the npm package "
                  "vhacd-js, installed by ./run build)")
      ->check(CLI::IsMember({"hacd", "vhacd"}))
      ->capture_default_str();
  app->add_option("--pieces", options->run.pieces,
                  "At most this many convex pieces (HACD's clusters, V-HACD's hulls)")
      ->transform(integer_in_range(1, 1024))
      ->capture_default_str();
  app->add_option("--simplify", options->run.simplify,
                  "HACD partitions a copy decimated to at most F faces (CGAL's edge collapse); "
                  "the pieces are hulls of the original vertices")
      ->type_name("F")
      ->transform(integer_in_range(4, 100000000));
  app->add_option("--resolution", options->run.resolution,
                  "V-HACD: voxels in the mesh's bounding box (finer: closer pieces, slower)")
      ->type_name("R")
      ->transform(integer_in_range(10000, 64000000))
      ->capture_default_str();
  app->add_option("--timeout", options->run.timeout,
                  "V-HACD: node is stopped after this many seconds (the mesh is then refused)")
      ->type_name("S")
      ->check(positive_number())
      ->capture_default_str();
  app->add_option("--hausdorff-bound", options->run.hausdorff_bound,
                  "Error bound of the Hausdorff distance in m (default 0.001 of the bounding box "
                  "diagonal; from 1e-6 of it up to the diagonal itself)")
      ->check(positive_number());
  app->add_flag("--json", options->json, "Print one JSON document instead of text");
  app->footer(wrap_help(
      "Two engines (--engine). hacd (the default): HACD (Mamou and Ghorbel, ICIP 2009; Debian's "
      "libHACD) clusters the mesh's faces along "
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
      "vhacd: V-HACD 4 (Mamou, Game Engine Gems 3, 2016; the npm package vhacd-js, "
      "WebAssembly, run by node from tools/vhacd/vhacd.mjs of graspcd's source tree, or the "
      "script GRASPCD_VHACD_SCRIPT names; ./run build installs the package there with npm ci) "
      "voxelizes the closed mesh (--resolution voxels in its bounding box, V-HACD's default "
      "400000), splits the voxels recursively where the hull of a part exceeds its volume by "
      "more than 1% (at most 10 levels), merges the parts down to --pieces hulls and "
      "shrink-wraps each hull (at most 64 vertices) onto the mesh; graspcd rebuilds every hull "
      "with qhull and leaves out one without volume. Meant for closed meshes: an open one is "
      "filled where its voxels enclose a volume. Where node or vhacd-js is missing, --engine "
      "vhacd is one line and exit code 2 (nothing else needs them). --simplify is for hacd; "
      "--resolution and --timeout for vhacd. Choose vhacd for a large or scanned mesh (its "
      "time grows with the voxels, not the faces; no --simplify needed) and for hulls close to "
      "the solid; hacd needs no node and follows the mesh's own faces.\n"
      "--describe PIECES: no engine. The convex pieces someone else made (e.g. the contactK.stl "
      "beside each YCB object of ../shared/models, in the object's coordinates and metres) are "
      "read from the folder PIECES (every mesh file, in the order of their names with numbers "
      "by value), each rebuilt as its convex hull (qhull: what MuJoCo collides), scaled by "
      "--scale as MESH is, and written, measured and described as a decomposition of MESH "
      "(engine 'given'), so that graspcd grasp --decomposed DIR runs on them. Pieces whose "
      "bounding box is not MESH's (its diagonal off by more than a factor 1.5, or its centre "
      "more than a quarter of the diagonal away) are refused: they are in other units or "
      "another frame.\n"
      "Written into DIR: STEM_piece_K.obj (K = 0, 1, ...; in MESH's own coordinates, times "
      "--scale when given), "
      "STEM.xml (an MJCF fragment MuJoCo 2.2 includes: <mujocoinclude> with the <mesh> assets, "
      "files relative to DIR, and a <body name=\"STEM\"> with one <geom> per piece) and "
      "decomposition.json (the JSON document below; graspcd grasp --decomposed DIR reads it). "
      "It records the scale: the pieces are MESH's coordinates times --scale (1 without it), "
      "and grasp --decomposed gives each piece the scale of the scene's <mesh> divided by it, "
      "so that a scale is never applied twice.\n"
      "Reported: the pieces' count, the engine's time in s (for vhacd with node's start), the "
      "one-sided Hausdorff distance from the "
      "pieces' surfaces to MESH's surface with its error bound (CGAL 5.5's "
      "bounded_error_Hausdorff_distance; faces of a piece inside the object count too), and for "
      "a closed mesh the volume the pieces add (the sum of their volumes minus MESH's; overlaps "
      "between pieces count twice); a loss of more than 10% of MESH's volume (pieces that do not "
      "fill "
      "it, e.g. thin slabs along its faces) is the warning 'decompose_volume_lost', a gain (pieces "
      "closing a cavity) is reported only.\n"
      "Text output: lines 'engine E', 'pieces N (at most M)', with --simplify 'simplify_faces F0 "
      "-> F1 (at "
      "most F) in S s' or 'simplify_faces F0 (at most F: not decimated)', 'seconds S' (the engine "
      "and the hulls; with --simplify after the decimation), 'hausdorff_m D +- B', "
      "'volume_added_m3 V (P% of V0)' or '- (open mesh)', 'fragment PATH'. --json: one "
      "document: source, engine (hacd, vhacd or given), scale, units (m: the pieces are in "
      "metres, --scale was given or MESH is glTF or COLLADA; source: in MESH's own units), "
      "pieces_from (given: the folder PIECES), engine_parameters (hacd: max_clusters; vhacd: "
      "max_hulls, voxel_resolution, max_vertices_per_hull, min_volume_percent_error, "
      "max_recursion_depth), source_faces, closed, max_pieces, simplify (max_faces, faces_before, "
      "faces_after, decimated, seconds; null without --simplify), piece_count, slabs, "
      "flat_clusters, "
      "seconds, "
      "hausdorff (distance, error_bound, seconds), volume (original, pieces, added, "
      "added_fraction; null for an open mesh), fragment, pieces (file, vertices, faces), "
      "graspcd, warnings.\n"
      "DIR is written whole or not at all: the files go to a hidden folder beside it "
      "(.NAME.graspcd-XXXXXX), renamed to DIR at the end and removed on an error or on INT, "
      "TERM and HUP (exit code 128 + the signal). A DIR that holds an earlier decomposition "
      "(decomposition.json) or nothing is replaced whole (no stale piece stays); a DIR that "
      "holds other files is refused before the work.\n"
      "Progress on stderr: the stage (reading, HACD's merges with their share done and an "
      "estimate of the time left, V-HACD, CGAL's Hausdorff distance, the volumes) and the time "
      "so far, on a terminal one line rewritten as the work goes, otherwise one line every 5 s "
      "(GRASPCD_PROGRESS_SECONDS); then one final line '[decompose] wrote N pieces of MESH to DIR "
      "in S s'.\n"
      "Errors: a missing or bad mesh (docs/bad-input.md), a DIR that is a file, lies under a file, "
      "cannot be written or holds other files is one line 'FILE: message' on stderr, exit code "
      "2.\n"
      "Example:\n"
      "  graspcd decompose ../shared/models/objects/mujoco/cube_cup.obj --out /tmp/cup8 "
      "--pieces 8\n"
      "  graspcd decompose ../shared/models/objects/mujoco/mug.obj --out /tmp/mug16 --pieces 16 "
      "--simplify 3000\n"
      "  graspcd decompose ../shared/models/objects/mujoco/mug.obj --out /tmp/mug32v --pieces 32 "
      "--engine vhacd\n"
      "  graspcd decompose ../shared/models/objects/ycb/005_tomato_soup_can/textured.obj "
      "--describe ../shared/models/objects/ycb/005_tomato_soup_can/pieces --out /tmp/can"));
  return Command{app, [options, app] { run_decompose(*options, *app); }};
}

}  // namespace graspcd::cli
