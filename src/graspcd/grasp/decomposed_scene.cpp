// The scene with its object's collision replaced by convex pieces (decomposed_scene.h).
#include "graspcd/grasp/decomposed_scene.h"

#include <stdlib.h>
#include <tinyxml2.h>
#include <unistd.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "graspcd/decompose/manifest.h"
#include "graspcd/grasp/grasp.h"
#include "graspcd/io/mesh_io.h"
#include "graspcd/io/output_files.h"
#include "graspcd/io/text_input.h"
#include "graspcd/io/warnings.h"
#include "graspcd/mujoco/registry.h"

namespace graspcd::grasp {

namespace {

namespace fs = std::filesystem;

// Every element named `tag` below `root`, in document order.
void for_each_element(tinyxml2::XMLElement* root, const char* tag,
                      const std::function<void(tinyxml2::XMLElement*)>& visit) {
  for (tinyxml2::XMLElement* e = root->FirstChildElement(); e != nullptr;
       e = e->NextSiblingElement()) {
    if (std::string(e->Name()) == tag) visit(e);
    for_each_element(e, tag, visit);
  }
}

// A copy of `from` with every attribute, inserted after `after`.
tinyxml2::XMLElement* sibling_copy(tinyxml2::XMLElement* from, tinyxml2::XMLElement* after) {
  tinyxml2::XMLElement* copy = from->GetDocument()->NewElement(from->Name());
  for (const tinyxml2::XMLAttribute* a = from->FirstAttribute(); a != nullptr; a = a->Next()) {
    copy->SetAttribute(a->Name(), a->Value());
  }
  from->Parent()->InsertAfterChild(after, copy);
  return copy;
}

// The decomposition's manifest (graspcd/decompose/manifest.h), its pieces by absolute path, and
// their box. A manifest without a scale (written before graspcd 0.5, as the race's caches) is read
// as scale 1, with a warning.
struct Manifest {
  std::string source;
  double scale = 1;
  bool scale_recorded = true;
  std::vector<std::string> pieces;
  decompose::Box box;
  std::string path;                // DIR/decomposition.json
  std::vector<std::string> named;  // the pieces as DIR/FILE
};

Manifest read_manifest(const std::string& dir) {
  const decompose::Manifest manifest = decompose::read_manifest(dir);
  Manifest m;
  m.source = manifest.source;
  m.scale = manifest.scale;
  m.scale_recorded = manifest.scale_recorded;
  m.path = (fs::path(dir) / decompose::kManifestFile).string();
  for (const decompose::Manifest::Piece& p : manifest.pieces) {
    m.pieces.push_back(fs::absolute(fs::path(dir) / p.file).lexically_normal());
    m.named.push_back((fs::path(dir) / p.file).lexically_normal().string());
  }
  if (!manifest.scale_recorded) {
    warnings().add("decomposition_scale",
                   m.path +
                       ": no \"scale\" (written before graspcd 0.5): read as 1, the pieces in " +
                       fs::path(manifest.source).filename().string() + "'s own units",
                   "scene");
  }
  m.box = decompose::pieces_box(dir, manifest);
  return m;
}

// The three numbers of a scale attribute ("S" or "X Y Z"); nullopt when it is not that.
std::optional<std::array<double, 3>> scale_numbers(const char* text) {
  if (text == nullptr) return std::nullopt;
  std::istringstream in(text);
  std::vector<double> v;
  for (double x; in >> x;) v.push_back(x);
  if (!in.eof() || (v.size() != 1 && v.size() != 3)) return std::nullopt;
  if (v.size() == 1) return std::array<double, 3>{v[0], v[0], v[0]};
  return std::array<double, 3>{v[0], v[1], v[2]};
}

// The <default> element of class `name` under `root` ("main": the top <default>), or null.
tinyxml2::XMLElement* default_class(tinyxml2::XMLElement* root, const std::string& name) {
  tinyxml2::XMLElement* found = nullptr;
  for_each_element(root, "default", [&](tinyxml2::XMLElement* d) {
    const char* c = d->Attribute("class");  // only the top <default> has none: "main"
    if (found == nullptr && (c != nullptr ? name == c : name == "main")) found = d;
  });
  return found;
}

// The scale MuJoCo gives a <mesh>: its own attribute, else its class's (the mesh's `class`, else
// "main"), else that class's parents', else 1.
std::array<double, 3> asset_scale(tinyxml2::XMLElement* root, tinyxml2::XMLElement* mesh) {
  if (const auto own = scale_numbers(mesh->Attribute("scale"))) return *own;
  const char* c = mesh->Attribute("class");
  for (tinyxml2::XMLElement* d = default_class(root, c != nullptr ? c : "main"); d != nullptr;) {
    if (const tinyxml2::XMLElement* m = d->FirstChildElement("mesh")) {
      if (const auto s = scale_numbers(m->Attribute("scale"))) return *s;
    }
    tinyxml2::XMLElement* parent = d->Parent() != nullptr ? d->Parent()->ToElement() : nullptr;
    d = parent != nullptr && std::string(parent->Name()) == "default" ? parent : nullptr;
  }
  return {1, 1, 1};
}

// The file a <mesh file> names as MuJoCo 2.2 reads it: absolute, or under the main file's last
// <compiler meshdir> (relative to the scene's folder), or beside the scene.
fs::path mesh_file(tinyxml2::XMLElement* root, const std::string& scene_path, const char* file) {
  if (fs::path(file).is_absolute()) return file;
  const fs::path folder = fs::absolute(scene_path).parent_path();
  std::string meshdir;
  for_each_element(root, "compiler", [&](tinyxml2::XMLElement* c) {
    if (const char* d = c->Attribute("meshdir")) meshdir = d;
  });
  const fs::path dir = meshdir.empty()                   ? folder
                       : fs::path(meshdir).is_absolute() ? fs::path(meshdir)
                                                         : folder / meshdir;
  return (dir / file).lexically_normal();
}

// Refuses pieces that do not lie where the scene's mesh `file` (or else the manifest's source)
// lies at the decomposition's scale (decompose::placement_mismatch): a scale applied twice or
// forgotten. Neither file readable: nothing to compare with.
void check_placement(const Manifest& manifest, const fs::path& file) {
  std::error_code ec;
  const fs::path source = fs::is_regular_file(file, ec) ? file : fs::path(manifest.source);
  if (!fs::is_regular_file(source, ec)) return;
  const std::string mismatch = decompose::placement_mismatch(
      decompose::bounding_box(io::load_mesh(source.string())), manifest.scale, manifest.box);
  if (!mismatch.empty()) {
    // A refusal is the run's one line (no warnings follow it): it says the scale was missing.
    const std::string read_as =
        manifest.scale_recorded ? "" : "no \"scale\" (written before graspcd 0.5), read as 1: ";
    throw io::InputError(manifest.path, 0,
                         "not a decomposition of " + source.string() + ": " + read_as + mismatch +
                             " (give the scale the pieces were written at as \"scale\", or "
                             "decompose the mesh again)");
  }
}

}  // namespace

DecomposedScene write_decomposed_scene(const std::string& scene_path,
                                       const std::string& decomposition_dir) {
  const Manifest manifest = read_manifest(decomposition_dir);
  tinyxml2::XMLDocument doc;
  if (doc.LoadFile(scene_path.c_str()) != tinyxml2::XML_SUCCESS || doc.RootElement() == nullptr) {
    throw io::InputError(scene_path, 0, "cannot read the scene (XML)");
  }
  DecomposedScene out;
  out.source = manifest.source;
  out.pieces = static_cast<int>(manifest.pieces.size());
  out.piece_files = manifest.named;
  const std::string source_name = fs::path(manifest.source).filename().string();

  // The mesh assets that read the source file (a <mesh> without a name is named by its file's
  // stem, as MuJoCo does), each followed by its pieces.
  std::map<std::string, std::string> piece_prefix;  // mesh name -> the pieces' name prefix
  for_each_element(doc.RootElement(), "mesh", [&](tinyxml2::XMLElement* mesh) {
    const char* file = mesh->Attribute("file");
    if (file == nullptr || fs::path(file).filename().string() != source_name) return;
    const char* named = mesh->Attribute("name");
    const std::string name = named != nullptr ? named : fs::path(file).stem().string();
    check_placement(manifest, mesh_file(doc.RootElement(), scene_path, file));
    // The pieces are the source times the decomposition's scale: the asset's scale divided by it
    // puts them where the scene's mesh is.
    const std::array<double, 3> scale = asset_scale(doc.RootElement(), mesh);
    std::ostringstream piece_scale;
    piece_scale << std::setprecision(17) << scale[0] / manifest.scale << ' '
                << scale[1] / manifest.scale << ' ' << scale[2] / manifest.scale;
    piece_prefix[name] = name + "__piece_";
    tinyxml2::XMLElement* after = mesh;
    for (std::size_t k = 0; k < manifest.pieces.size(); ++k) {
      tinyxml2::XMLElement* piece = sibling_copy(mesh, after);
      piece->SetAttribute("name", (name + "__piece_" + std::to_string(k)).c_str());
      piece->SetAttribute("file", manifest.pieces[k].c_str());
      piece->SetAttribute("scale", piece_scale.str().c_str());
      after = piece;
    }
    ++out.mesh_assets;
  });
  if (out.mesh_assets == 0) {
    throw io::InputError(
        scene_path, 0,
        "no <mesh> of the scene reads " + source_name + ", the source of " + decomposition_dir);
  }

  // Their geoms: kept for the mass, out of collision, followed by the pieces (mass 0).
  std::vector<tinyxml2::XMLElement*> geoms;
  for_each_element(doc.RootElement(), "geom", [&](tinyxml2::XMLElement* g) {
    const char* mesh = g->Attribute("mesh");
    if (mesh != nullptr && piece_prefix.count(mesh) > 0) geoms.push_back(g);
  });
  for (tinyxml2::XMLElement* g : geoms) {
    const std::string prefix = piece_prefix.at(g->Attribute("mesh"));
    const char* named = g->Attribute("name");
    tinyxml2::XMLElement* after = g;
    for (std::size_t k = 0; k < manifest.pieces.size(); ++k) {
      tinyxml2::XMLElement* piece = sibling_copy(g, after);
      if (named != nullptr) {
        piece->SetAttribute("name", (std::string(named) + "__piece_" + std::to_string(k)).c_str());
      }
      piece->SetAttribute("mesh", (prefix + std::to_string(k)).c_str());
      piece->DeleteAttribute("density");
      piece->SetAttribute("mass", "0");
      after = piece;
    }
    g->SetAttribute("contype", "0");
    g->SetAttribute("conaffinity", "0");
    ++out.replaced_geoms;
  }

  // Beside the original, under a unique hidden name.
  const fs::path original(scene_path);
  std::string pattern =
      (original.parent_path() / ("." + original.stem().string() + ".decomposed-XXXXXX")).string();
  const int fd = mkstemp(pattern.data());
  if (fd < 0) throw io::InputError(scene_path, 0, "cannot write a scene beside it");
  close(fd);
  if (doc.SaveFile(pattern.c_str()) != tinyxml2::XML_SUCCESS) {
    fs::remove(pattern);
    throw io::InputError(scene_path, 0, "cannot write a scene beside it");
  }
  out.scene = pattern;
  return out;
}

GraspResult run_decomposed_grasp(const std::string& scene_path,
                                 const std::string& decomposition_dir, GraspOptions options,
                                 DecomposedScene* written) {
  const DecomposedScene scene = write_decomposed_scene(scene_path, decomposition_dir);
  // Removed on return, on errors and on INT, TERM and HUP (io/output_files.h).
  const io::CleanupGuard remove{scene.scene};
  if (written != nullptr) *written = scene;
  options.native = true;
  if (options.config_path.empty()) options.config_path = mujoco::pair_config_path(scene_path);
  // A refusal of the written scene names the user's, without its line (the written scene's).
  options.names.written_scene = scene.scene;
  options.names.scene = scene_path;
  options.names.scene_context = "with " + decomposition_dir + ": ";
  options.names.pieces = scene.piece_files;
  GraspResult result = run_grasp(scene.scene, options);
  result.scene = scene_path;
  return result;
}

}  // namespace graspcd::grasp
