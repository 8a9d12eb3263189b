#include "graspcd/grasp/hand_wrapper.h"

#include <tinyxml2.h>

#include <Eigen/Geometry>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <tuple>
#include <vector>

#include "graspcd/io/input_error.h"
#include "graspcd/mujoco/json_config.h"
#include "graspcd/mujoco/model_loading.h"

namespace graspcd::grasp {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// The support's box: half-extents across gravity and along it, m; its mass, kg. The shipped
// templates' table.
constexpr double kSupportHalf = 0.1;
constexpr double kSupportHalfThickness = 0.01;
constexpr double kSupportMass = 2;
// The placeholder object's half-edge, m (a cube, in place until the object run's mesh replaces it).
constexpr double kPlaceholderHalf = 0.01;

// The shortest text that reads back as v (-0 as 0).
std::string shortest_text(double v) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, v + 0.0).ptr;
  return std::string(text, end);
}

std::string numbers(const Vec3& v) {
  return shortest_text(v.x()) + " " + shortest_text(v.y()) + " " + shortest_text(v.z());
}

// A drive file's array of `n` finite numbers at `key` of `object`; an error naming the file.
std::vector<double> finite_numbers(const json& object, const std::string& key, std::size_t n,
                                   const std::string& drive) {
  const json& v = object.at(key);
  std::vector<double> out;
  if (v.is_array() && v.size() == n) {
    for (const json& x : v) {
      if (!x.is_number() || !std::isfinite(x.get<double>())) break;
      out.push_back(x.get<double>());
    }
  }
  if (out.size() != n) {
    throw io::InputError(drive, 0,
                         "'mount': '" + key + "' must be " + std::to_string(n) + " finite numbers");
  }
  return out;
}

// The "mount" of a drive file.
HandMount read_mount(const json& doc, const std::string& drive) {
  if (!doc.contains("mount") || !doc.at("mount").is_object()) {
    throw io::InputError(drive, 0,
                         "no \"mount\": {\"gravity\": [GX, GY, GZ], \"support\": [X, Y, Z]} (where "
                         "the object hangs from the hand and where its lowest point goes)");
  }
  const json& m = doc.at("mount");
  for (const auto& [key, value] : m.items()) {
    if (key != "gravity" && key != "support" && key != "room")
      throw io::InputError(drive, 0, "'mount': unknown field '" + key + "'");
  }
  for (const char* key : {"gravity", "support"}) {
    if (!m.contains(key)) throw io::InputError(drive, 0, std::string("'mount': no '") + key + "'");
  }
  HandMount mount;
  const std::vector<double> g = finite_numbers(m, "gravity", 3, drive);
  mount.gravity = Vec3(g[0], g[1], g[2]);
  if (mount.gravity.norm() == 0) throw io::InputError(drive, 0, "'mount': 'gravity' is zero");
  const std::vector<double> s = finite_numbers(m, "support", 3, drive);
  mount.support = Vec3(s[0], s[1], s[2]);
  if (m.contains("room")) {
    const std::vector<double> r = finite_numbers(m, "room", 2, drive);
    if (!(r[0] > 0 && r[1] > 0)) {
      throw io::InputError(drive, 0, "'mount': 'room' must be a width and a height > 0");
    }
    mount.room = std::array<double, 2>{r[0], r[1]};
  }
  return mount;
}

// The hand file's compiler folders (meshdir, texturedir, assetdir) made absolute: MuJoCo 2.2 reads
// them relative to the main scene, which is the wrapper.
std::vector<std::pair<std::string, std::string>> hand_folders(const std::string& hand_file) {
  tinyxml2::XMLDocument doc;
  if (doc.LoadFile(hand_file.c_str()) != tinyxml2::XML_SUCCESS) {
    throw io::InputError(hand_file, static_cast<std::size_t>(std::max(0, doc.ErrorLineNum())),
                         std::string("cannot read the hand file: ") + doc.ErrorName());
  }
  const tinyxml2::XMLElement* root = doc.RootElement();
  if (root == nullptr || std::string(root->Name()) != "mujoco" ||
      root->FirstChildElement("worldbody") == nullptr) {
    throw io::InputError(hand_file, 0, "not a hand file: no <mujoco> with a <worldbody>");
  }
  const fs::path folder = fs::absolute(hand_file).parent_path();
  std::vector<std::pair<std::string, std::string>> out;
  for (const tinyxml2::XMLElement* c = root->FirstChildElement("compiler"); c;
       c = c->NextSiblingElement("compiler")) {
    for (const char* a : {"meshdir", "texturedir", "assetdir"}) {
      if (c->Attribute(a)) out.emplace_back(a, (folder / c->Attribute(a)).lexically_normal());
    }
  }
  return out;
}

// The hand file loaded alone (its errors name it): the bodies holding a collidable geom, for the
// default pairs; a body, joint or actuator of the wrapper's names is refused.
std::vector<std::string> hand_bodies(const std::string& hand_file) {
  const mujoco::ModelPtr model = mujoco::load_model(hand_file);
  const mjModel* m = model.get();
  for (const auto& [type, name, what] : {std::tuple{mjOBJ_BODY, kWrapperObject, "body"},
                                         std::tuple{mjOBJ_BODY, kWrapperSupport, "body"},
                                         std::tuple{mjOBJ_ACTUATOR, kWrapperLift, "actuator"}}) {
    if (mj_name2id(m, type, name) >= 0) {
      throw io::InputError(hand_file, 0,
                           std::string("has a ") + what + " named '" + name +
                               "', a name the wrapper gives what it adds: rename it, or write a "
                               "template of your own (docs/hands.md)");
    }
  }
  std::vector<std::string> out;
  std::set<int> seen;
  for (int g = 0; g < m->ngeom; ++g) {
    const int b = m->geom_bodyid[g];
    if (b == 0 || (m->geom_contype[g] == 0 && m->geom_conaffinity[g] == 0) || seen.count(b)) {
      continue;
    }
    seen.insert(b);
    const char* name = mj_id2name(m, mjOBJ_BODY, b);
    if (name == nullptr) {
      throw io::InputError(hand_file, 0,
                           "body " + std::to_string(b) +
                               " has a collidable geom and no name: give the drive file "
                               "\"pairs\" that name its geoms");
    }
    out.emplace_back(name);
  }
  return out;
}

// The wrapper's pair config: the drive file without "mount", its "grasp" given the wrapper's
// object, support and lift where it names none, and "pairs" by default every body of `bodies`
// against the object.
json wrapper_config(json doc, const std::vector<std::string>& bodies, const std::string& drive) {
  doc.erase("mount");
  if (!doc.contains("grasp") || !doc.at("grasp").is_object()) {
    throw io::InputError(drive, 0,
                         "no \"grasp\" section: {\"hand\": BODY, \"close\": [...]} (how the hand "
                         "closes: docs/hands.md)");
  }
  json& grasp = doc.at("grasp");
  if (!grasp.contains("object")) grasp["object"] = kWrapperObject;
  if (!grasp.contains("support")) grasp["support"] = kWrapperSupport;
  if (!grasp.contains("lift")) grasp["lift"] = {{"actuator", kWrapperLift}, {"by", kWrapperLiftBy}};
  if (!doc.contains("pairs")) {
    json pairs = json::array();
    for (const std::string& b : bodies) {
      pairs.push_back({{"a", "body:" + b}, {"b", std::string("body:") + kWrapperObject}});
    }
    doc["pairs"] = pairs;
  }
  return doc;
}

// The wrapper scene's text.
std::string wrapper_scene(const HandTemplate& hand, const HandMount& mount,
                          const std::vector<std::pair<std::string, std::string>>& folders,
                          const fs::path& placeholder) {
  const Vec3 down = mount.gravity.normalized();
  // The support's frame: its z along gravity (its slide axis), so its face toward the object is
  // its -z face at the support point.
  const Eigen::Quaterniond turn = Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), down);
  const Vec3 centre = mount.support + kSupportHalfThickness * down;
  const Vec3 object = mount.support - (kPlaceholderHalf + 0.5e-3) * down;
  std::ostringstream x;
  x << "<mujoco model=\"wrapped hand\">\n"
    << "  <!-- Written by graspcd around the hand file " << fs::absolute(hand.scene).string()
    << "\n       with the drive " << fs::absolute(hand.drive).string()
    << " (src/graspcd/grasp/hand_wrapper.h). -->\n"
    << "  <include file=\"" << fs::absolute(hand.scene).lexically_normal().string() << "\"/>\n"
    << "  <compiler";
  for (const auto& [attribute, folder] : folders) x << ' ' << attribute << "=\"" << folder << '"';
  x << "/>\n"
    << "  <option gravity=\"" << numbers(mount.gravity) << "\"/>\n"
    << "  <custom>\n"
    << "    <numeric name=\"graspcd_support\" data=\"" << numbers(mount.support) << "\"/>\n";
  if (mount.room) {
    x << "    <numeric name=\"graspcd_fit\" data=\"" << shortest_text((*mount.room)[0]) << ' '
      << shortest_text((*mount.room)[1]) << "\"/>\n";
  }
  x << "  </custom>\n"
    << "  <asset>\n"
    << "    <mesh name=\"object_placeholder\" file=\"" << placeholder.string() << "\"/>\n"
    << "  </asset>\n"
    << "  <worldbody>\n"
    << "    <body name=\"" << kWrapperObject << "\" pos=\"" << numbers(object) << "\">\n"
    << "      <freejoint/>\n"
    << "      <geom name=\"object\" type=\"mesh\" mesh=\"object_placeholder\" density=\"1000\" "
       "friction=\"1 0.01 0.001\" contype=\"3\" conaffinity=\"3\"/>\n"
    << "    </body>\n"
    << "    <body name=\"" << kWrapperSupport << "\" pos=\"" << numbers(centre) << "\" quat=\""
    << shortest_text(turn.w()) << ' ' << shortest_text(turn.x()) << ' ' << shortest_text(turn.y())
    << ' ' << shortest_text(turn.z()) << "\">\n"
    << "      <joint name=\"support_slide\" type=\"slide\" axis=\"0 0 1\" damping=\"50\"/>\n"
    << "      <geom name=\"support\" type=\"box\" size=\"" << kSupportHalf << ' ' << kSupportHalf
    << ' ' << kSupportHalfThickness << "\" mass=\"" << kSupportMass
    << "\" contype=\"2\" conaffinity=\"2\"/>\n"
    << "    </body>\n"
    << "  </worldbody>\n"
    << "  <actuator>\n"
    << "    <position name=\"" << kWrapperLift
    << "\" joint=\"support_slide\" kp=\"4000\" ctrlrange=\"-0.1 0.1\"/>\n"
    << "  </actuator>\n"
    << "</mujoco>\n";
  return x.str();
}

}  // namespace

void write_placeholder_object(const std::string& path) {
  std::ofstream out(path);
  const double h = kPlaceholderHalf;
  for (int k = 0; k < 8; ++k)
    out << "v " << (k & 1 ? h : -h) << ' ' << (k & 2 ? h : -h) << ' ' << (k & 4 ? h : -h) << '\n';
  out << "f 1 3 2\nf 2 3 4\nf 5 6 7\nf 6 8 7\nf 1 2 5\nf 2 6 5\n"
         "f 3 7 4\nf 4 7 8\nf 1 5 3\nf 3 5 7\nf 2 4 6\nf 4 8 6\n";
  if (!out) throw io::InputError(path, 0, "cannot write the placeholder object");
}

HandTemplate hand_with_drive(const std::string& hand_file, const std::string& drive) {
  for (const char* name : {"project", "robotiq", "shadow", "allegro"}) {
    if (hand_file == name) {
      throw std::invalid_argument("--drive goes with a hand file, not the built-in template '" +
                                  hand_file + "' (which has its drive)");
    }
  }
  for (const std::string& file : {hand_file, drive}) {
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) throw io::InputError(file, 0, "no such file");
  }
  HandTemplate hand;
  hand.name = hand_file;
  hand.scene = hand_file;
  hand.drive = drive;
  return hand;
}

HandTemplate write_hand_wrapper(const HandTemplate& hand, const std::string& dir) {
  const json doc = mujoco::parse_json_config(mujoco::read_config_file(hand.drive), hand.drive);
  if (!doc.is_object()) throw io::InputError(hand.drive, 0, "the drive must be a JSON object");
  const HandMount mount = read_mount(doc, hand.drive);
  const auto folders = hand_folders(hand.scene);
  const json config = wrapper_config(doc, hand_bodies(hand.scene), hand.drive);

  const fs::path folder(dir);
  fs::create_directories(folder);
  const fs::path placeholder = fs::absolute(folder / "object.obj");
  write_placeholder_object(placeholder.string());
  HandTemplate wrapped = hand;
  wrapped.scene = (folder / "hand.xml").string();
  wrapped.fit = mount.room;
  wrapped.fit_fraction = 1;
  wrapped.moved = {};
  std::ofstream(wrapped.scene) << wrapper_scene(hand, mount, folders, placeholder);
  std::ofstream pairs(wrapped.pairs());
  pairs << config.dump(2) << '\n';
  if (!pairs) throw io::InputError(wrapped.pairs(), 0, "cannot write the wrapper's pair config");
  return wrapped;
}

}  // namespace graspcd::grasp
