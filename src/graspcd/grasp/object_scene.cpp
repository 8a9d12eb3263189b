#include "graspcd/grasp/object_scene.h"

#include <stdlib.h>
#include <tinyxml2.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "graspcd/core/geometry.h"
#include "graspcd/core/warnings.h"
#include "graspcd/io/mesh_io.h"
#include "graspcd/io/text_input.h"

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

}  // namespace

ObjectScene write_object_scene(const ObjectPlacement& placement, const std::string& template_path,
                               const std::string& hand, const std::string& dir,
                               const std::optional<std::array<double, 2>>& default_fit,
                               const std::vector<TemplatePath>& moved) {
  // The mesh as graspcd reads it (an error names the file): its extent places and fits it.
  io::MeshStats stats;
  const TriangleMesh mesh = io::load_mesh(placement.file, &stats);
  for (const std::string& w : io::mesh_warnings(placement.file, stats, true)) {
    warnings().add("mesh_hygiene", w, "mesh");
  }

  // The template, read by tinyxml2.
  tinyxml2::XMLDocument doc;
  if (doc.LoadFile(template_path.c_str()) != tinyxml2::XML_SUCCESS) {
    throw io::InputError(template_path, static_cast<std::size_t>(std::max(0, doc.ErrorLineNum())),
                         std::string("cannot read the template scene: ") + doc.ErrorName());
  }
  tinyxml2::XMLElement* root = doc.RootElement();
  const auto fail = [&](const tinyxml2::XMLElement* at, const std::string& what) {
    return io::InputError(template_path, at ? static_cast<std::size_t>(at->GetLineNum()) : 0,
                          "template scene: " + what);
  };
  if (root == nullptr || std::string(root->Name()) != "mujoco") throw fail(root, "no <mujoco>");
  tinyxml2::XMLElement* world = root->FirstChildElement("worldbody");
  tinyxml2::XMLElement* body = nullptr;
  for (tinyxml2::XMLElement* world_element = world; world_element;
       world_element = world_element->NextSiblingElement("worldbody")) {
    for (tinyxml2::XMLElement* b = world_element->FirstChildElement("body"); b;
         b = b->NextSiblingElement("body")) {
      if (b->Attribute("name", "object")) body = b;
    }
  }
  if (body == nullptr) throw fail(world, "no <body name=\"object\"> in <worldbody>");
  tinyxml2::XMLElement* geom = nullptr;
  for (tinyxml2::XMLElement* g = body->FirstChildElement("geom"); g;
       g = g->NextSiblingElement("geom")) {
    if (g->Attribute("type", "mesh") && g->Attribute("mesh")) {
      if (geom != nullptr) throw fail(g, "the object body has more than one mesh geom");
      geom = g;
    }
  }
  if (geom == nullptr) throw fail(body, "the object body has no mesh geom");
  std::vector<tinyxml2::XMLElement*> meshes;
  collect(root, "mesh", meshes);
  tinyxml2::XMLElement* asset = nullptr;
  for (tinyxml2::XMLElement* m : meshes) {
    if (m->Attribute("name", geom->Attribute("mesh"))) asset = m;
  }
  if (asset == nullptr) throw fail(geom, "no <mesh> asset for the object's geom");

  // Gravity (the main file's <option>, else MuJoCo's default) and the placement's frame.
  Vec3 gravity(0, 0, -9.81);
  for (tinyxml2::XMLElement* o = root->FirstChildElement("option"); o;
       o = o->NextSiblingElement("option")) {
    if (o->Attribute("gravity")) {
      const std::vector<double> g = read_numbers(o, "gravity", 3, template_path);
      gravity = Vec3(g[0], g[1], g[2]);
    }
  }
  if (gravity.norm() == 0) throw fail(root, "gravity is zero: no up to place the object by");
  const Vec3 up = -gravity.normalized();
  // Across gravity: the world x axis made perpendicular to up (y when up is near x), then up x e1.
  const Vec3 across = std::abs(up.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 e1 = (across - across.dot(up) * up).normalized();
  const Vec3 e2 = up.cross(e1);

  // The template's support point and room for the object.
  Vec3 support = Vec3::Zero();
  if (body->Attribute("pos")) {
    const std::vector<double> p = read_numbers(body, "pos", 3, template_path);
    support = Vec3(p[0], p[1], p[2]);
  }
  std::optional<std::array<double, 2>> fit_room = default_fit;
  std::vector<tinyxml2::XMLElement*> numerics;
  collect(root, "numeric", numerics);
  for (tinyxml2::XMLElement* n : numerics) {
    if (n->Attribute("name", "graspcd_support")) {
      const std::vector<double> p = read_numbers(n, "data", 3, template_path);
      support = Vec3(p[0], p[1], p[2]);
    } else if (n->Attribute("name", "graspcd_fit")) {
      const std::vector<double> p = read_numbers(n, "data", 2, template_path);
      fit_room = std::array<double, 2>{p[0], p[1]};
    }
  }

  // The rotation: the file's up axis along `up`, then the yaw about it; or the given quaternion.
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
  const Mat3 R = q.toRotationMatrix();

  // The turned mesh's extent in (e1, e2, up), unscaled.
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -lo;
  for (const Vec3& v : mesh.vertices) {
    const Vec3 w = R * v;
    const Vec3 c(w.dot(e1), w.dot(e2), w.dot(up));
    lo = lo.cwiseMin(c);
    hi = hi.cwiseMax(c);
  }
  const Vec3 extent = hi - lo;
  ObjectScene out;
  out.fitted = placement.fit;
  out.scale = placement.scale;
  if (placement.fit) {
    if (!fit_room) {
      throw fail(root, "no <numeric name=\"graspcd_fit\" data=\"WIDTH HEIGHT\"/> for --fit");
    }
    const double width = std::max(extent[0], extent[1]);
    out.scale = std::numeric_limits<double>::infinity();
    if (width > 0) out.scale = (*fit_room)[0] / width;
    if (extent[2] > 0) out.scale = std::min(out.scale, (*fit_room)[1] / extent[2]);
  }
  const double s = out.scale;
  out.size = {s * extent[0], s * extent[1], s * extent[2]};
  if (std::max(out.size[0], out.size[1]) > kLargeObject || out.size[2] > kLargeObject) {
    std::ostringstream w;
    w << placement.file << ": at scale " << s << " the object is " << std::setprecision(3)
      << std::max({out.size[0], out.size[1], out.size[2]})
      << " m across: if the file is not in metres, give --scale (0.001 for millimetres)";
    warnings().add("mesh_units", w.str(), "mesh");
  }
  // Lowest point kSupportGap above the support point, centred on it across gravity.
  const Vec3 centre = 0.5 * s * (lo + hi);
  const Vec3 pos = support + (kSupportGap - s * lo[2]) * up - centre[0] * e1 - centre[1] * e2;
  out.pos = {pos.x(), pos.y(), pos.z()};
  out.quat = {q.w(), q.x(), q.y(), q.z()};

  // The new scene's folder and the paths, relative to it.
  const fs::path target = fs::path(dir);
  fs::create_directories(target);
  const fs::path template_dir = fs::absolute(template_path).parent_path();
  // A path as the template writes it, made a file: beside the template, or under a moved folder.
  const auto resolved = [&](const std::string& path) {
    for (const TemplatePath& m : moved) {
      if (path.compare(0, m.from.size(), m.from) == 0) {
        return fs::path(m.to) / path.substr(m.from.size());
      }
    }
    return template_dir / path;
  };
  std::vector<tinyxml2::XMLElement*> compilers;
  collect(root, "compiler", compilers);
  std::string meshdir;  // the main file's last meshdir (or assetdir), as the template wrote it
  for (tinyxml2::XMLElement* c : compilers) {
    for (const char* a : {"meshdir", "texturedir", "assetdir"}) {
      if (!c->Attribute(a)) continue;
      if (std::string(a) != "texturedir") meshdir = c->Attribute(a);
      c->SetAttribute(a, relative_to(resolved(c->Attribute(a)), target).c_str());
    }
  }
  std::vector<tinyxml2::XMLElement*> includes;
  collect(root, "include", includes);
  for (tinyxml2::XMLElement* inc : includes) {
    if (inc->Attribute("file")) {
      inc->SetAttribute("file", relative_to(resolved(inc->Attribute("file")), target).c_str());
    }
  }
  if (meshdir.empty()) {
    for (const char* kind : {"mesh", "texture", "hfield", "skin"}) {
      std::vector<tinyxml2::XMLElement*> files;
      collect(root, kind, files);
      for (tinyxml2::XMLElement* f : files) {
        if (f->Attribute("file") && f != asset) {
          f->SetAttribute("file", relative_to(resolved(f->Attribute("file")), target).c_str());
        }
      }
    }
  }
  const fs::path mesh_folder = meshdir.empty() ? target : resolved(meshdir);

  // The object: its mesh, scale, place and turn.
  for (const char* a : {"refpos", "refquat", "scale", "file", "vertex", "face", "normal"}) {
    asset->DeleteAttribute(a);
  }
  // The template's names (the cup, the mug, the glass) would mislead: the object's geom and mesh
  // are named after what they are.
  asset->SetAttribute("name", "object_mesh");
  geom->SetAttribute("mesh", "object_mesh");
  geom->SetAttribute("name", "object");
  asset->SetAttribute("file", relative_to(placement.file, mesh_folder).c_str());
  const double scale3[3] = {s, s, s};
  asset->SetAttribute("scale", numbers(scale3, 3).c_str());
  for (const char* a : {"quat", "axisangle", "xyaxes", "zaxis", "euler"}) body->DeleteAttribute(a);
  body->SetAttribute("pos", numbers(out.pos.data(), 3).c_str());
  body->SetAttribute("quat", numbers(out.quat.data(), 4).c_str());
  for (const char* a : {"pos", "quat", "axisangle", "xyaxes", "zaxis", "euler"}) {
    geom->DeleteAttribute(a);
  }

  // Room for the contacts of a fine mesh.
  tinyxml2::XMLElement* size = root->FirstChildElement("size");
  if (size == nullptr) {
    size = doc.NewElement("size");
    root->InsertFirstChild(size);
  }
  size->SetAttribute("nconmax", std::max(kMinNconmax, size->IntAttribute("nconmax")));
  size->SetAttribute("njmax", std::max(kMinNjmax, size->IntAttribute("njmax")));

  // The template's comments (its own header) go; ours says what this scene is.
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
  std::ostringstream header;
  header << "\n  Generated by graspcd (the grasp command given an object file) from the template "
         << fs::absolute(template_path).lexically_normal().string() << " (hand: " << hand
         << ").\n  Object: " << fs::absolute(placement.file).lexically_normal().string()
         << "\n    scale " << short_number(s)
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
         << " m above the support point (" << numbers(support.data(), 3)
         << "), centred on it across gravity.\n"
         << "  Every path is relative to this file's folder. Pairs and the drive: "
         << fs::path(placement.file).stem().string()
         << ".pairs.json beside it.\n  Edit freely: graspcd grasp on this file reruns the grasp.\n";
  root->InsertFirstChild(doc.NewComment(header.str().c_str()));

  const std::string stem = fs::path(placement.file).stem().string();
  out.scene = (target / (stem + ".xml")).string();
  out.pairs = (target / (stem + ".pairs.json")).string();
  if (doc.SaveFile(out.scene.c_str()) != tinyxml2::XML_SUCCESS) {
    throw io::InputError(out.scene, 0, "cannot write the scene");
  }
  // The template's pair config, unchanged: it names body:object.
  const std::string pairs = fs::path(template_path).replace_extension(".pairs.json").string();
  std::ifstream in(pairs, std::ios::binary);
  if (!in) throw io::InputError(pairs, 0, "cannot read the template's pair config");
  std::ofstream(out.pairs, std::ios::binary) << in.rdbuf();
  return out;
}

TempFolder::TempFolder() {
  std::string pattern = (fs::temp_directory_path() / "graspcd-object-XXXXXX").string();
  if (mkdtemp(pattern.data()) == nullptr) {
    throw std::runtime_error("cannot create a temporary folder in " +
                             fs::temp_directory_path().string());
  }
  path_ = pattern;
}

TempFolder::~TempFolder() {
  std::error_code ignored;
  fs::remove_all(path_, ignored);
}

}  // namespace graspcd::grasp
