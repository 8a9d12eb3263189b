#include "graspcd/io/mesh_declared.h"

#include <tinyxml2.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "graspcd/io/input_error.h"
#include "graspcd/io/text_input.h"

namespace graspcd::io {

namespace {

using nlohmann::json;

[[noreturn]] void refuse(const std::string& path, const std::string& message,
                         std::size_t line = 0) {
  throw InputError(path, line, message);
}

std::vector<std::string> words_of(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

// A count written in decimal digits only; false for anything else.
bool decimal_count(const std::string& text, std::uint64_t& out) {
  if (text.empty() || text.size() > 19) return false;
  out = 0;
  for (const char c : text) {
    if (c < '0' || c > '9') return false;
    out = out * 10 + static_cast<std::uint64_t>(c - '0');
  }
  return true;
}

// --- PLY: the header's element counts against the data that follows it. ---

// The bytes of a binary PLY scalar type; 0 for a name PLY does not define.
std::uint64_t ply_type_bytes(const std::string& type) {
  static const std::pair<const char*, std::uint64_t> kTypes[] = {
      {"char", 1},  {"uchar", 1},   {"int8", 1},   {"uint8", 1},  {"short", 2}, {"ushort", 2},
      {"int16", 2}, {"uint16", 2},  {"int", 4},    {"uint", 4},   {"int32", 4}, {"uint32", 4},
      {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  for (const auto& [name, bytes] : kTypes) {
    if (type == name) return bytes;
  }
  return 0;
}

// ASCII: each element is a line of its own, so the lines holding a word must be as many as the
// elements declared. Binary: each element takes at least its scalar properties' bytes and its
// lists' counts, a face's list at least 3 items (other lists none), so the data must be at least
// that long (a binary PLY that declares fewer elements than it holds passes: the sizes of its
// lists are in its data).
void check_ply(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) refuse(path, "cannot open");
  std::string line;
  std::string format;
  bool ended = false;
  std::uint64_t declared = 0;
  std::uint64_t least_bytes = 0;  // of binary data; 0 once a type is unknown
  bool sized = true;
  std::uint64_t element_count = 0;
  std::string element;
  std::string elements;  // "8 vertex, 100 face"
  for (std::size_t number = 1; !ended && read_line(in, line, path, number); ++number) {
    const std::vector<std::string> w = words_of(line);
    if (w.empty()) continue;
    if (w[0] == "format" && w.size() >= 2) {
      format = w[1];
    } else if (w[0] == "element" && w.size() >= 3) {
      // A count that is not one is Assimp's to refuse.
      if (!decimal_count(w[2], element_count) || element_count > (std::uint64_t{1} << 40)) return;
      element = w[1];
      declared += element_count;
      elements += (elements.empty() ? "" : ", ") + w[2] + " " + w[1];
    } else if (w[0] == "property" && w.size() >= 3) {
      // A list takes its count, and a face's list at least 3 vertices (graspcd refuses fewer).
      const bool list = w[1] == "list" && w.size() >= 4;
      const std::uint64_t bytes = list ? ply_type_bytes(w[2]) : ply_type_bytes(w[1]);
      const std::uint64_t items = list && element == "face" ? 3 * ply_type_bytes(w[3]) : 0;
      sized = sized && bytes > 0 && (!list || ply_type_bytes(w[3]) > 0);
      least_bytes += element_count * (bytes + items);
    } else if (w[0] == "end_header") {
      ended = true;
    }
  }
  // A header without its end is Assimp's (which hangs on it: mesh_import.h's time limit).
  if (!ended) return;
  const std::string head =
      "the header declares " + std::to_string(declared) + " elements (" + elements + ")";
  if (format != "ascii") {
    const std::streamoff at = in.tellg();
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    if (!sized || at < 0 || size < at) return;
    const auto data = static_cast<std::uint64_t>(size - at);
    if (data >= least_bytes) return;
    refuse(path, head + ", at least " + std::to_string(least_bytes) +
                     " bytes of binary data (a face of 3 vertices or more), but " +
                     std::to_string(data) + " bytes follow end_header");
  }
  // Count the lines that hold a word.
  std::uint64_t lines = 0;
  bool word = false;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    const std::streamsize n = in.gcount();
    for (std::streamsize i = 0; i < n; ++i) {
      const char c = buffer[i];
      if (c == '\n') {
        lines += word ? 1 : 0;
        word = false;
      } else if (c != ' ' && c != '\t' && c != '\r') {
        word = true;
      }
    }
  }
  lines += word ? 1 : 0;
  if (lines == declared) return;
  refuse(path, head + ", one line each in an ASCII PLY, but " + std::to_string(lines) + " line" +
                   (lines == 1 ? "" : "s") + " of data follow end_header");
}

// --- glTF: the JSON's structure. ---

std::size_t line_of(const std::string& text, std::size_t at) {
  at = std::min(at, text.size());
  return 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + at, '\n'));
}

// nlohmann's message without its "[json.exception.parse_error.101] parse error at line 1, column
// 7: " prefix (the line is given as FILE:LINE).
std::string json_message(const std::exception& e) {
  std::string message =
      std::regex_replace(e.what(), std::regex(R"(^\[json\.exception\.[^\]]*\] )"), "");
  return std::regex_replace(message, std::regex(R"(^parse error at line \d+, column \d+: )"), "");
}

// The glTF JSON of a .gltf file, or of a .glb's first chunk (its header: "glTF", version, length;
// then the chunk's length and type, "JSON"). Empty when a .glb holds no JSON chunk where it should
// (Assimp's to refuse).
std::string gltf_json_text(const std::string& path, const std::string& format) {
  std::ifstream in(path, std::ios::binary);
  if (!in) refuse(path, "cannot open");
  if (format == "gltf") {
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  unsigned char header[20];
  if (!in.read(reinterpret_cast<char*>(header), sizeof header)) return "";
  const auto u32 = [&](int at) {
    return static_cast<std::uint32_t>(header[at]) |
           static_cast<std::uint32_t>(header[at + 1]) << 8 |
           static_cast<std::uint32_t>(header[at + 2]) << 16 |
           static_cast<std::uint32_t>(header[at + 3]) << 24;
  };
  if (std::memcmp(header + 16, "JSON", 4) != 0) return "";
  const std::uint32_t length = u32(12);
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0 || length > static_cast<std::uint64_t>(size) - 20) return "";
  in.seekg(20);
  std::string text(length, '\0');
  if (!in.read(&text[0], static_cast<std::streamsize>(length))) return "";
  return text;
}

const char* component_name(std::int64_t type) {
  switch (type) {
    case 5120:
      return "BYTE";
    case 5121:
      return "UNSIGNED_BYTE";
    case 5122:
      return "SHORT";
    case 5123:
      return "UNSIGNED_SHORT";
    case 5125:
      return "UNSIGNED_INT";
    case 5126:
      return "FLOAT";
    default:
      return nullptr;
  }
}

// The accessor `index` of `accessors`, or nullptr when there is none (Assimp's to refuse).
const json* accessor_at(const json& accessors, const json& index) {
  if (!index.is_number_unsigned() || !accessors.is_array()) return nullptr;
  const auto i = index.get<std::uint64_t>();
  if (i >= accessors.size() || !accessors[i].is_object()) return nullptr;
  return &accessors[i];
}

std::uint64_t count_of(const json& accessor) {
  const auto it = accessor.find("count");
  return it != accessor.end() && it->is_number_unsigned() ? it->get<std::uint64_t>() : 0;
}

DeclaredMesh check_gltf(const std::string& path, const std::string& format) {
  const std::string text = gltf_json_text(path, format);
  if (text.empty() && format == "glb") return {};
  json root;
  try {
    root = json::parse(text);
  } catch (const json::exception& e) {
    std::size_t line = 0;
    if (const auto* parse = dynamic_cast<const json::parse_error*>(&e)) {
      if (parse->byte > 0 && format == "gltf") line = line_of(text, parse->byte - 1);
    }
    refuse(path,
           std::string(format == "glb" ? "bad JSON in its JSON chunk: " : "bad JSON: ") +
               json_message(e),
           line);
  }
  DeclaredMesh out;
  if (!root.is_object()) refuse(path, "not a glTF file (its JSON is not an object)");
  // glTF 1.0 (an object of named accessors) is Assimp's other reader's.
  const auto asset = root.find("asset");
  if (asset != root.end() && asset->is_object()) {
    const auto version = asset->find("version");
    if (version != asset->end() && version->is_string() &&
        version->get<std::string>().rfind("2", 0) != 0) {
      return out;
    }
  }
  const auto meshes = root.find("meshes");
  const auto accessors = root.find("accessors");
  if (meshes == root.end() || !meshes->is_array() || accessors == root.end()) return out;
  for (std::size_t m = 0; m < meshes->size(); ++m) {
    const json& mesh = (*meshes)[m];
    const auto primitives = mesh.is_object() ? mesh.find("primitives") : mesh.end();
    if (!mesh.is_object() || primitives == mesh.end() || !primitives->is_array()) return {};
    for (std::size_t p = 0; p < primitives->size(); ++p) {
      const json& primitive = (*primitives)[p];
      const std::string where =
          "meshes[" + std::to_string(m) + "].primitives[" + std::to_string(p) + "]: ";
      const auto attributes = primitive.is_object() ? primitive.find("attributes") : mesh.end();
      if (!primitive.is_object() || attributes == primitive.end() || !attributes->is_object()) {
        return {};
      }
      const auto position = attributes->find("POSITION");
      if (position == attributes->end()) return {};
      const json* accessor = accessor_at(*accessors, *position);
      if (accessor == nullptr) return {};
      DeclaredPrimitive d;
      d.mesh = m;
      d.primitive = p;
      d.position_accessor = position->get<std::size_t>();
      d.positions = count_of(*accessor);
      const auto type = accessor->find("type");
      const auto component = accessor->find("componentType");
      const std::string type_name =
          type != accessor->end() && type->is_string() ? type->get<std::string>() : "no type";
      const std::int64_t component_type =
          component != accessor->end() && component->is_number_integer()
              ? component->get<std::int64_t>()
              : 0;
      if (type_name != "VEC3" || component_type != 5126) {
        const char* name = component_name(component_type);
        refuse(path, where + "its POSITION accessor " + std::to_string(d.position_accessor) +
                         " holds " + type_name + " of " +
                         (name ? name : "componentType " + std::to_string(component_type)) +
                         "; a glTF position is a VEC3 of FLOAT (componentType 5126)");
      }
      const auto mode = primitive.find("mode");
      const std::int64_t mode_value =
          mode != primitive.end() && mode->is_number_integer() ? mode->get<std::int64_t>() : 4;
      std::uint64_t vertices = d.positions;
      const auto indices = primitive.find("indices");
      if (indices != primitive.end()) {
        const json* index_accessor = accessor_at(*accessors, *indices);
        if (index_accessor == nullptr) return {};
        d.indices_accessor = indices->get<long long>();
        vertices = count_of(*index_accessor);
      }
      d.triangle_mode = mode_value == 4 || mode_value == 5 || mode_value == 6;
      if (mode_value == 4) {
        if (vertices % 3 != 0) {
          refuse(path, where + std::to_string(vertices) +
                           (d.indices_accessor >= 0
                                ? " indices (accessor " + std::to_string(d.indices_accessor) + ")"
                                : " vertices") +
                           " in TRIANGLES mode, not a multiple of 3");
        }
        d.triangles = vertices / 3;
      } else if (d.triangle_mode) {
        d.triangles = vertices >= 3 ? vertices - 2 : 0;
      }
      out.primitives.push_back(d);
    }
  }
  return out;
}

// --- COLLADA: the units. ---

void find_units(const tinyxml2::XMLElement* e, std::vector<const tinyxml2::XMLElement*>& out) {
  for (const tinyxml2::XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    if (std::strcmp(c->Name(), "unit") == 0) out.push_back(c);
    find_units(c, out);
  }
}

void check_collada(const std::string& path) {
  tinyxml2::XMLDocument doc;
  if (doc.LoadFile(path.c_str()) != tinyxml2::XML_SUCCESS) {
    refuse(path, std::string("not well-formed XML: ") + doc.ErrorName(),
           static_cast<std::size_t>(std::max(0, doc.ErrorLineNum())));
  }
  if (doc.RootElement() == nullptr) return;
  std::vector<const tinyxml2::XMLElement*> units;
  find_units(doc.RootElement(), units);
  for (const tinyxml2::XMLElement* unit : units) {
    const char* meter = unit->Attribute("meter");
    if (meter == nullptr) continue;
    char* end = nullptr;
    const double value = std::strtod(meter, &end);
    const bool number = end != meter && *end == '\0';
    if (number && std::isfinite(value) && value > 0) continue;
    refuse(path,
           std::string("<unit meter=\"") + meter +
               "\">: the metres per unit of the file must be a finite number > 0 (COLLADA "
               "scales the mesh by it)",
           static_cast<std::size_t>(unit->GetLineNum()));
  }
}

}  // namespace

DeclaredMesh check_declared(const std::string& path, const std::string& format) {
  if (format == "ply") {
    check_ply(path);
  } else if (format == "gltf" || format == "glb") {
    return check_gltf(path, format);
  } else if (format == "dae") {
    check_collada(path);
  }
  return {};
}

void check_read_faces(const std::string& path, const DeclaredMesh& declared,
                      const std::vector<std::uint64_t>& read_faces) {
  if (declared.primitives.size() != read_faces.size()) return;
  for (std::size_t i = 0; i < read_faces.size(); ++i) {
    const DeclaredPrimitive& d = declared.primitives[i];
    if (!d.triangle_mode || read_faces[i] >= d.triangles) continue;
    const std::uint64_t dropped = d.triangles - read_faces[i];
    refuse(path, "meshes[" + std::to_string(d.mesh) + "].primitives[" +
                     std::to_string(d.primitive) + "]: " + std::to_string(dropped) + " of its " +
                     std::to_string(d.triangles) + " triangles (indices accessor " +
                     std::to_string(d.indices_accessor) + ") name a vertex beyond the " +
                     std::to_string(d.positions) + " of its POSITION accessor " +
                     std::to_string(d.position_accessor));
  }
}

}  // namespace graspcd::io
