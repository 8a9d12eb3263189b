#include "graspcd/decompose/manifest.h"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <utility>

#include "graspcd/io/mesh_io.h"
#include "graspcd/io/text_input.h"
#include "graspcd/version/envelope.h"

namespace graspcd::decompose {

namespace {

namespace fs = std::filesystem;

nlohmann::json to_json(const Manifest& m) {
  nlohmann::json simplify = nullptr;
  if (m.simplify) {
    simplify = {{"max_faces", m.simplify->max_faces},
                {"faces_before", m.simplify->faces_before},
                {"faces_after", m.simplify->faces_after},
                {"decimated", m.simplify->decimated},
                {"seconds", m.simplify->seconds}};
  }
  nlohmann::json volume = nullptr;
  if (m.volume) {
    volume = {{"original", m.volume->original},
              {"pieces", m.volume->pieces},
              {"added", m.volume->added},
              {"added_fraction", m.volume->added_fraction}};
  }
  nlohmann::json pieces = nlohmann::json::array();
  for (const Manifest::Piece& p : m.pieces) {
    pieces.push_back({{"file", p.file}, {"vertices", p.vertices}, {"faces", p.faces}});
  }
  nlohmann::json parameters = nlohmann::json::object();
  for (const auto& [name, value] : m.engine_parameters) {
    if (std::floor(value) == value && std::fabs(value) < 9e15) {
      parameters[name] = static_cast<std::int64_t>(value);
    } else {
      parameters[name] = value;
    }
  }
  nlohmann::json doc = {{"source", m.source},
                        {"engine", m.engine},
                        {"scale", m.scale},
                        {"units", m.units},
                        {"engine_parameters", parameters},
                        {"source_faces", m.source_faces},
                        {"closed", m.closed},
                        {"max_pieces", m.max_pieces},
                        {"simplify", simplify},
                        {"piece_count", m.piece_count},
                        {"slabs", m.slabs},
                        {"flat_clusters", m.flat_clusters},
                        {"seconds", m.seconds},
                        {"hausdorff",
                         {{"distance", m.hausdorff.distance},
                          {"error_bound", m.hausdorff.error_bound},
                          {"seconds", m.hausdorff.seconds}}},
                        {"volume", volume},
                        {"fragment", m.fragment},
                        {"pieces", pieces}};
  if (!m.pieces_from.empty()) doc["pieces_from"] = m.pieces_from;
  return doc;
}

// A field of a manifest that is read when present: `fallback` when it is missing or of another
// type.
template <class T>
T field(const nlohmann::json& j, const char* key, T fallback) {
  const auto it = j.find(key);
  if (it == j.end()) return fallback;
  try {
    return it->template get<T>();
  } catch (const nlohmann::json::exception&) {
    return fallback;
  }
}

// The manifest's fields; "source" and every piece's "file" are required (a missing one, or one
// that is not a string, throws nlohmann's exception).
Manifest from_json(const nlohmann::json& doc) {
  Manifest m;
  m.source = doc.at("source").get<std::string>();
  for (const auto& p : doc.at("pieces")) {
    Manifest::Piece piece;
    piece.file = p.at("file").get<std::string>();
    piece.vertices = field(p, "vertices", std::size_t{0});
    piece.faces = field(p, "faces", std::size_t{0});
    m.pieces.push_back(std::move(piece));
  }
  m.engine = field(doc, "engine", std::string("hacd"));
  if (const auto it = doc.find("scale"); it != doc.end()) {
    m.scale = it->is_number() ? it->get<double>() : 0.0;
  } else {
    m.scale_recorded = false;
  }
  m.units = field(doc, "units", std::string("source"));
  m.pieces_from = field(doc, "pieces_from", std::string());
  if (const auto it = doc.find("engine_parameters"); it != doc.end() && it->is_object()) {
    for (const auto& [name, value] : it->items()) {
      if (value.is_number()) m.engine_parameters.emplace_back(name, value.get<double>());
    }
  }
  m.source_faces = field(doc, "source_faces", std::size_t{0});
  m.closed = field(doc, "closed", false);
  m.max_pieces = field(doc, "max_pieces", 0);
  const auto object = [&](const char* key) -> const nlohmann::json* {
    const auto it = doc.find(key);
    return it != doc.end() && it->is_object() ? &*it : nullptr;
  };
  if (const nlohmann::json* s = object("simplify")) {
    m.simplify =
        Manifest::Simplify{field(*s, "max_faces", 0), field(*s, "faces_before", std::size_t{0}),
                           field(*s, "faces_after", std::size_t{0}), field(*s, "decimated", false),
                           field(*s, "seconds", 0.0)};
  }
  m.piece_count = field(doc, "piece_count", m.pieces.size());
  m.slabs = field(doc, "slabs", std::size_t{0});
  m.flat_clusters = field(doc, "flat_clusters", std::size_t{0});
  m.seconds = field(doc, "seconds", 0.0);
  if (const nlohmann::json* h = object("hausdorff")) {
    m.hausdorff = {field(*h, "distance", 0.0), field(*h, "error_bound", 0.0),
                   field(*h, "seconds", 0.0)};
  }
  if (const nlohmann::json* v = object("volume")) {
    m.volume = Manifest::Volume{field(*v, "original", 0.0), field(*v, "pieces", 0.0),
                                field(*v, "added", 0.0), field(*v, "added_fraction", 0.0)};
  }
  m.fragment = field(doc, "fragment", std::string());
  return m;
}

}  // namespace

std::string write_manifest(const std::string& dir, const Manifest& manifest) {
  nlohmann::json doc = to_json(manifest);
  add_envelope(doc);
  std::string document = doc.dump(2);
  std::ofstream((fs::path(dir) / kManifestFile).string(), std::ios::binary) << document << '\n';
  return document;
}

Manifest read_manifest(const std::string& dir) {
  const fs::path path = fs::path(dir) / kManifestFile;
  io::require_regular_file(path.string());  // a FIFO is refused, never opened
  std::ifstream in(path);
  if (!in) {
    throw io::InputError(dir, 0,
                         std::string("no ") + kManifestFile + " (made by graspcd decompose)");
  }
  Manifest m;
  try {
    m = from_json(nlohmann::json::parse(in));
  } catch (const nlohmann::json::exception& e) {
    throw io::InputError(path.string(), 0, std::string("not a decomposition: ") + e.what());
  }
  if (m.pieces.empty()) throw io::InputError(path.string(), 0, "a decomposition without pieces");
  if (!(std::isfinite(m.scale) && m.scale > 0)) {
    throw io::InputError(path.string(), 0,
                         "\"scale\" must be a number > 0 (the pieces' coordinates are the "
                         "source's times it)");
  }
  return m;
}

Box bounding_box(const TriangleMesh& mesh) {
  Box b{mesh.vertices.front(), mesh.vertices.front()};
  for (const Vec3& v : mesh.vertices) {
    b.lo = b.lo.cwiseMin(v);
    b.hi = b.hi.cwiseMax(v);
  }
  return b;
}

Box pieces_box(const std::string& dir, const Manifest& manifest) {
  std::optional<Box> out;
  for (const Manifest::Piece& p : manifest.pieces) {
    const std::string file = (fs::path(dir) / p.file).lexically_normal().string();
    const TriangleMesh piece = io::load_mesh(file);
    const Box b = bounding_box(piece);
    if (!out) {
      out = b;
    } else {
      out->lo = out->lo.cwiseMin(b.lo);
      out->hi = out->hi.cwiseMax(b.hi);
    }
  }
  return out.value_or(Box{});
}

std::string placement_mismatch(const Box& source, double scale, const Box& pieces) {
  const double expected = source.diagonal() * scale;
  const double ratio = pieces.diagonal() / expected;
  const Vec3 offset = 0.5 * (pieces.lo + pieces.hi) - 0.5 * scale * (source.lo + source.hi);
  std::ostringstream out;
  out << std::setprecision(3);
  if (!(ratio <= kPlacementRatio && ratio >= 1 / kPlacementRatio)) {
    out << "its pieces are " << ratio << " times the size of the mesh at scale " << scale << " ("
        << pieces.diagonal() << " against " << expected << " across): written at scale "
        << ratio * scale << "?";
    return out.str();
  }
  if (!(offset.norm() <= kPlacementOffset * expected)) {
    out << "its pieces lie " << offset.norm() << " from the mesh at scale " << scale
        << " (their boxes' centres; the mesh is " << expected
        << " across): not in the mesh's coordinates";
    return out.str();
  }
  return "";
}

}  // namespace graspcd::decompose
