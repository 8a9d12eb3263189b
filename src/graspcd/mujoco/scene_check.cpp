#include "graspcd/mujoco/scene_check.h"

#include <tinyxml2.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "graspcd/io/mesh_io.h"
#include "graspcd/io/text_input.h"
#include "graspcd/mujoco/input_error.h"

namespace graspcd::mujoco {
namespace {

namespace fs = std::filesystem;

// MJCF attributes whose values are names or files, never numbers: a geom may be called "nan".
const std::set<std::string>& name_attributes() {
  static const std::set<std::string> names = {
      "name",          "class",    "childclass", "file",      "mesh",        "material",
      "texture",       "hfield",   "skin",       "joint",     "joint1",      "joint2",
      "jointinparent", "tendon",   "tendon1",    "tendon2",   "site",        "body",
      "body1",         "body2",    "geom",       "geom1",     "geom2",       "target",
      "objname",       "objtype",  "actuator",   "model",     "prefix",      "meshdir",
      "texturedir",    "assetdir", "fileright",  "fileleft",  "fileup",      "filedown",
      "filefront",     "fileback", "slidersite", "cranksite", "refsite",     "camera",
      "light",         "key",      "plugin",     "instance",  "content_type"};
  return names;
}

// The first word of `value` that strtod reads whole as a non-finite number, or "" when none does
// (or when some word is not a number at all: then the attribute is not a list of numbers).
std::string non_finite_word(const std::string& value) {
  std::istringstream words(value);
  std::string bad;
  for (std::string word; words >> word;) {
    char* end = nullptr;
    const double x = std::strtod(word.c_str(), &end);
    if (end == word.c_str() || *end != '\0') return "";
    if (!std::isfinite(x) && bad.empty()) bad = word;
  }
  return bad;
}

struct MeshFile {
  std::string scene;  // the MJCF file that names it
  int line = 0;
  std::string file;  // as written
};

// The attributes that name a file MuJoCo reads (an asset's file, a cube texture's six faces).
const std::set<std::string>& file_attributes() {
  static const std::set<std::string> names = {"file",     "fileright", "fileleft", "fileup",
                                              "filedown", "filefront", "fileback"};
  return names;
}

struct Scan {
  const SceneNames* names = nullptr;  // how messages name the files
  fs::path main_dir;       // the main file's folder: includes and mesh folders start there
  std::string meshdir;     // <compiler meshdir>, or assetdir, as written
  std::string texturedir;  // <compiler texturedir>, or assetdir, as written
  std::vector<MeshFile> meshes;
  std::vector<MeshFile> assets;      // every other file an asset names (hfield, skin, texture)
  std::vector<std::string> visited;  // the scene and the files it includes, as read
  int depth = 0;
};

// Where MuJoCo may look for an asset's file `file` (meshdir, texturedir, the main folder): an
// absolute file as is.
std::vector<fs::path> asset_places(const Scan& scan, const std::string& file) {
  const fs::path named(file);
  if (named.is_absolute()) return {named};
  return {(scan.main_dir / fs::path(scan.meshdir) / named).lexically_normal(),
          (scan.main_dir / fs::path(scan.texturedir) / named).lexically_normal(),
          (scan.main_dir / named).lexically_normal()};
}

// A file the scene names that is a FIFO, a folder or a device: refused at its line before
// anything opens it (reading a FIFO waits for a writer, for ever).
void require_regular(const Scan& scan, const std::string& scene, int line,
                     const std::string& element, const std::string& file, const fs::path& place) {
  try {
    io::require_regular_file(place.string());
  } catch (const io::InputError& e) {
    throw scan.names->refusal(
        scene, static_cast<std::size_t>(line),
        "<" + element + " file=\"" + file + "\">: " + place.string() + ": " + e.message());
  }
}

void scan_file(const std::string& path, Scan& scan);

void scan_element(const std::string& path, const tinyxml2::XMLElement* e, Scan& scan) {
  const std::string element = e->Name();
  for (const tinyxml2::XMLAttribute* a = e->FirstAttribute(); a != nullptr; a = a->Next()) {
    const std::string name = a->Name();
    const std::string value = a->Value();
    if (name_attributes().count(name) != 0) continue;
    const std::string bad = non_finite_word(value);
    if (bad.empty()) continue;
    const char* label = e->Attribute("name");
    throw scan.names->refusal(path, static_cast<std::size_t>(a->GetLineNum()),
                              "<" + element +
                                  (label ? std::string(" name=\"") + label + "\"" : "") + "> " +
                                  name + "=\"" + value + "\": non-finite number \"" + bad + "\"");
  }
  if (element == "compiler") {
    if (const char* dir = e->Attribute("assetdir")) scan.meshdir = scan.texturedir = dir;
    if (const char* dir = e->Attribute("meshdir")) scan.meshdir = dir;
    if (const char* dir = e->Attribute("texturedir")) scan.texturedir = dir;
  } else if (element == "mesh" && e->Attribute("file") != nullptr) {
    scan.meshes.push_back({path, e->GetLineNum(), e->Attribute("file")});
  } else if (element == "include" && e->Attribute("file") != nullptr) {
    const std::string file = e->Attribute("file");
    const fs::path included = scan.main_dir / file;
    require_regular(scan, path, e->GetLineNum(), element, file, included);
    scan_file(included.string(), scan);
  } else if (element != "include") {
    for (const tinyxml2::XMLAttribute* a = e->FirstAttribute(); a != nullptr; a = a->Next()) {
      if (file_attributes().count(a->Name()) == 0) continue;
      scan.assets.push_back({path, e->GetLineNum(), a->Value()});
      for (const fs::path& place : asset_places(scan, a->Value())) {
        require_regular(scan, path, e->GetLineNum(), element, a->Value(), place);
      }
    }
  }
  for (const tinyxml2::XMLElement* c = e->FirstChildElement(); c != nullptr;
       c = c->NextSiblingElement()) {
    scan_element(path, c, scan);
  }
}

// A file that does not parse (or an include nested too deep) is left to MuJoCo's reader.
void scan_file(const std::string& path, Scan& scan) {
  constexpr int kMaxIncludeDepth = 16;
  if (scan.depth >= kMaxIncludeDepth) return;
  scan.visited.push_back(path);
  tinyxml2::XMLDocument doc;
  if (doc.LoadFile(path.c_str()) != tinyxml2::XML_SUCCESS || doc.RootElement() == nullptr) return;
  // MuJoCo's reader reads the first root element and ignores what follows it.
  if (const tinyxml2::XMLElement* second = doc.RootElement()->NextSiblingElement()) {
    throw scan.names->refusal(path, static_cast<std::size_t>(second->GetLineNum()),
                              std::string("a second root element <") + second->Name() +
                                  "> after <" + doc.RootElement()->Name() +
                                  ">: an XML file has one root");
  }
  ++scan.depth;
  scan_element(path, doc.RootElement(), scan);
  --scan.depth;
}

// The main file, its includes and every file they name, checked as check_scene_file says.
Scan scan_scene(const std::string& path, const SceneNames& names) {
  Scan scan;
  scan.names = &names;
  scan.main_dir = fs::path(path).parent_path();
  scan_file(path, scan);
  return scan;
}

// A mesh as MuJoCo 2.2 finds it: an absolute file as is, otherwise in meshdir, itself relative to
// the main file's folder unless absolute.
fs::path mesh_place(const Scan& scan, const MeshFile& mesh) {
  fs::path file(mesh.file);
  if (file.is_relative()) file = scan.main_dir / fs::path(scan.meshdir) / file;
  return file.lexically_normal();
}

}  // namespace

void check_scene_file(const std::string& path, const SceneNames& names) {
  const Scan scan = scan_scene(path, names);
  for (const MeshFile& mesh : scan.meshes) {
    const fs::path file = mesh_place(scan, mesh);
    std::error_code ec;
    if (!fs::exists(file, ec)) continue;  // MuJoCo's error names it
    try {
      io::check_mesh_file(file.string());
    } catch (const io::InputError& e) {
      throw scan.names->refusal(e.file(), e.line(), e.message());  // the user's name for a copy
    }
  }
}

std::vector<std::string> scene_files(const std::string& path) {
  const SceneNames names;
  const Scan scan = scan_scene(path, names);
  std::vector<std::string> files = scan.visited;
  std::error_code ec;
  for (const MeshFile& mesh : scan.meshes) files.push_back(mesh_place(scan, mesh).string());
  for (const MeshFile& asset : scan.assets) {
    for (const fs::path& place : asset_places(scan, asset.file)) files.push_back(place.string());
  }
  files.erase(std::remove_if(files.begin(), files.end(),
                             [&ec](const std::string& f) { return !fs::exists(f, ec); }),
              files.end());
  return files;
}

}  // namespace graspcd::mujoco
