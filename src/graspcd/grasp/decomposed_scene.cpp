// The scene with its object's collision replaced by convex pieces (decomposed_scene.h).
#include "graspcd/grasp/decomposed_scene.h"

#include <stdlib.h>
#include <tinyxml2.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "graspcd/decompose/manifest.h"
#include "graspcd/grasp/grasp.h"
#include "graspcd/io/output_files.h"
#include "graspcd/io/text_input.h"
#include "graspcd/mujoco/registry.h"

namespace graspcd::grasp {

namespace {

namespace fs = std::filesystem;

// The decomposition's manifest (graspcd/decompose/manifest.h) and its pieces by absolute path.
struct Manifest {
  std::string source;
  std::vector<std::string> pieces;
};

Manifest read_manifest(const std::string& dir) {
  const decompose::Manifest manifest = decompose::read_manifest(dir);
  Manifest m;
  m.source = manifest.source;
  for (const decompose::Manifest::Piece& p : manifest.pieces) {
    m.pieces.push_back(fs::absolute(fs::path(dir) / p.file).lexically_normal());
  }
  return m;
}

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
  const std::string source_name = fs::path(manifest.source).filename().string();

  // The mesh assets that read the source file (a <mesh> without a name is named by its file's
  // stem, as MuJoCo does), each followed by its pieces.
  std::map<std::string, std::string> piece_prefix;  // mesh name -> the pieces' name prefix
  for_each_element(doc.RootElement(), "mesh", [&](tinyxml2::XMLElement* mesh) {
    const char* file = mesh->Attribute("file");
    if (file == nullptr || fs::path(file).filename().string() != source_name) return;
    const char* named = mesh->Attribute("name");
    const std::string name = named != nullptr ? named : fs::path(file).stem().string();
    piece_prefix[name] = name + "__piece_";
    tinyxml2::XMLElement* after = mesh;
    for (std::size_t k = 0; k < manifest.pieces.size(); ++k) {
      tinyxml2::XMLElement* piece = sibling_copy(mesh, after);
      piece->SetAttribute("name", (name + "__piece_" + std::to_string(k)).c_str());
      piece->SetAttribute("file", manifest.pieces[k].c_str());
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
  GraspResult result = run_grasp(scene.scene, options);
  result.scene = scene_path;
  return result;
}

}  // namespace graspcd::grasp
