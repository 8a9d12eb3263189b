#include "graspcd/decompose/mesh_decomposition.h"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iomanip>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "graspcd/core/clock.h"
#include "graspcd/core/geometry.h"
#include "graspcd/decompose/decomposition_files.h"
#include "graspcd/decompose/hacd.h"
#include "graspcd/decompose/vhacd.h"
#include "graspcd/exact/hausdorff.h"
#include "graspcd/exact/simplify.h"
#include "graspcd/exact/surface_distance.h"
#include "graspcd/io/mesh_io.h"
#include "graspcd/io/output_files.h"
#include "graspcd/io/text_input.h"
#include "graspcd/io/warnings.h"

namespace graspcd::decompose {

namespace {

namespace fs = std::filesystem;

// A --scale as a header line prints it (6 significant digits).
std::string scale_text(double scale) {
  std::ostringstream out;
  out << std::setprecision(6) << scale;
  return out.str();
}

// The options' progress callback, when set.
void report(const DecomposeOptions& o, const std::string& stage, double share = -1) {
  if (o.progress) o.progress(stage, share);
}

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
Partition transfer_partition(const Partition& coarse_partition, const TriangleMesh& coarse,
                             const TriangleMesh& mesh) {
  const exact::SurfaceDistance nearest(coarse);
  Partition out;
  out.clusters = coarse_partition.clusters;
  out.cluster_of_face.reserve(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Triangle t = mesh.triangle(f);
    const Vec3 centroid = (t.v[0] + t.v[1] + t.v[2]) / 3.0;
    out.cluster_of_face.push_back(coarse_partition.cluster_of_face[nearest.nearest_face(centroid)]);
  }
  return out;
}

// --simplify F: the copy HACD partitions, decimated by CGAL's edge collapse when the mesh has more
// than F faces, timed alone. `coarse` gets the copy when it was decimated.
std::optional<Manifest::Simplify> simplify_copy(const DecomposeOptions& o, const TriangleMesh& mesh,
                                                TriangleMesh& coarse) {
  if (o.simplify <= 0) return std::nullopt;
  const bool decimate = mesh.faces.size() > static_cast<std::size_t>(o.simplify);
  const Clock::time_point start = Clock::now();
  if (decimate) {
    report(o, "CGAL: decimating " + std::to_string(mesh.faces.size()) + " faces to at most " +
                  std::to_string(o.simplify));
    try {
      coarse = exact::simplify_edge_collapse(mesh, static_cast<std::size_t>(o.simplify));
    } catch (const std::invalid_argument& e) {
      throw io::InputError(o.mesh, 0, e.what());
    }
  }
  Manifest::Simplify s;
  s.max_faces = o.simplify;
  s.faces_before = mesh.faces.size();
  s.faces_after = decimate ? coarse.faces.size() : mesh.faces.size();
  s.decimated = decimate;
  s.seconds = seconds_since(start);
  return s;
}

VhacdOptions vhacd_options(const DecomposeOptions& o) {
  VhacdOptions v;
  v.max_hulls = static_cast<std::size_t>(o.pieces);
  v.voxel_resolution = static_cast<std::size_t>(o.resolution);
  v.timeout_seconds = o.timeout;
  v.script = o.vhacd_script;
  return v;
}

// The engine's settings as the manifest records them.
std::vector<std::pair<std::string, double>> engine_parameters(const DecomposeOptions& o) {
  if (o.engine == Engine::kVhacd) {
    const VhacdOptions v = vhacd_options(o);
    return {{"max_hulls", static_cast<double>(v.max_hulls)},
            {"voxel_resolution", static_cast<double>(v.voxel_resolution)},
            {"max_vertices_per_hull", static_cast<double>(v.max_vertices_per_hull)},
            {"min_volume_percent_error", 1.0},
            {"max_recursion_depth", 10.0}};
  }
  return {{"max_clusters", static_cast<double>(o.pieces)}};
}

// The engine (HACD or V-HACD), timed with the pieces' hulls (and with --simplify, the transfer of
// the decimated copy's partition to the mesh's faces).
Decomposition run_engine(const DecomposeOptions& o, const TriangleMesh& mesh, bool decimated,
                         const TriangleMesh& coarse, double& seconds) {
  HacdOptions hacd;
  hacd.max_pieces = static_cast<std::size_t>(o.pieces);
  const std::string merging = "HACD: merging the faces' clusters down to " +
                              std::to_string(o.pieces) + " (the share merged)";
  if (o.progress) hacd.progress = [&o, &merging](double share) { report(o, merging, share); };
  const Clock::time_point start = Clock::now();
  Decomposition d;
  try {
    if (o.engine == Engine::kVhacd) {
      report(o, "V-HACD in node: voxels, splits and hulls (no progress from it; stopped after " +
                    scale_text(o.timeout) + " s)");
      d = vhacd_decompose(mesh, vhacd_options(o));
    } else if (decimated) {
      report(o, "HACD: the cost of every merge of the decimated copy's faces");
      const Partition partition = transfer_partition(hacd_partition(coarse, hacd), coarse, mesh);
      d = pieces_of_partition(mesh, partition);
    } else {
      report(o, "HACD: the cost of every merge of " + std::to_string(mesh.faces.size()) + " faces");
      d = hacd_decompose(mesh, hacd);
    }
  } catch (const VhacdUnavailable&) {
    throw;
  } catch (const io::InputError&) {
    throw;  // (the temporary folder) names its own file
  } catch (const std::runtime_error& e) {
    throw io::InputError(o.mesh, 0, e.what());
  }
  seconds = seconds_since(start);
  if (d.flat_clusters > 0) {
    warnings().add("decompose_flat_pieces",
                   o.mesh + ": " + std::to_string(d.flat_clusters) +
                       (o.engine == Engine::kVhacd
                            ? " of V-HACD's hulls have no volume and were left out"
                            : " of HACD's clusters have no hull even as a slab and were left out"));
  }
  return d;
}

// Whether `a` comes before `b` with runs of digits compared by value ("contact2" before
// "contact10").
bool natural_less(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (std::isdigit(static_cast<unsigned char>(a[i])) &&
        std::isdigit(static_cast<unsigned char>(b[j]))) {
      std::size_t i2 = i, j2 = j;
      while (i2 < a.size() && std::isdigit(static_cast<unsigned char>(a[i2]))) ++i2;
      while (j2 < b.size() && std::isdigit(static_cast<unsigned char>(b[j2]))) ++j2;
      const std::string x = a.substr(i, i2 - i), y = b.substr(j, j2 - j);
      const std::size_t zx = x.find_first_not_of('0'), zy = y.find_first_not_of('0');
      const std::string vx = zx == std::string::npos ? "" : x.substr(zx);
      const std::string vy = zy == std::string::npos ? "" : y.substr(zy);
      if (vx.size() != vy.size()) return vx.size() < vy.size();
      if (vx != vy) return vx < vy;
      i = i2;
      j = j2;
    } else {
      if (a[i] != b[j]) return a[i] < b[j];
      ++i;
      ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

// The mesh files of the folder of given pieces (Engine::kGiven), by natural_less of their names.
std::vector<fs::path> given_piece_files(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw io::InputError(dir, 0, "not a folder of pieces");
  std::vector<fs::path> files;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    std::string ext = e.path().extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const bool mesh = ext == ".obj" || ext == ".stl" || ext == ".off" || ext == ".ply" ||
                      ext == ".gltf" || ext == ".glb" || ext == ".dae";
    if (mesh && e.is_regular_file(ec)) files.push_back(e.path());
  }
  if (ec) throw io::InputError(dir, 0, "cannot read the folder: " + ec.message());
  if (files.empty()) {
    throw io::InputError(dir, 0,
                         "no mesh file in the folder (.obj, .stl, .off, .ply, .gltf, .glb, .dae)");
  }
  std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
    return natural_less(a.filename().string(), b.filename().string());
  });
  return files;
}

// Engine::kGiven: each piece of `o.describe` read, scaled as the mesh and rebuilt as its convex
// hull (qhull), refused when it has no volume; the pieces together refused when they do not lie
// where `mesh` (already scaled) lies.
Decomposition given_pieces(const DecomposeOptions& o, const TriangleMesh& mesh, double& seconds) {
  const Clock::time_point start = Clock::now();
  const std::vector<fs::path> files = given_piece_files(o.describe);
  Decomposition d;
  Box box;
  for (std::size_t k = 0; k < files.size(); ++k) {
    report(o, "reading the pieces of " + o.describe,
           static_cast<double>(k) / static_cast<double>(files.size()));
    const std::string file = files[k].string();
    TriangleMesh piece = io::load_mesh(file);
    io::scale_mesh(file, o.scale, &piece);
    ConvexPiece p{convex_hull(piece.vertices)};
    if (p.hull.faces.empty()) {
      throw io::InputError(file, 0, "a piece without volume (its points are flat or fewer than 4)");
    }
    const Box b = bounding_box(p.hull);
    box = k == 0 ? b : Box{box.lo.cwiseMin(b.lo), box.hi.cwiseMax(b.hi)};
    d.pieces.push_back(std::move(p));
  }
  const std::string mismatch = placement_mismatch(bounding_box(mesh), 1, box);
  if (!mismatch.empty()) {
    throw io::InputError(o.describe, 0,
                         "not pieces of " + o.mesh + " at --scale " + scale_text(o.scale) + ": " +
                             mismatch +
                             " (the pieces must be in the mesh's coordinates and units)");
  }
  seconds = seconds_since(start);
  return d;
}

// The volume the pieces add to a closed mesh (overlaps between pieces count twice).
std::optional<Manifest::Volume> added_volume(const std::vector<TriangleMesh>& hulls,
                                             const TriangleMesh& mesh, const std::string& name) {
  try {
    double pieces_volume = 0;
    for (const TriangleMesh& hull : hulls) pieces_volume += exact::closed_mesh_volume(hull);
    const double original = exact::closed_mesh_volume(mesh);
    Manifest::Volume v;
    v.original = original;
    v.pieces = pieces_volume;
    v.added = pieces_volume - original;
    v.added_fraction = original > 0 ? (pieces_volume - original) / original : 0.0;
    return v;
  } catch (const std::invalid_argument&) {
    // Closed for graspcd's check (welded by exact coordinates) but not a closed triangle mesh
    // for CGAL's polygon-soup conversion: no volume rather than a wrong one.
    warnings().add("decompose_no_volume", name + ": CGAL cannot close the mesh; no volume");
    return std::nullopt;
  }
}

// The output folder, written whole or not at all: the pieces go to a private folder beside it
// (.NAME.graspcd-XXXXXX, removed on errors and on INT, TERM and HUP), renamed to it at the end. A
// folder that holds nothing, or only the files of an earlier decomposition (decomposition.json
// and the fragment and pieces it lists), is replaced whole, so no stale piece stays; one that
// holds the mesh the run reads or any other file, or that is read-only, is refused before the
// work.
struct OutputFolder {
  fs::path target;
  std::optional<fs::perms> mode;  // the replaced folder's
  std::optional<io::RemoveIfEmpty> created_parent;
  io::CleanupGuard work;
};

// Whether `inner` lies under the folder `outer` (both existing; links resolved).
bool lies_under(const fs::path& inner, const fs::path& outer) {
  std::error_code ec;
  const fs::path a = fs::canonical(inner, ec);
  if (ec) return false;
  const fs::path b = fs::canonical(outer, ec);
  if (ec) return false;
  const auto [o, i] = std::mismatch(b.begin(), b.end(), a.begin(), a.end());
  return o == b.end() && i != a.end();
}

// An existing --out: refused unless graspcd decompose wrote everything in it (nothing, or an
// earlier decomposition's files as its manifest lists them) and it can be written into.
void check_existing_out(const DecomposeOptions& o, const fs::path& target) {
  std::error_code ec;
  if (!fs::is_directory(target, ec)) throw io::InputError(o.out, 0, "not a folder");
  const std::string keep = ": not replaced; give a new or empty folder";
  if (lies_under(o.mesh, target)) {
    throw io::InputError(
        o.out, 0,
        "holds the mesh this run reads (" +
            fs::relative(fs::canonical(o.mesh, ec), fs::canonical(target, ec)).string() + ")" +
            keep);
  }
  if (fs::is_empty(target, ec)) {
    io::writable_folder(o.out);
    return;
  }
  if (!fs::exists(fs::symlink_status(target / kManifestFile, ec))) {
    throw io::InputError(o.out, 0,
                         "holds files graspcd decompose did not write (no decomposition.json): "
                         "give a new or empty folder");
  }
  Manifest earlier;
  try {
    earlier = read_manifest(target.string());
  } catch (const io::InputError& e) {
    throw io::InputError(
        o.out, 0,
        "holds a decomposition.json graspcd decompose did not write (" + e.message() + ")" + keep);
  }
  std::set<std::string> written = {kManifestFile, earlier.fragment};
  for (const Manifest::Piece& p : earlier.pieces) written.insert(p.file);
  for (const fs::directory_entry& e : fs::directory_iterator(target, ec)) {
    const std::string name = e.path().filename().string();
    if (io::same_file(e.path(), o.mesh)) {
      throw io::InputError(o.out, 0, "holds the mesh this run reads (" + name + ")" + keep);
    }
    if (written.count(name) == 0) {
      throw io::InputError(o.out, 0,
                           "holds " + name + ", which graspcd decompose did not write (" +
                               kManifestFile + " does not list it)" + keep);
    }
  }
  if (ec) throw io::InputError(o.out, 0, "cannot read the folder: " + ec.message());
  io::writable_folder(o.out);
}

void prepare_out(const DecomposeOptions& o, OutputFolder& f) {
  const std::string& out = o.out;
  f.target = fs::absolute(out).lexically_normal();
  if (f.target.filename().empty()) f.target = f.target.parent_path();
  std::error_code ec;
  if (fs::exists(f.target, ec)) {
    check_existing_out(o, f.target);
    f.mode = fs::status(f.target, ec).permissions();
  }
  const fs::path parent = f.target.parent_path();
  if (io::prepare_output_folder(parent.string())) f.created_parent.emplace(parent);
  f.work = io::make_private_folder(parent, "." + f.target.filename().string() + ".graspcd", out);
}

// The written folder renamed to `out` (an earlier one moved aside and removed); it gets the mode
// of the folder it replaces, or a new folder's (0777 less the umask) rather than the private
// folder's 0700.
void commit_out(OutputFolder& f, const std::string& out) {
  std::error_code ec;
  const mode_t mask = ::umask(0);
  ::umask(mask);
  fs::permissions(f.work.path(), f.mode.value_or(static_cast<fs::perms>(0777 & ~mask)), ec);
  if (fs::exists(f.target, ec)) {
    const io::CleanupGuard old = io::make_private_folder(
        f.target.parent_path(), "." + f.target.filename().string() + ".graspcd-old", out);
    fs::rename(f.target, old.path(), ec);
    if (ec) throw io::InputError(out, 0, "cannot replace the folder: " + ec.message());
    fs::rename(f.work.path(), f.target, ec);
    if (ec) throw io::InputError(out, 0, "cannot write the folder: " + ec.message());
  } else {
    fs::rename(f.work.path(), f.target, ec);
    if (ec) throw io::InputError(out, 0, "cannot write the folder: " + ec.message());
  }
  f.work.release();
}

// The decomposition written into `work`, named `o.out` in messages.
DecomposeRun decompose_into(const DecomposeOptions& o, const std::string& work) {
  if (o.engine == Engine::kVhacd) {
    if (o.simplify > 0) throw std::invalid_argument("simplify is for the HACD engine");
    if (const std::string missing = vhacd_missing(vhacd_options(o)); !missing.empty()) {
      throw VhacdUnavailable(missing);
    }
  }
  // The mesh as graspcd reads it: a bad file is one line naming it.
  io::MeshStats stats;
  report(o, "reading " + o.mesh);
  const TriangleMesh mesh = [&] {
    TriangleMesh loaded = io::load_mesh(o.mesh, &stats);
    io::scale_mesh(o.mesh, o.scale, &loaded);
    return loaded;
  }();
  const double finest = kMinBoundFraction * bounding_diagonal(mesh);
  // (The slack accepts the finest bound as the message prints it, to 6 digits.)
  if (o.hausdorff_bound > 0 && !(o.hausdorff_bound >= finest * (1 - 1e-5))) {
    std::ostringstream out;
    out << "the bound " << o.hausdorff_bound << " m is finer than the distance can be refined to: "
        << "at least " << kMinBoundFraction << " of " << o.mesh << "'s bounding box diagonal ("
        << finest << " m)";
    throw BoundError(out.str());
  }
  const double coarsest = kMaxBoundFraction * bounding_diagonal(mesh);
  if (o.hausdorff_bound > coarsest) {
    std::ostringstream out;
    out << "the bound " << o.hausdorff_bound << " m is coarser than " << o.mesh
        << "'s bounding box diagonal (" << coarsest
        << " m): a distance known only to within the mesh's size says nothing";
    throw BoundError(out.str());
  }
  for (const std::string& w : io::mesh_warnings(o.mesh, stats, true)) {
    warnings().add("mesh_hygiene", w);
  }
  std::error_code ec;
  fs::create_directories(work, ec);
  if (ec || !fs::is_directory(work)) {
    throw io::InputError(o.out, 0, "cannot create the output folder: " + ec.message());
  }

  Manifest m;
  TriangleMesh coarse;
  m.simplify = simplify_copy(o, mesh, coarse);
  const Decomposition d =
      o.engine == Engine::kGiven
          ? given_pieces(o, mesh, m.seconds)
          : run_engine(o, mesh, m.simplify && m.simplify->decimated, coarse, m.seconds);

  // How far the pieces' hulls lie from the original surface, and the volume they add.
  std::vector<TriangleMesh> hulls;
  for (const ConvexPiece& p : d.pieces) hulls.push_back(p.hull);
  const double bound =
      o.hausdorff_bound > 0 ? o.hausdorff_bound : kDefaultBoundFraction * bounding_diagonal(mesh);
  const Clock::time_point h_start = Clock::now();
  report(o, "the Hausdorff distance from the pieces to the mesh (CGAL; no progress from it)");
  const exact::BoundedHausdorff h = exact::one_sided_hausdorff(hulls, mesh, bound);
  m.hausdorff = {h.distance, h.error_bound, seconds_since(h_start)};
  const double diagonal = bounding_diagonal(mesh);
  if (h.distance - h.error_bound > kFarPiecesDiagonals * diagonal) {
    std::ostringstream w;
    w << std::setprecision(4) << o.mesh << ": "
      << (o.engine == Engine::kVhacd   ? "V-HACD's pieces"
          : o.engine == Engine::kGiven ? "the given pieces"
                                       : "HACD's pieces")
      << " lie up to " << h.distance << " m from the mesh, farther than " << kFarPiecesDiagonals
      << " x its bounding box diagonal (" << diagonal
      << " m), which no piece of it can: the engine's answer does not fit the mesh";
    warnings().add("decompose_far_pieces", w.str());
  }
  if (stats.closedness.closed()) {
    report(o, "the volumes (CGAL)");
    m.volume = added_volume(hulls, mesh, o.mesh);
  }
  if (m.volume && m.volume->added_fraction < -kMaxVolumeLoss) {
    std::ostringstream w;
    w << std::setprecision(3) << o.mesh << ": the pieces hold " << -100 * m.volume->added_fraction
      << "% less volume than the mesh (" << m.volume->pieces << " of " << m.volume->original
      << " m^3; more than " << 100 * kMaxVolumeLoss
      << "% lost): they do not fill it; try fewer --pieces";
    warnings().add("decompose_volume_lost", w.str());
  }

  const std::string stem = fs::path(o.mesh).stem().string();
  DecompositionFiles files;
  try {
    files = write_decomposition_files(
        d.pieces, work, stem,
        "graspcd decompose: " + std::to_string(d.pieces.size()) + " convex pieces (" +
            (o.engine == Engine::kVhacd   ? "V-HACD"
             : o.engine == Engine::kGiven ? "given in " + o.describe
                                          : "HACD") +
            ") of " + fs::path(o.mesh).filename().string() +
            (o.scale == 1 ? std::string(", in its own coordinates and scale")
                          : ", in its own coordinates times the scale " + scale_text(o.scale)),
        o.out);
  } catch (const std::runtime_error& e) {
    throw io::InputError(o.out, 0, e.what());
  }

  m.source = fs::absolute(o.mesh).lexically_normal().string();
  m.engine = engine_name(o.engine);
  m.scale = o.scale;
  m.units = o.scale_given || stats.in_metres ? "m" : "source";
  if (o.engine == Engine::kGiven) {
    m.pieces_from = fs::absolute(o.describe).lexically_normal().string();
  } else {
    m.engine_parameters = engine_parameters(o);
  }
  m.source_faces = mesh.faces.size();
  m.closed = stats.closedness.closed();
  m.max_pieces = o.engine == Engine::kGiven ? static_cast<int>(d.pieces.size()) : o.pieces;
  m.piece_count = d.pieces.size();
  m.slabs = d.slabs;
  m.flat_clusters = d.flat_clusters;
  m.fragment = files.fragment;
  for (std::size_t k = 0; k < d.pieces.size(); ++k) {
    m.pieces.push_back(
        {files.pieces[k], d.pieces[k].hull.vertices.size(), d.pieces[k].hull.faces.size()});
  }
  std::string document = write_manifest(work, m);
  return DecomposeRun{std::move(m), std::move(document)};
}

}  // namespace

const char* engine_name(Engine engine) {
  return engine == Engine::kVhacd ? "vhacd" : engine == Engine::kGiven ? "given" : "hacd";
}

std::string decomposition_text(const Manifest& m, const DecomposeOptions& o) {
  std::ostringstream out;
  out << std::setprecision(4);
  out << "engine " << m.engine << (m.pieces_from.empty() ? "" : " (" + m.pieces_from + ")") << "\n";
  out << "scale " << m.scale << " (" << (m.units == "m" ? "metres" : "the mesh's own units")
      << ")\n";
  if (m.engine == engine_name(Engine::kGiven)) {
    out << "pieces " << m.piece_count << "\n";
  } else {
    out << "pieces " << m.piece_count << " (at most " << o.pieces << ")\n";
  }
  if (m.simplify) {
    out << "simplify_faces " << m.simplify->faces_before;
    if (m.simplify->decimated) {
      out << " -> " << m.simplify->faces_after << " (at most " << o.simplify << ") in "
          << m.simplify->seconds << " s\n";
    } else {
      out << " (at most " << o.simplify << ": not decimated)\n";
    }
  }
  out << "seconds " << m.seconds << "\n";
  out << "hausdorff_m " << m.hausdorff.distance << " +- " << m.hausdorff.error_bound << "\n";
  if (m.volume) {
    out << "volume_added_m3 " << m.volume->added << " (" << 100 * m.volume->added_fraction
        << "% of " << m.volume->original << ")\n";
  } else {
    out << "volume_added_m3 - (open mesh)\n";
  }
  out << "fragment " << (std::filesystem::path(o.out) / m.fragment).string() << "\n";
  return out.str();
}

DecomposeRun decompose_mesh(const DecomposeOptions& o) {
  OutputFolder folder;
  prepare_out(o, folder);
  DecomposeRun run = decompose_into(o, folder.work.path().string());
  commit_out(folder, o.out);
  return run;
}

}  // namespace graspcd::decompose
