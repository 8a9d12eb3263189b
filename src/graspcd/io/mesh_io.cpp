#include "graspcd/io/mesh_io.h"

#include <sys/stat.h>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <limits>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "graspcd/core/mesh_hygiene.h"
#include "graspcd/core/tolerances.h"
#include "graspcd/io/input_error.h"
#include "graspcd/io/mesh_declared.h"
#include "graspcd/io/mesh_import.h"

namespace graspcd::io {

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& message, std::size_t line = 0) {
  throw InputError(path, line, message);
}

// Fails unless `path` names a readable regular file (a directory opens but cannot be read).
void require_readable(const std::string& path) {
  require_regular_file(path);
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) fail(path, std::string("cannot open: ") + std::strerror(errno));
  struct stat info {};
  const bool is_dir = ::fstat(::fileno(file), &info) == 0 && S_ISDIR(info.st_mode);
  std::fclose(file);
  if (is_dir) fail(path, std::string("cannot open: ") + std::strerror(EISDIR));
}

bool in_exact_range(double x) {
  const double m = std::fabs(x);
  return x == 0.0 || (m >= tol::kMinCoordinate && m <= tol::kMaxCoordinate);
}

// Checks that a vertex is finite and inside the exact-arithmetic range of tolerances.h.
void check_vertex(const std::string& path, const std::string& which, const Vec3& p) {
  for (int i = 0; i < 3; ++i) {
    if (in_exact_range(p[i])) continue;
    std::ostringstream out;
    out << which << " has coordinate " << p[i];
    if (std::isfinite(p[i])) {
      out << ", outside the exact-arithmetic range (0 or " << tol::kMinCoordinate
          << " <= |x| <= " << tol::kMaxCoordinate << ")";
    } else {
      out << " (coordinates must be finite)";
    }
    fail(path, out.str());
  }
}

std::string lower_extension(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// tinyobjloader's number parser reads what it does not understand as 0 or as a prefix of the token
// ("nan" and "x" become 0, "0x1p3" becomes 0, "1,5" becomes 1) and an overflowing literal as inf,
// without naming a line. So every vertex line is first read here with the command line's number
// grammar (text_input.h, parse_number), and a bad coordinate is reported at its line before
// tinyobjloader reads the file. A vertex line is what tinyobjloader takes for one: after leading
// spaces or tabs, 'v' followed by a space or a tab. It must hold x y z, optionally followed by w
// (4 numbers) or a colour r g b (6 numbers); a '#' ends the line's content. Hexadecimal floats,
// which strtod reads but tinyobjloader does not, are refused. The values read here are then
// compared with tinyobjloader's (check_obj_vertices), so that no other misreading goes unnoticed.
struct ObjVertexLine {
  std::size_t line = 0;  // 1-based physical line
  Vec3 position;         // x y z as strtod reads them
};

// A face line's vertex references, as tinyobjloader resolves them: the number before the first
// '/' of each word, 1-based, or negative for "counted back from the last vertex read so far".
struct ObjFaceLine {
  std::size_t line = 0;  // 1-based physical line
  std::size_t face = 0;  // 1-based, in file order (before triangulation)
  long largest = 0;      // the largest positive reference (0: none); checked at the end
};

// The scan also collects the names of the file's objects ('o NAME' lines): MuJoCo 2.2 loads only
// the first object of an OBJ file, silently. And it checks every face line ('f' then a blank): at
// least 3 vertex references, each an integer that names a vertex of the file (a negative one a
// vertex read before it); tinyobjloader would drop or misread such a face without a line number.
// A UTF-8 byte-order mark is refused: neither this scan nor tinyobjloader (nor MuJoCo's reader)
// would see the first line's 'v', and every face would then name the wrong vertices.
std::vector<ObjVertexLine> read_obj_vertex_lines(const std::string& path,
                                                 std::vector<std::string>& objects) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open");
  const auto blank = [](char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
  };
  std::vector<ObjVertexLine> vertices;
  std::vector<ObjFaceLine> faces;
  std::string line;
  std::vector<std::string> tokens;
  // The words of `line` from `pos` up to a '#' (which ends the line's content).
  const auto split_words = [&](std::size_t pos) {
    const std::size_t end = std::min(line.find('#', pos), line.size());
    tokens.clear();
    while (pos < end) {
      while (pos < end && blank(line[pos])) ++pos;
      std::size_t stop = pos;
      while (stop < end && !blank(line[stop])) ++stop;
      if (stop > pos) tokens.push_back(line.substr(pos, stop - pos));
      pos = stop;
    }
  };
  for (std::size_t line_number = 1; read_line(in, line, path, line_number); ++line_number) {
    if (line_number == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) {
      fail(path, "UTF-8 byte-order mark", 1);
    }
    std::size_t pos = 0;
    while (pos < line.size() && (line[pos] == ' ' || line[pos] == '\t')) ++pos;
    if (pos + 1 < line.size() && line[pos] == 'o' &&
        (line[pos + 1] == ' ' || line[pos + 1] == '\t')) {
      std::string name = line.substr(pos + 2);
      while (!name.empty() && blank(name.back())) name.pop_back();
      while (!name.empty() && blank(name.front())) name.erase(name.begin());
      objects.push_back(name);
      continue;
    }
    if (pos + 1 < line.size() && line[pos] == 'f' &&
        (line[pos + 1] == ' ' || line[pos + 1] == '\t')) {
      ObjFaceLine face;
      face.line = line_number;
      face.face = faces.size() + 1;
      const std::string which = "face " + std::to_string(face.face);
      split_words(pos + 1);
      if (tokens.size() < 3) {
        fail(path, which + ": " + std::to_string(tokens.size()) + " vertices (a face needs 3)",
             line_number);
      }
      for (const std::string& token : tokens) {
        const std::string index = token.substr(0, token.find('/'));
        char* end = nullptr;
        errno = 0;
        const long value = std::strtol(index.c_str(), &end, 10);
        if (index.empty() || *end != '\0' || errno == ERANGE) {
          fail(path, which + ": bad vertex index \"" + token + "\"", line_number);
        }
        if (value == 0)
          fail(path, which + ": vertex index 0 (OBJ indices start at 1)", line_number);
        if (value < 0 && static_cast<std::size_t>(-(value + 1)) >= vertices.size()) {
          fail(path,
               which + ": vertex index " + index + " points before the first vertex (" +
                   std::to_string(vertices.size()) + " vertices precede it)",
               line_number);
        }
        face.largest = std::max(face.largest, value);
      }
      faces.push_back(face);
      continue;
    }
    // A normal or a texture coordinate: numbers that MuJoCo 2.2's reader copies as it counts
    // them, reading past its buffer on a line of other words (found by fuzz_scene_mjcf).
    if (pos + 2 < line.size() && line[pos] == 'v' &&
        (line[pos + 1] == 'n' || line[pos + 1] == 't') &&
        (line[pos + 2] == ' ' || line[pos + 2] == '\t')) {
      const bool normal = line[pos + 1] == 'n';
      const std::string which = normal ? "normal" : "texture coordinate";
      split_words(pos + 2);
      if (normal ? tokens.size() != 3 : tokens.size() < 2 || tokens.size() > 3) {
        fail(path,
             which + ": expected " + (normal ? "3" : "2 or 3") + " numbers, got " +
                 std::to_string(tokens.size()),
             line_number);
      }
      // Words, not numbers, are refused; a non-finite normal is not a vertex and stays allowed.
      for (const std::string& token : tokens) {
        char* end = nullptr;
        std::strtod(token.c_str(), &end);
        if (end == token.c_str() || *end != '\0') {
          fail(path, which + ": malformed number \"" + token + "\"", line_number);
        }
      }
      continue;
    }
    if (pos + 1 >= line.size() || line[pos] != 'v' ||
        (line[pos + 1] != ' ' && line[pos + 1] != '\t')) {
      continue;
    }
    const std::string which = "vertex " + std::to_string(vertices.size() + 1);
    split_words(pos + 1);
    if (tokens.size() != 3 && tokens.size() != 4 && tokens.size() != 6) {
      fail(path,
           which + ": expected x y z (optionally followed by w, or by r g b), got " +
               std::to_string(tokens.size()) + " numbers",
           line_number);
    }
    ObjVertexLine vertex;
    vertex.line = line_number;
    for (std::size_t k = 0; k < tokens.size(); ++k) {
      const std::string& token = tokens[k];
      const std::size_t digits = token[0] == '+' || token[0] == '-' ? 1 : 0;
      if (token.size() > digits + 1 && token[digits] == '0' &&
          (token[digits + 1] == 'x' || token[digits + 1] == 'X')) {
        fail(path, which + ": hexadecimal number \"" + token + "\" (OBJ files take decimals)",
             line_number);
      }
      try {
        const double x = parse_number(token);
        if (k < 3) vertex.position[static_cast<Eigen::Index>(k)] = x;
      } catch (const ValueError& e) {
        fail(path, which + ": " + e.what(), line_number);
      }
    }
    vertices.push_back(vertex);
  }
  if (in.bad()) fail(path, "read error");
  for (const ObjFaceLine& face : faces) {
    if (static_cast<std::size_t>(face.largest) <= vertices.size()) continue;
    fail(path,
         "face " + std::to_string(face.face) + ": vertex index " + std::to_string(face.largest) +
             " out of range (the file has " + std::to_string(vertices.size()) + " vertices)",
         face.line);
  }
  return vertices;
}

// tinyobjloader's number parser is not correctly rounded (docs/stress.md, "Known limitations"): its
// values may differ from strtod's by a few ulps, never by more than this relative amount.
constexpr double kObjParserRelativeError = 1e-12;

// Checks that tinyobjloader read the vertices the scan found, with the same values up to its
// rounding: the guard against a misreading the scan does not foresee.
void check_obj_vertices(const std::string& path, const std::vector<ObjVertexLine>& scanned,
                        const std::vector<tinyobj::real_t>& read) {
  if (read.size() != 3 * scanned.size()) {
    fail(path, "the OBJ parser read " + std::to_string(read.size() / 3) + " vertices from " +
                   std::to_string(scanned.size()) + " vertex lines");
  }
  for (std::size_t i = 0; i < scanned.size(); ++i) {
    for (std::size_t k = 0; k < 3; ++k) {
      const double ours = scanned[i].position[static_cast<Eigen::Index>(k)];
      const double theirs = read[3 * i + k];
      if (std::fabs(theirs - ours) <= kObjParserRelativeError * std::fabs(ours)) continue;
      std::ostringstream out;
      out.precision(17);
      out << "vertex " << i + 1 << ": the OBJ parser read coordinate " << k + 1 << " as " << theirs
          << " where strtod reads " << ours;
      fail(path, out.str(), scanned[i].line);
    }
  }
}

TriangleMesh load_obj(const std::string& path, std::vector<std::string>& objects) {
  const std::vector<ObjVertexLine> scanned = read_obj_vertex_lines(path, objects);
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, config)) {
    // tinyobjloader names the line inside its message, as "line N".
    const std::string message = one_line(reader.Error());
    std::smatch match;
    std::size_t line = 0;
    if (std::regex_search(message, match, std::regex("line (\\d+)"))) {
      line = static_cast<std::size_t>(std::stoul(match[1].str()));
    }
    fail(path, "OBJ parse error: " + message, line);
  }
  // tinyobjloader only warns when it drops a face; here that is bad input.
  const std::string& warning = reader.Warning();
  if (warning.find("Degenerated face") != std::string::npos) {
    fail(path, "a face has fewer than 3 vertices");
  }
  if (warning.find("invalid vertex index") != std::string::npos) {
    fail(path, "a face references a vertex index out of range");
  }

  TriangleMesh mesh;
  const auto& v = reader.GetAttrib().vertices;
  check_obj_vertices(path, scanned, v);
  const std::size_t vertex_count = v.size() / 3;
  if (vertex_count > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
    fail(path, "too many vertices");
  }
  mesh.vertices.reserve(vertex_count);
  for (std::size_t i = 0; i < vertex_count; ++i) {
    mesh.vertices.emplace_back(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
    check_vertex(path, "vertex " + std::to_string(i + 1), mesh.vertices.back());
  }

  // Concatenate every shape's triangles.
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const auto& indices = shape.mesh.indices;
    std::size_t offset = 0;
    for (const unsigned char arity : shape.mesh.num_face_vertices) {
      if (arity != 3 || offset + 3 > indices.size()) {
        fail(path, "tinyobjloader returned a face that is not a triangle");
      }
      std::array<std::int32_t, 3> face{};
      for (std::size_t k = 0; k < 3; ++k) {
        const int index = indices[offset + k].vertex_index;
        if (index < 0 || static_cast<std::size_t>(index) >= vertex_count) {
          std::ostringstream out;
          out << "face " << mesh.faces.size() + 1
              << " references a vertex out of range (the file has " << vertex_count << " vertices)";
          fail(path, out.str());
        }
        face[k] = static_cast<std::int32_t>(index);
      }
      mesh.faces.push_back(face);
      offset += 3;
    }
  }
  return mesh;
}

std::uint32_t read_u32_le(const unsigned char* p) {
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
         static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}

double read_f32_le(const unsigned char* p) {
  const std::uint32_t bits = read_u32_le(p);
  float value = 0.0f;
  static_assert(sizeof(value) == sizeof(bits), "IEEE single precision float expected");
  std::memcpy(&value, &bits, sizeof(value));
  return static_cast<double>(value);
}

// The words of a text line up to a '#' when `comments` (OFF), blank-separated.
std::vector<std::string> words_of(const std::string& line, bool comments) {
  std::vector<std::string> out;
  const std::size_t end = comments ? std::min(line.find('#'), line.size()) : line.size();
  std::size_t pos = 0;
  while (pos < end) {
    while (pos < end && std::isspace(static_cast<unsigned char>(line[pos]))) ++pos;
    std::size_t stop = pos;
    while (stop < end && !std::isspace(static_cast<unsigned char>(line[stop]))) ++stop;
    if (stop > pos) out.push_back(line.substr(pos, stop - pos));
    pos = stop;
  }
  return out;
}

// A coordinate read with the command line's number grammar (text_input.h), at its line.
double coordinate(const std::string& path, const std::string& which, const std::string& token,
                  std::size_t line) {
  try {
    return parse_number(token);
  } catch (const ValueError& e) {
    fail(path, which + ": " + e.what(), line);
  }
}

// A vertex from three coordinate tokens at its line, checked (check_vertex) with that line named.
Vec3 text_vertex(const std::string& path, const std::string& which, const std::string& x,
                 const std::string& y, const std::string& z, std::size_t line) {
  const Vec3 p(coordinate(path, which, x, line), coordinate(path, which, y, line),
               coordinate(path, which, z, line));
  try {
    check_vertex(path, which, p);
  } catch (const InputError& e) {
    fail(path, e.message(), line);
  }
  return p;
}

// ASCII STL, read here in double precision with line numbers (Assimp reads floats and names no
// line): "solid [name]", then per facet "facet normal nx ny nz", "outer loop", three
// "vertex x y z", "endloop", "endfacet"; "endsolid [name]". Several solids in one file are
// concatenated (the multi-object rule of OBJ). The normals are not used; keywords are
// case-insensitive. Every facet gets its own three vertices (load_mesh welds them).
TriangleMesh load_ascii_stl(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open");
  TriangleMesh mesh;
  enum class State { kOutside, kSolid, kFacet, kLoop, kEndLoop };
  State state = State::kOutside;
  std::size_t facet_line = 0;
  int corners = 0;
  std::string line;
  const auto lower = [](std::string w) {
    std::transform(w.begin(), w.end(), w.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return w;
  };
  std::size_t line_number = 1;
  for (; read_line(in, line, path, line_number); ++line_number) {
    const std::vector<std::string> w = words_of(line, false);
    if (w.empty()) continue;
    const std::string key = lower(w[0]);
    const std::string facet = "facet " + std::to_string(mesh.faces.size() + 1);
    const auto expect = [&](const char* what) {
      fail(path, "ASCII STL: expected " + std::string(what) + ", found \"" + w[0] + "\"",
           line_number);
    };
    switch (state) {
      case State::kOutside:
        if (key != "solid") expect("'solid'");
        state = State::kSolid;
        break;
      case State::kSolid:
        if (key == "endsolid") {
          state = State::kOutside;
        } else if (key == "facet") {
          if (w.size() != 5 || lower(w[1]) != "normal") {
            fail(path, facet + ": expected 'facet normal nx ny nz'", line_number);
          }
          state = State::kFacet;
          facet_line = line_number;
        } else {
          expect("'facet' or 'endsolid'");
        }
        break;
      case State::kFacet:
        if (key != "outer" || w.size() != 2 || lower(w[1]) != "loop") expect("'outer loop'");
        state = State::kLoop;
        corners = 0;
        break;
      case State::kLoop:
        if (key == "vertex") {
          if (w.size() != 4) {
            fail(path,
                 facet + ": expected 'vertex x y z', got " + std::to_string(w.size() - 1) +
                     " numbers",
                 line_number);
          }
          if (corners == 3) fail(path, facet + ": more than 3 vertices", line_number);
          const std::string which = facet + " vertex " + std::to_string(corners + 1);
          mesh.vertices.push_back(text_vertex(path, which, w[1], w[2], w[3], line_number));
          ++corners;
        } else if (key == "endloop") {
          if (corners != 3) {
            fail(path, facet + ": " + std::to_string(corners) + " vertices (a facet needs 3)",
                 line_number);
          }
          const auto n = static_cast<std::int32_t>(mesh.vertices.size());
          mesh.faces.push_back({n - 3, n - 2, n - 1});
          state = State::kEndLoop;
        } else {
          expect("'vertex' or 'endloop'");
        }
        break;
      case State::kEndLoop:
        if (key != "endfacet") expect("'endfacet'");
        state = State::kSolid;
        break;
    }
  }
  if (in.bad()) fail(path, "read error");
  if (state == State::kOutside && line_number == 1) fail(path, "empty file");
  if (state != State::kOutside && state != State::kSolid) {
    fail(path, "ASCII STL: the file ends inside facet " + std::to_string(mesh.faces.size() + 1),
         facet_line);
  }
  return mesh;
}

// OFF (Object File Format), read here in double precision with line numbers: "OFF" (or its
// variants COFF, NOFF, CNOFF: colours and normals after the coordinates are ignored), then
// "V F E", V vertex lines "x y z ...", F face lines "n i1 ... in ..." (0-based indices; colours
// after them ignored). '#' starts a comment. A face of n > 3 vertices is triangulated as a fan
// from its first vertex (exact for a convex face, as OFF writers give).
TriangleMesh load_off(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open");
  std::string line;
  std::size_t line_number = 0;
  std::vector<std::string> w;
  // The next line with words, or false at the end.
  const auto next = [&]() {
    while (read_line(in, line, path, line_number + 1)) {
      ++line_number;
      w = words_of(line, true);
      if (!w.empty()) return true;
    }
    return false;
  };
  if (!next()) fail(path, "empty file (an OFF file starts with 'OFF')");
  if (line_number == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0)
    fail(path, "UTF-8 byte-order mark", 1);
  const std::string head = w[0];
  const bool known = head == "OFF" || head == "COFF" || head == "NOFF" || head == "CNOFF";
  if (!known) fail(path, "expected 'OFF' first, found \"" + head + "\"", line_number);
  w.erase(w.begin());
  if (w.empty() && !next()) fail(path, "no 'V F E' counts after 'OFF'", line_number);
  if (w.size() < 2) fail(path, "expected the counts 'V F E'", line_number);
  const auto count = [&](const std::string& token, const char* what) {
    char* end = nullptr;
    errno = 0;
    const long long x = std::strtoll(token.c_str(), &end, 10);
    if (token.empty() || *end != '\0' || errno == ERANGE || x < 0 ||
        x > std::numeric_limits<std::int32_t>::max()) {
      fail(path, std::string("bad ") + what + " \"" + token + "\"", line_number);
    }
    return static_cast<std::size_t>(x);
  };
  const std::size_t nv = count(w[0], "vertex count");
  const std::size_t nf = count(w[1], "face count");
  TriangleMesh mesh;
  for (std::size_t i = 0; i < nv; ++i) {
    const std::string which = "vertex " + std::to_string(i);
    if (!next()) fail(path, "the file ends at " + which + " (" + std::to_string(nv) + " declared)");
    if (w.size() < 3) fail(path, which + ": expected x y z", line_number);
    mesh.vertices.push_back(text_vertex(path, which, w[0], w[1], w[2], line_number));
  }
  for (std::size_t f = 0; f < nf; ++f) {
    const std::string which = "face " + std::to_string(f);
    if (!next()) fail(path, "the file ends at " + which + " (" + std::to_string(nf) + " declared)");
    const std::size_t n = count(w[0], "face size");
    if (n < 3)
      fail(path, which + ": " + std::to_string(n) + " vertices (a face needs 3)", line_number);
    if (w.size() < n + 1) {
      fail(path,
           which + ": " + std::to_string(n) + " vertices declared, " +
               std::to_string(w.size() - 1) + " given",
           line_number);
    }
    std::vector<std::int32_t> ids(n);
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t id = count(w[k + 1], "vertex index");
      if (id >= nv) {
        fail(path,
             which + ": vertex index " + std::to_string(id) + " out of range (" +
                 std::to_string(nv) + " vertices, counted from 0)",
             line_number);
      }
      ids[k] = static_cast<std::int32_t>(id);
    }
    for (std::size_t k = 1; k + 1 < n; ++k) mesh.faces.push_back({ids[0], ids[k], ids[k + 1]});
  }
  return mesh;
}

// PLY, glTF/GLB and COLLADA through Assimp (mesh_import.h), in a child process, its error words
// naming the file and where Assimp found the fault.
TriangleMesh load_with_assimp(const std::string& path, const std::string& ext, MeshStats& s) {
  // The file must be what its extension says: Assimp, when the extension's reader refuses a file,
  // tries every other reader on its content (a ".gltf" holding an OFF text would be read as OFF).
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(path, "cannot open");
    std::string head(4096, '\0');
    in.read(&head[0], static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(in.gcount()));
    const std::size_t first = head.find_first_not_of(" \t\r\n");
    if (ext == "ply" && head.rfind("ply", 0) != 0) {
      fail(path, "not a PLY file (it does not start with 'ply')", 1);
    } else if (ext == "glb" && head.rfind("glTF", 0) != 0) {
      fail(path, "not a GLB file (it does not start with 'glTF')");
    } else if (ext == "gltf" && (first == std::string::npos || head[first] != '{')) {
      fail(path, "not a glTF file (a .gltf file is a JSON object, starting with '{')");
    } else if (ext == "dae" && head.find("<COLLADA") == std::string::npos) {
      fail(path, "not a COLLADA file (no <COLLADA> in its first 4096 bytes)");
    }
  }
  // What the file declares, checked where Assimp does not (mesh_declared.h).
  const DeclaredMesh declared = check_declared(path, ext);
  ImportedMesh imported = import_with_assimp(path, ext);
  if (imported.error.empty()) check_read_faces(path, declared, imported.read_faces);
  if (!imported.error.empty()) {
    std::string where;
    if (imported.error_mesh > 0) where = "mesh " + std::to_string(imported.error_mesh) + " ";
    if (imported.error_face > 0) where += "face " + std::to_string(imported.error_face) + " ";
    if (!where.empty()) where.back() = ':', where += ' ';
    fail(path, where + imported.error);
  }
  for (std::size_t i = 0; i < imported.mesh.vertices.size(); ++i) {
    check_vertex(path, "vertex " + std::to_string(i + 1), imported.mesh.vertices[i]);
  }
  s.parts = std::move(imported.parts);
  return std::move(imported.mesh);
}

TriangleMesh load_stl(const std::string& path, bool* ascii = nullptr) {
  constexpr std::uint64_t kHeaderBytes = 84;  // 80-byte header + uint32 triangle count
  constexpr std::uint64_t kRecordBytes = 50;  // normal, 3 vertices (12 floats), uint16 attribute
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open");
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                         std::istreambuf_iterator<char>());
  if (in.bad()) fail(path, "read error");

  // Size check; an ASCII STL begins with "solid" and (almost surely) fails it.
  const bool starts_solid = bytes.size() >= 5 && std::memcmp(bytes.data(), "solid", 5) == 0;
  if (bytes.size() < kHeaderBytes) {
    if (starts_solid) {
      if (ascii != nullptr) *ascii = true;
      return load_ascii_stl(path);
    }
    fail(path, "too short for a binary STL (" + std::to_string(bytes.size()) +
                   " bytes; header and count take 84)");
  }
  const std::uint64_t count = read_u32_le(bytes.data() + 80);
  const std::uint64_t expected = kHeaderBytes + kRecordBytes * count;
  if (bytes.size() != expected) {
    if (starts_solid) {
      if (ascii != nullptr) *ascii = true;
      return load_ascii_stl(path);
    }
    std::ostringstream out;
    out << "binary STL size mismatch: the header says " << count << " triangles (" << expected
        << " bytes) but the file has " << bytes.size() << " bytes";
    fail(path, out.str());
  }

  // Read the triangles; every face gets its own three vertices (load_mesh welds them).
  TriangleMesh mesh;
  mesh.faces.reserve(count);
  mesh.vertices.reserve(3 * count);
  for (std::uint64_t t = 0; t < count; ++t) {
    const unsigned char* record = bytes.data() + kHeaderBytes + kRecordBytes * t;
    std::array<std::int32_t, 3> face{};
    for (int k = 0; k < 3; ++k) {
      const unsigned char* p = record + 12 + 12 * k;  // skip the facet normal
      const Vec3 vertex(read_f32_le(p), read_f32_le(p + 4), read_f32_le(p + 8));
      check_vertex(path, "triangle " + std::to_string(t + 1) + " vertex " + std::to_string(k + 1),
                   vertex);
      face[k] = static_cast<std::int32_t>(mesh.vertices.size());
      mesh.vertices.push_back(vertex);
    }
    mesh.faces.push_back(face);
  }
  return mesh;
}

}  // namespace

TriangleMesh load_mesh(const std::string& path, MeshStats* stats) {
  require_readable(path);
  const std::string ext = lower_extension(path);
  TriangleMesh read;
  MeshStats local;
  MeshStats& s = stats != nullptr ? *stats : local;
  s = MeshStats{};
  if (ext == "obj") {
    read = load_obj(path, s.obj_objects);
    s.format = "OBJ";
  } else if (ext == "stl") {
    bool ascii = false;
    read = load_stl(path, &ascii);
    s.format = ascii ? "ASCII STL" : "binary STL";
  } else if (ext == "off") {
    read = load_off(path);
    s.format = "OFF";
  } else if (ext == "ply" || ext == "gltf" || ext == "glb" || ext == "dae") {
    read = load_with_assimp(path, ext, s);
    s.format = ext == "ply" ? "PLY" : ext == "dae" ? "COLLADA" : "glTF";
    s.in_metres = ext != "ply";
  } else {
    fail(path, "unknown mesh format (" + std::string(kMeshFormats) + ")");
  }
  if (read.faces.empty()) fail(path, "the mesh has no faces");

  // Hygiene (core/mesh_hygiene.h): weld equal vertices, drop zero-area faces.
  HygieneReport hygiene;
  TriangleMesh mesh = clean_mesh(read, &hygiene);
  if (mesh.faces.empty()) {
    fail(path, "every face has zero area (" + std::to_string(read.faces.size()) +
                   " faces, each a segment or a point)");
  }
  s.zero_area_faces = hygiene.dropped_faces.size();
  s.dropped_faces = std::move(hygiene.dropped_faces);
  s.source_face = std::move(hygiene.source_face);
  s.welded_vertices = hygiene.welded_vertices;
  s.file_vertices = hygiene.input_vertices;
  if (stats != nullptr) s.closedness = closedness(mesh);
  return mesh;
}

double signed_volume(const TriangleMesh& mesh) {
  double six_volume = 0;
  for (const auto& f : mesh.faces) {
    six_volume += mesh.vertices[f[0]].dot(mesh.vertices[f[1]].cross(mesh.vertices[f[2]]));
  }
  return six_volume / 6;
}

std::string turn_right_way_out(const std::string& path, const MeshStats& stats, TriangleMesh* mesh,
                               double unit) {
  if (!stats.closedness.closed()) return "";
  const double volume = signed_volume(*mesh);
  if (!(volume < 0)) return "";
  for (auto& f : mesh->faces) std::swap(f[1], f[2]);
  std::ostringstream out;
  out << path << ": the faces point inward (signed volume " << std::setprecision(3)
      << volume * unit * unit * unit << " m^3): flipped";
  return out.str();
}

void write_obj(const std::string& path, const TriangleMesh& mesh) {
  std::ofstream out(path, std::ios::binary);
  out << std::setprecision(17);
  for (const Vec3& v : mesh.vertices) out << "v " << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
  for (const auto& f : mesh.faces) {
    out << "f " << f[0] + 1 << ' ' << f[1] + 1 << ' ' << f[2] + 1 << '\n';
  }
  out.flush();
  if (!out) throw std::runtime_error("cannot write " + path);
}

void scale_mesh(const std::string& path, double scale, TriangleMesh* mesh) {
  if (scale == 1) return;
  std::ostringstream at;
  at << "at --scale " << scale << " vertex ";
  for (std::size_t i = 0; i < mesh->vertices.size(); ++i) {
    Vec3& v = mesh->vertices[i];
    v *= scale;
    check_vertex(path, at.str() + std::to_string(i + 1), v);
  }
}

void check_mesh_file(const std::string& path) {
  require_readable(path);
  const std::string ext = lower_extension(path);
  if (ext == "obj") {
    std::vector<std::string> objects;
    if (read_obj_vertex_lines(path, objects).empty()) fail(path, "no vertex in the OBJ file");
  } else if (ext == "stl") {
    bool ascii = false;
    const TriangleMesh stl = load_stl(path, &ascii);
    if (ascii) fail(path, "an ASCII STL, which MuJoCo 2.2 cannot read (it reads binary STL)");
    if (stl.faces.size() > kMujocoStlFaces) {
      fail(path, "a binary STL of " + std::to_string(stl.faces.size()) +
                     " triangles, which MuJoCo 2.2 cannot read (at most " +
                     std::to_string(kMujocoStlFaces) + " per STL file; an OBJ has no such limit)");
    }
  }
}

std::vector<std::string> mesh_warnings(const std::string& path, const MeshStats& stats,
                                       bool changes_only) {
  std::vector<std::string> out;
  const std::string head = path + ": ";
  if (stats.welded_vertices > 0 && !changes_only) {
    out.push_back(head + "welded " + std::to_string(stats.welded_vertices) +
                  " duplicate vertices (" + std::to_string(stats.file_vertices) + " in the file, " +
                  std::to_string(stats.file_vertices - stats.welded_vertices) + " distinct)");
  }
  if (!stats.dropped_faces.empty()) {
    std::string ids;
    const std::size_t shown = std::min<std::size_t>(stats.dropped_faces.size(), 5);
    for (std::size_t i = 0; i < shown; ++i) {
      ids += (i ? ", " : "") + std::to_string(stats.dropped_faces[i] + 1);
    }
    if (shown < stats.dropped_faces.size()) ids += ", ...";
    out.push_back(head + "dropped " + std::to_string(stats.dropped_faces.size()) +
                  " zero-area faces (faces " + ids +
                  " counted from 1 in the file's order; each spans a segment or a point)");
  }
  if (stats.closedness.faces > 0 && !stats.closedness.closed() && !changes_only) {
    out.push_back(head + "the mesh is " + stats.closedness.describe() +
                  "; containment inside it cannot be checked (surface contacts only)");
  }
  if (stats.obj_objects.size() > 1) {
    std::string names;
    for (std::size_t i = 0; i < stats.obj_objects.size() && i < 5; ++i) {
      names += (i ? ", '" : "'") + stats.obj_objects[i] + "'";
    }
    if (stats.obj_objects.size() > 5) names += ", ...";
    out.push_back(head + std::to_string(stats.obj_objects.size()) + " objects (" + names +
                  "): graspcd reads them all, but MuJoCo 2.2 keeps only the first ('" +
                  stats.obj_objects[0] + "'); merge them into one object for a scene");
  }
  return out;
}

}  // namespace graspcd::io
