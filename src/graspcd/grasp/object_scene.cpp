#include "graspcd/grasp/object_scene.h"

#include <stdlib.h>
#include <tinyxml2.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "graspcd/core/geometry.h"
#include "graspcd/grasp/drive_config.h"
#include "graspcd/io/mesh_io.h"
#include "graspcd/io/output_files.h"
#include "graspcd/io/text_input.h"
#include "graspcd/io/warnings.h"

namespace graspcd::grasp {

namespace {

namespace fs = std::filesystem;

// At least this many contacts and constraint rows (a fine mesh's contacts; example 1 has 300).
constexpr int kMinNconmax = 1000;
constexpr int kMinNjmax = 4000;
// A placed object wider than this (m) is most likely in other units than metres: warned about.
constexpr double kLargeObject = 1.0;

std::string number(double v) {
  std::ostringstream out;
  out << std::setprecision(17) << v + 0.0;  // + 0.0: -0 prints as 0
  return out.str();
}

// For people (the header): 6 significant digits.
std::string short_number(double v) {
  std::ostringstream out;
  out << std::setprecision(6) << v + 0.0;
  return out.str();
}

std::string numbers(const double* v, int n) {
  std::string out;
  for (int i = 0; i < n; ++i) out += (i ? " " : "") + number(v[i]);
  return out;
}

// The numbers of an attribute ("1 2 3"); an error naming the template's line when there are not
// `n` finite ones.
std::vector<double> read_numbers(const tinyxml2::XMLElement* e, const char* attribute,
                                 std::size_t n, const std::string& path) {
  std::istringstream words(e->Attribute(attribute));
  std::vector<double> out;
  for (double x; words >> x;) out.push_back(x);
  if (out.size() != n || !words.eof() ||
      !std::all_of(out.begin(), out.end(), [](double x) { return std::isfinite(x); })) {
    throw io::InputError(path, static_cast<std::size_t>(e->GetLineNum()),
                         std::string("<") + e->Name() + " " + attribute + "> must hold " +
                             std::to_string(n) + " finite numbers");
  }
  return out;
}

// Every element below `e` (depth first) whose name is `name`.
void collect(tinyxml2::XMLElement* e, const char* name, std::vector<tinyxml2::XMLElement*>& out) {
  for (tinyxml2::XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    if (std::string(c->Name()) == name) out.push_back(c);
    collect(c, name, out);
  }
}

Vec3 axis_of(const std::string& up) {
  static const char* kNames[] = {"x", "y", "z", "-x", "-y", "-z", "+x", "+y", "+z"};
  for (int i = 0; i < 9; ++i) {
    if (up != kNames[i]) continue;
    Vec3 a = Vec3::Zero();
    a[i % 3] = (i >= 3 && i < 6) ? -1 : 1;
    return a;
  }
  throw std::invalid_argument("--up must be one of x, y, z, -x, -y, -z (not '" + up + "')");
}

// `target` relative to `from` (both made absolute and normal): the path a scene in `from` names.
std::string relative_to(const fs::path& target, const fs::path& from) {
  const fs::path rel = fs::absolute(target).lexically_normal().lexically_relative(
      fs::absolute(from).lexically_normal());
  return rel.empty() ? fs::absolute(target).lexically_normal().string() : rel.generic_string();
}

// The template scene's error at element `at` (its line; 0 without one).
io::InputError template_error(const std::string& template_path, const tinyxml2::XMLElement* at,
                              const std::string& what) {
  return io::InputError(template_path, at ? static_cast<std::size_t>(at->GetLineNum()) : 0,
                        "template scene: " + what);
}

// The user's mesh as graspcd reads it (an error names the file), its hygiene warnings added: its
// extent places and fits it.
TriangleMesh read_object_mesh(const std::string& file, io::MeshStats* stats) {
  TriangleMesh mesh = io::load_mesh(file, stats);
  for (const std::string& w : io::mesh_warnings(file, *stats, true)) {
    warnings().add("mesh_hygiene", w, "mesh");
  }
  return mesh;
}

// The first <keyframe> of the files `e` includes (<include file>, read as MuJoCo 2.2 reads it:
// relative to the main file's folder `main_dir`, its children taking the include's place), and
// of the files those include, `depth` deep at most; the file that holds it is `file`. An include
// that cannot be read is left to MuJoCo, whose error names it; one that is no regular file (a
// FIFO) is refused here, before anything opens it.
const tinyxml2::XMLElement* included_keyframe(
    const tinyxml2::XMLElement* e, const fs::path& main_dir, int depth,
    std::vector<std::unique_ptr<tinyxml2::XMLDocument>>& docs, std::string& file) {
  constexpr int kMaxIncludeDepth = 16;
  for (const tinyxml2::XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const char* name = c->Attribute("file");
    if (std::string(c->Name()) == "include" && name != nullptr && depth < kMaxIncludeDepth) {
      const std::string path = (main_dir / name).string();
      std::error_code ec;
      if (!fs::exists(path, ec)) continue;
      io::require_regular_file(path);
      docs.push_back(std::make_unique<tinyxml2::XMLDocument>());
      tinyxml2::XMLDocument& doc = *docs.back();
      if (doc.LoadFile(path.c_str()) != tinyxml2::XML_SUCCESS || doc.RootElement() == nullptr) {
        continue;
      }
      std::vector<tinyxml2::XMLElement*> keys;
      collect(doc.RootElement(), "keyframe", keys);
      if (!keys.empty()) {
        file = path;
        return keys.front();
      }
      if (const tinyxml2::XMLElement* key =
              included_keyframe(doc.RootElement(), main_dir, depth + 1, docs, file)) {
        return key;
      }
      continue;
    }
    if (const tinyxml2::XMLElement* key = included_keyframe(c, main_dir, depth, docs, file)) {
      return key;
    }
  }
  return nullptr;
}

// What of the template the object scene changes, in `doc`.
struct TemplateParts {
  tinyxml2::XMLElement* root = nullptr;   // <mujoco>
  tinyxml2::XMLElement* body = nullptr;   // the <body name="object"> of <worldbody>
  tinyxml2::XMLElement* geom = nullptr;   // its one mesh geom
  tinyxml2::XMLElement* asset = nullptr;  // that geom's <mesh>
};

int line_of(const tinyxml2::XMLElement* e) { return e ? e->GetLineNum() : 0; }

// Whether the body has a free joint (<freejoint/> or <joint type="free"/>).
bool has_free_joint(const tinyxml2::XMLElement* body) {
  if (body->FirstChildElement("freejoint")) return true;
  for (const tinyxml2::XMLElement* j = body->FirstChildElement("joint"); j;
       j = j->NextSiblingElement("joint")) {
    if (j->Attribute("type", "free")) return true;
  }
  return false;
}

// The parts of a template read into `doc`, each piece of the contract it lacks added to
// `problems` (in the order they are met; a part that cannot be found stops the search below it).
TemplateParts find_template_parts(tinyxml2::XMLDocument& doc, const std::string& template_path,
                                  std::vector<TemplateProblem>& problems) {
  const auto lacks = [&](const tinyxml2::XMLElement* at, const std::string& what,
                         const std::string& how) {
    problems.push_back({static_cast<std::size_t>(std::max(0, line_of(at))), what, how, {}});
  };
  TemplateParts t;
  t.root = doc.RootElement();
  if (t.root == nullptr || std::string(t.root->Name()) != "mujoco") {
    lacks(t.root, "no <mujoco>", "a template is an MJCF scene: <mujoco> ... </mujoco>");
    return t;
  }
  // A keyframe is the grasp's start (grasp.h) and holds the template object's pose, which the new
  // object's placement would not replace, in the template or in a file it includes.
  constexpr const char* kKeyframe =
      "a template with a <keyframe> cannot take a new object (the keyframe starts the grasp with "
      "the template object's pose)";
  constexpr const char* kNoKeyframe =
      "remove the <keyframe>: the grasp starts from qpos0 and the drive's closing shapes the hand";
  if (tinyxml2::XMLElement* key = t.root->FirstChildElement("keyframe")) {
    lacks(key, kKeyframe, kNoKeyframe);
  }
  std::vector<std::unique_ptr<tinyxml2::XMLDocument>> included;
  std::string holder;
  if (const tinyxml2::XMLElement* key =
          included_keyframe(t.root, fs::path(template_path).parent_path(), 0, included, holder)) {
    problems.push_back({static_cast<std::size_t>(std::max(0, key->GetLineNum())),
                        "template scene (included by " + template_path + "): " + kKeyframe,
                        kNoKeyframe, holder});
  }
  tinyxml2::XMLElement* world = t.root->FirstChildElement("worldbody");
  for (tinyxml2::XMLElement* world_element = world; world_element;
       world_element = world_element->NextSiblingElement("worldbody")) {
    for (tinyxml2::XMLElement* b = world_element->FirstChildElement("body"); b;
         b = b->NextSiblingElement("body")) {
      if (b->Attribute("name", "object")) t.body = b;
    }
  }
  if (t.body == nullptr) {
    lacks(world, "no <body name=\"object\"> in <worldbody>",
          "add <body name=\"object\" pos=\"X Y Z\"><freejoint/><geom type=\"mesh\" "
          "mesh=\"object_mesh\"/></body> to <worldbody> and <mesh name=\"object_mesh\" "
          "file=\"ANY.obj\"/> to <asset> (the user's mesh takes its place; X Y Z: where it "
          "stands, or a graspcd_support numeric)");
    return t;
  }
  if (!has_free_joint(t.body)) {
    lacks(t.body, "the object body has no free joint",
          "add <freejoint/> to the object body: the object settles on the support and is lifted "
          "by the hand");
  }
  for (tinyxml2::XMLElement* g = t.body->FirstChildElement("geom"); g;
       g = g->NextSiblingElement("geom")) {
    if (g->Attribute("type", "mesh") && g->Attribute("mesh")) {
      if (t.geom != nullptr) {
        lacks(g, "the object body has more than one mesh geom",
              "keep one mesh geom in the object body: the user's mesh replaces that one");
        return t;
      }
      t.geom = g;
    }
  }
  if (t.geom == nullptr) {
    lacks(t.body, "the object body has no mesh geom",
          "give the object body one <geom type=\"mesh\" mesh=\"object_mesh\"/> (with its "
          "mass or density, friction and contype) and <mesh name=\"object_mesh\" "
          "file=\"ANY.obj\"/> in <asset>: the user's mesh takes its place");
    return t;
  }
  std::vector<tinyxml2::XMLElement*> meshes;
  collect(t.root, "mesh", meshes);
  for (tinyxml2::XMLElement* m : meshes) {
    if (m->Attribute("name", t.geom->Attribute("mesh"))) t.asset = m;
  }
  if (t.asset == nullptr) {
    lacks(t.geom, "no <mesh> asset for the object's geom",
          std::string("add <mesh name=\"") + t.geom->Attribute("mesh") +
              "\" file=\"ANY.obj\"/> to <asset>");
  }
  return t;
}

// The template read into `doc` by tinyxml2 and its parts found; an error names what is missing
// (the first piece of the contract it lacks).
TemplateParts read_template(tinyxml2::XMLDocument& doc, const std::string& template_path) {
  if (doc.LoadFile(template_path.c_str()) != tinyxml2::XML_SUCCESS) {
    throw io::InputError(template_path, static_cast<std::size_t>(std::max(0, doc.ErrorLineNum())),
                         std::string("cannot read the template scene: ") + doc.ErrorName());
  }
  std::vector<TemplateProblem> problems;
  const TemplateParts t = find_template_parts(doc, template_path, problems);
  if (!problems.empty()) {
    const TemplateProblem& p = problems.front();
    if (!p.file.empty()) throw io::InputError(p.file, p.line, p.what);
    throw io::InputError(template_path, p.line, "template scene: " + p.what);
  }
  return t;
}

// The placement's frame: up against gravity (the main file's <option>, else MuJoCo's default),
// e1 and e2 across it.
struct GravityFrame {
  Vec3 up;
  Vec3 e1;
  Vec3 e2;
};

GravityFrame gravity_frame(tinyxml2::XMLElement* root, const std::string& template_path) {
  Vec3 gravity(0, 0, -9.81);
  for (tinyxml2::XMLElement* o = root->FirstChildElement("option"); o;
       o = o->NextSiblingElement("option")) {
    if (o->Attribute("gravity")) {
      const std::vector<double> g = read_numbers(o, "gravity", 3, template_path);
      gravity = Vec3(g[0], g[1], g[2]);
    }
  }
  if (gravity.norm() == 0) {
    throw template_error(template_path, root, "gravity is zero: no up to place the object by");
  }
  GravityFrame f;
  f.up = -gravity.normalized();
  // Across gravity: the world x axis made perpendicular to up (y when up is near x), then up x e1.
  const Vec3 across = std::abs(f.up.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  f.e1 = (across - across.dot(f.up) * f.up).normalized();
  f.e2 = f.up.cross(f.e1);
  return f;
}

// The template's support point and room for the object (graspcd_support, graspcd_fit), and how
// far above the support the hand reaches down (graspcd_reach, with its element for messages).
struct TemplateRoom {
  Vec3 support = Vec3::Zero();
  std::optional<std::array<double, 2>> fit;
  std::optional<double> reach;
  const tinyxml2::XMLElement* reach_at = nullptr;
};

TemplateRoom template_room(const TemplateParts& t,
                           const std::optional<std::array<double, 2>>& default_fit,
                           const std::string& template_path) {
  TemplateRoom room;
  if (t.body->Attribute("pos")) {
    const std::vector<double> p = read_numbers(t.body, "pos", 3, template_path);
    room.support = Vec3(p[0], p[1], p[2]);
  }
  room.fit = default_fit;
  std::vector<tinyxml2::XMLElement*> numerics;
  collect(t.root, "numeric", numerics);
  for (tinyxml2::XMLElement* n : numerics) {
    if (n->Attribute("name", "graspcd_support")) {
      const std::vector<double> p = read_numbers(n, "data", 3, template_path);
      room.support = Vec3(p[0], p[1], p[2]);
    } else if (n->Attribute("name", "graspcd_fit")) {
      const std::vector<double> p = read_numbers(n, "data", 2, template_path);
      room.fit = std::array<double, 2>{p[0], p[1]};
    } else if (n->Attribute("name", "graspcd_reach")) {
      const std::vector<double> p = read_numbers(n, "data", 1, template_path);
      if (!(p[0] > 0)) throw template_error(template_path, n, "graspcd_reach must be > 0");
      room.reach = p[0];
      room.reach_at = n;
    }
  }
  return room;
}

// The rotation: the file's up axis along `up`, then the yaw about it; or the given quaternion.
Eigen::Quaterniond object_rotation(const ObjectPlacement& placement, const Vec3& up) {
  Eigen::Quaterniond q;
  if (placement.pose) {
    const auto& w = *placement.pose;
    q = Eigen::Quaterniond(w[0], w[1], w[2], w[3]);
    if (!(q.norm() > 0)) throw std::invalid_argument("--pose: the quaternion is zero");
    q.normalize();
  } else {
    const Eigen::Quaterniond tilt = Eigen::Quaterniond::FromTwoVectors(axis_of(placement.up), up);
    const Eigen::Quaterniond yaw(Eigen::AngleAxisd(placement.yaw_degrees * M_PI / 180.0, up));
    q = yaw * tilt;
  }
  return q;
}

// What the object's size (its largest extent, m, at `scale`) says about the file's units, when it
// is larger than kLargeObject: a hint for the user ("" otherwise), worded in the scale given.
// A file of a format without a unit (OBJ, STL, OFF, PLY) is most likely in millimetres when the
// object comes out more than 10 m across at scale 1, in centimetres when 1 to 10 m; a glTF or
// COLLADA file is in metres (by definition, or by its <unit>), said as such.
std::string units_hint(double size, double scale, bool fitted, const io::MeshStats& stats) {
  if (!(size > kLargeObject) || fitted) return "";
  std::ostringstream w;
  w << std::setprecision(3) << "the object is " << size << " m across at --scale "
    << std::setprecision(6) << scale << ": ";
  if (stats.in_metres) {
    w << "the " << stats.format << " file says metres; if it was modelled in other units, give "
      << "--scale (0.001 for millimetres)";
    return w.str();
  }
  const double file_size = size / scale;  // in file units
  const bool mm = file_size > 10 * kLargeObject;
  w << "is the file in "
    << (mm ? "millimetres? try --scale 0.001" : "centimetres? try --scale 0.01");
  return w.str();
}

// What a refused start adds about the object's size (an object too large for the hand reads as a
// finger or the palm penetrating it): its extent across and along gravity against the template's
// room (graspcd_fit) and what to try: --fit (with the scale it gives), an --up under which the
// file's box fits the room, or, for an object already within the room, another turn. "" without
// a room.
std::string size_hint(const TriangleMesh& mesh, const ObjectPlacement& placement,
                      const Vec3& extent, double scale, const TemplateRoom& room,
                      double fit_fraction, const std::string& hand) {
  if (!room.fit) return "";
  const double room_width = (*room.fit)[0], room_height = (*room.fit)[1];
  const Vec3 size = scale * extent;
  std::ostringstream out;
  out << std::setprecision(3) << "the object is " << size[0] << " x " << size[1] << " x " << size[2]
      << " m (across, across, up), " << hand << "room " << room_width << " across and "
      << room_height << " up";
  if (placement.fit) {
    out << ": fitted to it; turn it (--up, --yaw) or pick another hand";
    return out.str();
  }
  const double width = std::max(size[0], size[1]);
  const bool wide = width > room_width, tall = size[2] > room_height;
  if (!wide && !tall) {
    out << ": it fits; turn it (--up, --yaw) or pick another hand";
    return out.str();
  }
  out << ": too "
      << (wide && tall ? "large"
          : wide       ? "wide"
                       : "tall")
      << "; try --fit (scale " << std::setprecision(4)
      << fit_fraction *
             std::min(room_width / std::max(extent[0], extent[1]), room_height / extent[2])
      << ")";
  // The file's box at this scale, each axis up in turn (no yaw).
  Vec3 lo = mesh.vertices.front(), hi = lo;
  for (const Vec3& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const Vec3 box = scale * (hi - lo);
  static const char* kAxes[] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    const std::string axis = kAxes[a];
    if (placement.up == axis || placement.up == "-" + axis || placement.up == "+" + axis) continue;
    const double across = std::max(box[(a + 1) % 3], box[(a + 2) % 3]);
    if (across <= room_width && box[a] <= room_height) {
      out << std::setprecision(3) << " or --up " << axis << " (" << across << " across, " << box[a]
          << " up)";
      break;
    }
  }
  return out.str();
}

// The object turned, scaled (given or fitted to the room) and placed: its lowest point
// kSupportGap above the support point, centred on it across gravity. Warns when it comes out
// larger than kLargeObject. The scene and pairs paths are left empty.
ObjectScene place_object(const TriangleMesh& mesh, const ObjectPlacement& placement,
                         double fit_fraction, const GravityFrame& f, const TemplateRoom& room,
                         const TemplateParts& t, const std::string& template_path,
                         const io::MeshStats& stats, const std::string& hand) {
  const Eigen::Quaterniond q = object_rotation(placement, f.up);
  const Mat3 R = q.toRotationMatrix();
  // The turned mesh's extent in (e1, e2, up), unscaled.
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -lo;
  for (const Vec3& v : mesh.vertices) {
    const Vec3 w = R * v;
    const Vec3 c(w.dot(f.e1), w.dot(f.e2), w.dot(f.up));
    lo = lo.cwiseMin(c);
    hi = hi.cwiseMax(c);
  }
  const Vec3 extent = hi - lo;
  ObjectScene out;
  out.fitted = placement.fit;
  out.scale = placement.scale;
  if (placement.fit) {
    if (!room.fit) {
      throw template_error(template_path, t.root,
                           "no <numeric name=\"graspcd_fit\" data=\"WIDTH HEIGHT\"/> for --fit");
    }
    const double width = std::max(extent[0], extent[1]);
    out.scale = std::numeric_limits<double>::infinity();
    if (width > 0) out.scale = (*room.fit)[0] / width;
    if (extent[2] > 0) out.scale = std::min(out.scale, (*room.fit)[1] / extent[2]);
    out.scale *= fit_fraction;
  }
  const double s = out.scale;
  out.size = {s * extent[0], s * extent[1], s * extent[2]};
  out.units_hint =
      units_hint(std::max({out.size[0], out.size[1], out.size[2]}), s, placement.fit, stats);
  if (!out.units_hint.empty()) {
    warnings().add("mesh_units", placement.file + ": " + out.units_hint, "mesh");
  } else {
    out.size_hint = size_hint(mesh, placement, extent, s, room, fit_fraction, hand);
  }
  const Vec3 centre = 0.5 * s * (lo + hi);
  const Vec3 pos = room.support + (kSupportGap - s * lo[2]) * f.up +
                   (placement.offset[0] - centre[0]) * f.e1 +
                   (placement.offset[1] - centre[1]) * f.e2;
  out.pos = {pos.x(), pos.y(), pos.z()};
  out.quat = {q.w(), q.x(), q.y(), q.z()};
  return out;
}

// graspcd_reach: an object shorter than the reach (along gravity) would stand below what the hand
// reaches, so its support, the body the pair config's grasp section names "support" (one of
// <worldbody>'s), is raised by the difference, and the object with it. `support` is the support
// point, raised too.
void raise_to_reach(const TemplateParts& t, const TemplateRoom& room, const GravityFrame& f,
                    const HandTemplate& hand, const std::string& template_path, ObjectScene& out,
                    Vec3& support) {
  if (!room.reach || !(out.size[2] < *room.reach)) return;
  std::optional<DriveConfig> drive;
  try {
    drive = load_drive_config(hand.pairs());
  } catch (const std::runtime_error&) {
    drive.reset();  // the grasp names the pair config's fault
  }
  tinyxml2::XMLElement* body = nullptr;
  for (tinyxml2::XMLElement* w = t.root->FirstChildElement("worldbody"); w && drive;
       w = w->NextSiblingElement("worldbody")) {
    for (tinyxml2::XMLElement* b = w->FirstChildElement("body"); b;
         b = b->NextSiblingElement("body")) {
      if (!drive->support.empty() && b->Attribute("name", drive->support.c_str())) body = b;
    }
  }
  if (body == nullptr) {
    throw template_error(template_path, room.reach_at,
                         "graspcd_reach raises the support body, the \"support\" of the pair "
                         "config's \"grasp\" section, which must be a body of <worldbody>");
  }
  const double raise = *room.reach - out.size[2];
  Vec3 pos = Vec3::Zero();
  if (body->Attribute("pos")) {
    const std::vector<double> p = read_numbers(body, "pos", 3, template_path);
    pos = Vec3(p[0], p[1], p[2]);
  }
  pos += raise * f.up;
  body->SetAttribute("pos", numbers(pos.data(), 3).c_str());
  for (std::size_t i = 0; i < 3; ++i) out.pos[i] += raise * f.up[static_cast<Eigen::Index>(i)];
  support += raise * f.up;
  out.support_raised = raise;
}

// Every file path of the template made absolute (the hand stays where it is installed or shared):
// <include file>, <compiler texturedir>, the asset files but the object's when no meshdir is set.
// A meshdir (or assetdir) becomes the folder `meshes` beside the scene, which holds a link
// (absolute) to every file of the template's mesh folder, so that the hand's meshes load from
// there and the object's mesh, copied into it, is named relative to the scene. Returns the folder
// the object's mesh file is named relative to (`target` or `meshes`).
fs::path rewrite_paths(const TemplateParts& t, const std::string& template_path,
                       const fs::path& target, const fs::path& meshes,
                       const std::vector<TemplatePath>& moved) {
  const fs::path template_dir = fs::absolute(template_path).parent_path();
  // A path as the template writes it, made a file: beside the template, or under a moved folder,
  // that folder's links resolved (the scene names files by relative paths, and a ".." after a
  // link leaves the link's target, not the link's folder).
  const auto resolved = [&](const std::string& path) {
    for (const TemplatePath& m : moved) {
      if (path.compare(0, m.from.size(), m.from) == 0) {
        std::error_code ec;
        const fs::path to = fs::weakly_canonical(m.to, ec);
        return ((ec ? fs::path(m.to) : to) / path.substr(m.from.size())).lexically_normal();
      }
    }
    return (template_dir / path).lexically_normal();
  };
  std::vector<tinyxml2::XMLElement*> compilers;
  collect(t.root, "compiler", compilers);
  std::string meshdir;  // the main file's last meshdir (or assetdir), as the template wrote it
  for (tinyxml2::XMLElement* c : compilers) {
    for (const char* a : {"meshdir", "texturedir", "assetdir"}) {
      if (!c->Attribute(a)) continue;
      if (std::string(a) != "texturedir") meshdir = c->Attribute(a);
      c->SetAttribute(a, resolved(c->Attribute(a)).string().c_str());
    }
    if (c->Attribute("assetdir")) {
      if (!c->Attribute("texturedir")) c->SetAttribute("texturedir", c->Attribute("assetdir"));
      c->DeleteAttribute("assetdir");
      c->SetAttribute("meshdir", "");
    }
  }
  // MuJoCo 2.2 reads an <include file> relative to the scene's folder even when it is absolute:
  // the included file is linked into `meshes` and named there.
  fs::create_directories(meshes);
  std::vector<tinyxml2::XMLElement*> includes;
  collect(t.root, "include", includes);
  for (tinyxml2::XMLElement* inc : includes) {
    if (!inc->Attribute("file")) continue;
    const fs::path file = resolved(inc->Attribute("file"));
    const fs::path link = meshes / file.filename();
    std::error_code ec;
    fs::create_symlink(file, link, ec);
    if (ec) throw io::InputError(link.string(), 0, "cannot link the hand's file: " + ec.message());
    inc->SetAttribute("file", relative_to(link, target).c_str());
  }
  if (meshdir.empty()) {
    for (const char* kind : {"mesh", "texture", "hfield", "skin"}) {
      std::vector<tinyxml2::XMLElement*> files;
      collect(t.root, kind, files);
      for (tinyxml2::XMLElement* f : files) {
        if (f->Attribute("file") && f != t.asset) {
          f->SetAttribute("file", resolved(f->Attribute("file")).string().c_str());
        }
      }
    }
    return target;
  }
  // The hand's mesh folder linked file by file into `meshes`, named relative to the scene.
  const fs::path hand_meshes = resolved(meshdir);
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(hand_meshes, ec)) {
    fs::create_symlink(e.path(), meshes / e.path().filename(), ec);
    if (ec)
      throw io::InputError(meshes.string(), 0, "cannot link the hand's meshes: " + ec.message());
  }
  if (ec) {
    throw io::InputError(hand_meshes.string(), 0, "cannot read the hand's meshes: " + ec.message());
  }
  for (tinyxml2::XMLElement* c : compilers) {
    if (c->Attribute("meshdir")) {
      c->SetAttribute("meshdir", (meshes.filename().string() + "/").c_str());
    }
  }
  return meshes;
}

// The object in the template: its mesh (`file`, named relative to `mesh_folder`), scale, place
// and turn; the template's names (the cup, the mug, the glass) would mislead, so the object's geom
// and mesh are named after what they are.
void set_object(const TemplateParts& t, const std::string& file, const fs::path& mesh_folder,
                const ObjectScene& out) {
  for (const char* a : {"refpos", "refquat", "scale", "file", "vertex", "face", "normal"}) {
    t.asset->DeleteAttribute(a);
  }
  t.asset->SetAttribute("name", "object_mesh");
  t.geom->SetAttribute("mesh", "object_mesh");
  t.geom->SetAttribute("name", "object");
  t.asset->SetAttribute("file", relative_to(file, mesh_folder).c_str());
  const double scale3[3] = {out.scale, out.scale, out.scale};
  t.asset->SetAttribute("scale", numbers(scale3, 3).c_str());
  for (const char* a : {"quat", "axisangle", "xyaxes", "zaxis", "euler"}) {
    t.body->DeleteAttribute(a);
  }
  t.body->SetAttribute("pos", numbers(out.pos.data(), 3).c_str());
  t.body->SetAttribute("quat", numbers(out.quat.data(), 4).c_str());
  for (const char* a : {"pos", "quat", "axisangle", "xyaxes", "zaxis", "euler"}) {
    t.geom->DeleteAttribute(a);
  }
}

// Room for the contacts of a fine mesh: <size nconmax njmax> at least kMinNconmax, kMinNjmax.
void raise_size(tinyxml2::XMLDocument& doc, tinyxml2::XMLElement* root) {
  tinyxml2::XMLElement* size = root->FirstChildElement("size");
  if (size == nullptr) {
    size = doc.NewElement("size");
    root->InsertFirstChild(size);
  }
  size->SetAttribute("nconmax", std::max(kMinNconmax, size->IntAttribute("nconmax")));
  size->SetAttribute("njmax", std::max(kMinNjmax, size->IntAttribute("njmax")));
}

// The header of the new scene: what it is and how it was made.
std::string scene_header(const HandTemplate& hand, const ObjectPlacement& placement,
                         const ObjectScene& out, const Vec3& support, const std::string& stem) {
  std::ostringstream header;
  header << "\n  Generated by graspcd (the grasp command given an object file) from ";
  if (hand.drive.empty()) {
    header << "the template " << fs::absolute(hand.scene).lexically_normal().string()
           << " (hand: " << hand.name << ")";
  } else {  // a hand file wrapped with its drive (hand_wrapper.h)
    header << "the hand file " << fs::absolute(hand.name).lexically_normal().string()
           << "\n  with the drive " << fs::absolute(hand.drive).lexically_normal().string();
  }
  header << ".\n  Object: " << fs::absolute(placement.file).lexically_normal().string()
         << "\n    scale " << short_number(out.scale)
         << (out.fitted ? " (fitted to the hand's room)" : " (given)") << "; size "
         << short_number(out.size[0]) << " x " << short_number(out.size[1]) << " m across, "
         << short_number(out.size[2]) << " m tall;\n    ";
  if (placement.pose) {
    header << "rotation (quaternion w x y z) " << numbers(out.quat.data(), 4);
  } else {
    header << "file axis " << placement.up << " up, turned " << short_number(placement.yaw_degrees)
           << " degrees about it";
  }
  header << ";\n    its lowest point " << short_number(kSupportGap)
         << " m above the support point (" << numbers(support.data(), 3) << "), centred on it";
  if (placement.offset[0] != 0 || placement.offset[1] != 0) {
    header << " moved " << short_number(placement.offset[0]) << ", "
           << short_number(placement.offset[1]) << " m";
  }
  header << " across gravity";
  if (out.support_raised > 0) {
    header << ";\n    the support raised " << short_number(out.support_raised)
           << " m toward the hand, whose reach (graspcd_reach) the object is shorter than";
  }
  header << ".\n"
         << "  The object's mesh is in " << stem
         << ".meshes/ beside this file (with links to the hand's meshes when the hand has a mesh\n"
            "  folder); the hand's files are named by absolute paths. The folder can be moved or "
            "copied\n  (cp -r) and loads as long as the hand stays where it is. Pairs and the "
            "drive: "
         << stem << ".pairs.json beside it.\n  Edit freely: graspcd grasp on this file reruns "
         << "the grasp.\n  " << kGeneratedMarker
         << " (the write-scene option of graspcd grasp replaces this file, its .pairs.json and "
            "its .meshes folder).\n";
  return header.str();
}

// The template's comments (its own header) replaced by `header`.
void replace_comments(tinyxml2::XMLDocument& doc, tinyxml2::XMLElement* root,
                      const std::string& header) {
  for (tinyxml2::XMLNode* n = doc.FirstChild(); n;) {
    tinyxml2::XMLNode* next = n->NextSibling();
    if (n->ToComment()) doc.DeleteNode(n);
    n = next;
  }
  for (tinyxml2::XMLNode* n = root->FirstChild(); n;) {
    tinyxml2::XMLNode* next = n->NextSibling();
    if (n->ToComment()) root->DeleteChild(n);
    n = next;
  }
  root->InsertFirstChild(doc.NewComment(header.c_str()));
}

// The name of the support body the object stands on when graspcd can serve its pair with the
// object (docs/objects.md, "The object and its support"): the pair config's "grasp" section names
// it, no pair of the config names it, and its geoms (one or more, direct children of the body)
// are all boxes or meshes. Empty otherwise (the project hand's floor is a plane MuJoCo collides).
std::string servable_support(const tinyxml2::XMLElement* root,
                             const nlohmann::ordered_json& config) {
  if (!config.is_object() || !config.contains("grasp") || !config["grasp"].is_object()) return {};
  const nlohmann::ordered_json& grasp = config["grasp"];
  if (!grasp.contains("support") || !grasp["support"].is_string()) return {};
  const std::string support = grasp["support"].get<std::string>();
  if (config.contains("pairs") && config["pairs"].is_array()) {
    for (const nlohmann::ordered_json& p : config["pairs"]) {
      for (const char* side : {"a", "b"}) {
        if (p.is_object() && p.contains(side) && p[side] == "body:" + support) return {};
      }
    }
  }
  const tinyxml2::XMLElement* body = nullptr;
  for (const tinyxml2::XMLElement* w = root->FirstChildElement("worldbody"); w;
       w = w->NextSiblingElement("worldbody")) {
    for (const tinyxml2::XMLElement* b = w->FirstChildElement("body"); b;
         b = b->NextSiblingElement("body")) {
      if (b->Attribute("name", support.c_str())) body = b;
    }
  }
  if (body == nullptr || body->FirstChildElement("geom") == nullptr) return {};
  for (const tinyxml2::XMLElement* g = body->FirstChildElement("geom"); g;
       g = g->NextSiblingElement("geom")) {
    if (!g->Attribute("type", "box") && !g->Attribute("type", "mesh")) return {};
  }
  return support;
}

// The scene written as out.scene and the template's pair config copied to out.pairs: unchanged
// (it names body:object), or, where graspcd can serve the object's pair with its support
// (servable_support), with that pair added. MuJoCo 2.2 gives a convex pair one contact, so an
// object lying on a box sinks into it: a YCB soup can on its side in the Robotiq sank 4.1 mm
// and tilted 11 deg (2.3 mm with multiccd); served, 0.7 mm, for 14% more time per physics step.
void save_scene(tinyxml2::XMLDocument& doc, const std::string& template_path,
                const ObjectScene& out) {
  if (doc.SaveFile(out.scene.c_str()) != tinyxml2::XML_SUCCESS) {
    throw io::InputError(out.scene, 0, "cannot write the scene");
  }
  const std::string pairs = fs::path(template_path).replace_extension(".pairs.json").string();
  std::ifstream in(pairs, std::ios::binary);
  if (!in) throw io::InputError(pairs, 0, "cannot read the template's pair config");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // A config that does not parse is copied as it is: the grasp names its fault in the template's.
  // Its keys keep their order.
  nlohmann::ordered_json config = nlohmann::ordered_json::parse(text, nullptr, false);
  const std::string support =
      config.is_discarded() ? std::string() : servable_support(doc.RootElement(), config);
  std::ofstream written(out.pairs, std::ios::binary);
  if (support.empty() || !config.contains("pairs") || !config["pairs"].is_array()) {
    written << text;
  } else {
    config["pairs"].push_back({{"a", "body:object"}, {"b", "body:" + support}});
    written << config.dump(2) << '\n';
  }
  if (!written) throw io::InputError(out.pairs, 0, "cannot write the pair config");
}

// Whether MuJoCo 2.2's mesh compiler accepts the faces' orientation: no directed edge is used by
// two faces (its "faces have inconsistent orientation" otherwise).
bool orientation_consistent(const TriangleMesh& mesh) {
  std::vector<std::pair<std::int32_t, std::int32_t>> edges;
  edges.reserve(3 * mesh.faces.size());
  for (const auto& f : mesh.faces) {
    for (std::size_t k = 0; k < 3; ++k) edges.emplace_back(f[k], f[(k + 1) % 3]);
  }
  std::sort(edges.begin(), edges.end());
  return std::adjacent_find(edges.begin(), edges.end()) == edges.end();
}

}  // namespace

std::vector<TemplateProblem> template_problems(const std::string& template_path) {
  tinyxml2::XMLDocument doc;
  if (doc.LoadFile(template_path.c_str()) != tinyxml2::XML_SUCCESS) {
    throw io::InputError(template_path, static_cast<std::size_t>(std::max(0, doc.ErrorLineNum())),
                         std::string("cannot read the template scene: ") + doc.ErrorName());
  }
  std::vector<TemplateProblem> problems;
  const TemplateParts t = find_template_parts(doc, template_path, problems);
  if (t.root == nullptr || std::string(t.root->Name()) != "mujoco") return problems;
  try {
    gravity_frame(t.root, template_path);
  } catch (const io::InputError& e) {
    problems.push_back({e.line(),
                        e.message(),
                        "give <option gravity=\"GX GY GZ\"/> pointing from the hand to the "
                        "support (along it the object hangs from the hand)",
                        {}});
  }
  return problems;
}

ObjectScene write_object_scene(const ObjectPlacement& placement, const HandTemplate& hand,
                               const std::string& dir) {
  const std::string& template_path = hand.scene;
  io::MeshStats stats;
  TriangleMesh mesh = read_object_mesh(placement.file, &stats);
  tinyxml2::XMLDocument doc;
  const TemplateParts t = read_template(doc, template_path);
  const GravityFrame frame = gravity_frame(t.root, template_path);
  const TemplateRoom room = template_room(t, hand.fit, template_path);
  ObjectScene out = place_object(mesh, placement, hand.fit_fraction, frame, room, t, template_path,
                                 stats, hand.mesh_owner());
  out.faces = mesh.faces.size();
  Vec3 support = room.support;
  raise_to_reach(t, room, frame, hand, template_path, out, support);

  const fs::path target = fs::path(dir);
  fs::create_directories(target);
  const std::string stem = fs::path(placement.file).stem().string();
  const fs::path meshes = target / (stem + ".meshes");
  const fs::path mesh_folder = rewrite_paths(t, template_path, target, meshes, hand.moved);
  // The object's mesh moves with the scene: copied into STEM.meshes/ under its own file name (a
  // decomposition of it finds it by that name). A closed mesh whose faces point inward: MuJoCo's
  // inertia and graspcd's containment read the faces' direction, so the scene loads the mesh
  // turned right way out (STEM.outward.obj) instead.
  const std::string flipped = io::turn_right_way_out(placement.file, stats, &mesh, out.scale);
  // In its own folder STEM.meshes/object/, apart from the hand's linked files (the template's
  // mesh folder may hold a file of the object's name, e.g. the cup's).
  const fs::path object_folder = meshes / "object";
  std::error_code exists_ec;
  if (fs::exists(fs::symlink_status(object_folder, exists_ec))) {
    throw template_error(template_path, t.asset,
                         "the hand's mesh folder has a file named 'object', the object's folder");
  }
  fs::create_directories(object_folder);
  // MuJoCo 2.2 reads OBJ and binary STL only, a binary STL of at most kMujocoStlFaces triangles,
  // and refuses a mesh whose zero-area faces give a directed edge twice ("faces have inconsistent
  // orientation"): any other file is the mesh as graspcd read it (those faces dropped, with a
  // warning), written as STEM.converted.obj (in its file units). A file with zero-area faces is
  // converted only when the mesh read is consistently oriented: graspcd's reader joins vertices
  // of the same place, which a scanned mesh's seams keep apart in the file (the YCB soup can).
  const std::size_t file_faces = mesh.faces.size() + stats.dropped_faces.size();
  const bool convert = (stats.format != "OBJ" && stats.format != "binary STL") ||
                       (stats.format == "binary STL" && file_faces > io::kMujocoStlFaces) ||
                       (stats.zero_area_faces > 0 && orientation_consistent(mesh));
  const fs::path object_file =
      object_folder / (!flipped.empty() ? stem + ".outward.obj"
                       : convert        ? stem + ".converted.obj"
                                        : fs::path(placement.file).filename().string());
  if (!flipped.empty()) {
    warnings().add("mesh_inside_out", flipped, "mesh");
    io::write_obj(object_file.string(), mesh);
  } else if (convert) {
    io::write_obj(object_file.string(), mesh);
  } else {
    std::error_code ec;
    fs::copy_file(placement.file, object_file, ec);
    if (ec) throw io::InputError(placement.file, 0, "cannot copy the mesh: " + ec.message());
  }
  set_object(t, object_file.string(), mesh_folder, out);
  raise_size(doc, t.root);
  replace_comments(doc, t.root, scene_header(hand, placement, out, support, stem));

  out.scene = (target / (stem + ".xml")).string();
  out.pairs = (target / (stem + ".pairs.json")).string();
  out.meshes = meshes.string();
  save_scene(doc, template_path, out);
  out.names = {out.scene,
               placement.file,
               "in the template scene: ",
               out.units_hint.empty() ? "" : "; " + out.units_hint,
               {{out.pairs, hand.drive.empty() ? hand.pairs() : hand.drive},
                {object_file.string(), placement.file}},
               hand.mesh_owner(),
               "object_mesh",
               {},
               out.size_hint.empty() ? "" : "; " + out.size_hint};
  return out;
}

struct ObjectPlacer::Read {
  TriangleMesh mesh;
  io::MeshStats stats;
  tinyxml2::XMLDocument doc;
  TemplateParts parts;
  GravityFrame frame;
  TemplateRoom room;
  std::string file;
  std::string template_path;
  double fit_fraction = 1;
  double support_raised = 0;
  std::string hand;  // HandTemplate::mesh_owner(), for the size hint
};

ObjectPlacer::ObjectPlacer(const std::string& file, const HandTemplate& hand, double support_raised)
    : read_(std::make_unique<Read>()) {
  Read& r = *read_;
  r.support_raised = support_raised;
  r.hand = hand.mesh_owner();
  r.file = file;
  r.template_path = hand.scene;
  r.fit_fraction = hand.fit_fraction;
  r.mesh = read_object_mesh(file, &r.stats);
  r.parts = read_template(r.doc, r.template_path);
  r.frame = gravity_frame(r.parts.root, r.template_path);
  r.room = template_room(r.parts, hand.fit, r.template_path);
}

ObjectPlacer::~ObjectPlacer() = default;

ObjectScene ObjectPlacer::place(const ObjectPlacement& placement) const {
  const Read& r = *read_;
  ObjectPlacement p = placement;
  p.file = r.file;
  ObjectScene out = place_object(r.mesh, p, r.fit_fraction, r.frame, r.room, r.parts,
                                 r.template_path, r.stats, r.hand);
  for (std::size_t i = 0; i < 3; ++i) {
    out.pos[i] += r.support_raised * r.frame.up[static_cast<Eigen::Index>(i)];
  }
  out.support_raised = r.support_raised;
  return out;
}

}  // namespace graspcd::grasp
