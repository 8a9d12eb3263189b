#include "graspcd/grasp/hand_check.h"

#include <tinyxml2.h>

#include <filesystem>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "graspcd/grasp/drive_config.h"
#include "graspcd/grasp/hand_wrapper.h"
#include "graspcd/grasp/object_scene.h"
#include "graspcd/io/input_error.h"
#include "graspcd/io/output_files.h"
#include "graspcd/mujoco/geom_trees.h"
#include "graspcd/mujoco/json_config.h"
#include "graspcd/mujoco/model_loading.h"
#include "graspcd/mujoco/pair_config.h"

namespace graspcd::grasp {

namespace {

namespace fs = std::filesystem;

constexpr const char* kHowDrive = "docs/hands.md, \"A hand file and its drive\"";

// The pair config's text, parsed: the MuJoCo layer's fields and the "grasp" section.
struct CheckedConfig {
  bool read = false;  // found and parsed
  mujoco::RegistryConfig registry;
  std::optional<DriveConfig> drive;
};

// Step 3: the pair config `path` (named `shown`).
CheckedConfig check_config(const std::string& path, const std::string& shown, HandCheck& out) {
  CheckedConfig c;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    out.missing.push_back(
        {shown, 0, "no pair config " + shown + " beside the scene",
         "write one: {\"pairs\": [{\"a\": \"body:HAND_BODY*\", \"b\": \"body:object\"}], "
         "\"grasp\": {\"hand\": BODY, \"support\": BODY, \"close\": [{\"actuator\": NAME, "
         "\"step\": CTRL, \"touch\": [PATTERN]}], \"lift\": {\"actuator\": NAME, \"by\": CTRL}}} "
         "(docs/hands.md, steps 5 and 6); or give the hand file with --drive"});
    return c;
  }
  const std::string text = mujoco::read_config_file(path);
  try {
    c.registry = mujoco::parse_registry_config(text, shown);
    c.drive = parse_drive_config(text, shown);
    c.read = true;
  } catch (const io::InputError& e) {
    out.missing.push_back(
        {shown, e.line(), e.message(), "docs/hands.md, steps 5 and 6, give the form"});
  }
  return c;
}

// Whether geoms a and b may collide by their contype and conaffinity.
bool filter_collides(const mjModel* m, int a, int b) {
  return (m->geom_contype[a] & m->geom_conaffinity[b]) ||
         (m->geom_contype[b] & m->geom_conaffinity[a]);
}

// The geoms of body `root` and the bodies below it.
std::vector<int> subtree_geoms(const mjModel* m, int root) {
  std::vector<int> out;
  for (int g = 0; g < m->ngeom; ++g) {
    for (int b = m->geom_bodyid[g]; b > 0; b = m->body_parentid[b]) {
      if (b == root) {
        out.push_back(g);
        break;
      }
    }
  }
  return out;
}

// Step 4 on the loaded trial scene: the pairs, the drive's names, the support.
void check_model(const mjModel* m, const CheckedConfig& c, const std::string& shown,
                 HandCheck& out) {
  const auto lacks = [&](const std::string& what, const std::string& how) {
    out.missing.push_back({shown, 0, what, how});
  };
  const int object_body = mj_name2id(m, mjOBJ_BODY, c.drive ? c.drive->object.c_str() : "object");
  const std::vector<int> object_geoms =
      object_body > 0 ? subtree_geoms(m, object_body) : std::vector<int>{};
  bool object_served = false;
  for (const mujoco::PairPattern& p : c.registry.patterns) {
    std::vector<int> sides[2];
    for (int k = 0; k < 2; ++k) {
      const std::string& pattern = k == 0 ? p.a : p.b;
      try {
        sides[k] = mujoco::resolve_pattern(m, pattern, shown);
      } catch (const io::InputError& e) {
        lacks(e.message(),
              "name collidable geoms of a served type (mesh, box, sphere, capsule, cylinder, "
              "ellipsoid) by \"geom:GLOB\" or \"body:GLOB\"");
      }
    }
    for (int g : object_geoms) {
      for (int k = 0; k < 2; ++k) {
        for (int h : sides[k]) object_served = object_served || h == g;
      }
    }
  }
  if (!object_served) {
    lacks("no pair serves the object: graspcd would not collide it with the hand",
          "add {\"a\": \"body:HAND_BODY*\", \"b\": \"body:object\"} to \"pairs\"");
  }
  if (!c.drive) {
    // The project's hand follows grasp.h's scene contract instead of a drive.
    if (mj_name2id(m, mjOBJ_JOINT, "arm1") < 0 || mj_name2id(m, mjOBJ_JOINT, "finger1_A") < 0) {
      lacks("no \"grasp\" section in the pair config: nothing says how to close the hand",
            "add \"grasp\": {\"hand\": BODY, \"support\": BODY, \"close\": [...], \"lift\": "
            "{...}} (docs/hands.md, step 6)");
    }
    return;
  }
  const DriveConfig& d = *c.drive;
  const auto body = [&](const std::string& name, const std::string& role, const std::string& how) {
    const int id = mj_name2id(m, mjOBJ_BODY, name.c_str());
    if (id < 0) lacks("'grasp': " + role + " '" + name + "' is no body of the scene", how);
    return id;
  };
  body(d.object, "the object", "name the object body (\"object\")");
  body(d.hand, "the hand", "name the body the hold's drift is measured against (the palm)");
  const int support =
      d.support.empty() ? 0 : body(d.support, "the support", "name the body the object stands on");
  std::set<std::string> actuators;
  for (const CloseDrive& cd : d.close) actuators.insert(cd.actuator);
  actuators.insert(d.lift_actuator);
  for (const std::string& a : actuators) {
    if (mj_name2id(m, mjOBJ_ACTUATOR, a.c_str()) < 0) {
      lacks("'grasp': no actuator named '" + a + "'",
            "name one of the scene's <actuator>s (a closing joint's, or the lift's)");
    }
  }
  for (const CloseDrive& cd : d.close) {
    for (const std::string& t : cd.touch) {
      if (mujoco::match_geoms(m, t).empty()) {
        lacks("'grasp': touch pattern '" + t + "' of '" + cd.actuator +
                  "' matches no collidable geom",
              "name the geoms that stop this actuator when they touch the object (\"body:GLOB\")");
      }
    }
  }
  // The object rests on the support before the grasp: they must collide.
  if (support > 0 && !object_geoms.empty()) {
    bool rests = false;
    for (int s : subtree_geoms(m, support)) {
      for (int g : object_geoms) rests = rests || filter_collides(m, s, g);
    }
    if (!rests) {
      lacks("the object does not collide with the support '" + d.support +
                "' (contype/conaffinity): it would fall through it",
            "give the support's geoms and the object's geom a contype/conaffinity bit in common");
    }
  }
}

// The template's graspcd numerics, for the notes.
std::set<std::string> numerics(const std::string& scene) {
  std::set<std::string> out;
  tinyxml2::XMLDocument doc;
  if (doc.LoadFile(scene.c_str()) != tinyxml2::XML_SUCCESS || !doc.RootElement()) return out;
  for (const tinyxml2::XMLElement* c = doc.RootElement()->FirstChildElement("custom"); c;
       c = c->NextSiblingElement("custom")) {
    for (const tinyxml2::XMLElement* n = c->FirstChildElement("numeric"); n;
         n = n->NextSiblingElement("numeric")) {
      if (n->Attribute("name")) out.insert(n->Attribute("name"));
    }
  }
  return out;
}

std::string summary(const mjModel* m, const CheckedConfig& c) {
  std::ostringstream s;
  s << "gravity " << m->opt.gravity[0] << ' ' << m->opt.gravity[1] << ' ' << m->opt.gravity[2]
    << ", " << c.registry.patterns.size() << " pair pattern(s)";
  if (c.drive) {
    s << ", " << c.drive->close.size() << " closing actuator(s), lift '" << c.drive->lift_actuator
      << "' by " << c.drive->lift_by << ", hand body '" << c.drive->hand << "'";
    if (!c.drive->support.empty()) s << ", support body '" << c.drive->support << "'";
  } else {
    s << ", the project's hand (no \"grasp\" section)";
  }
  return s.str();
}

}  // namespace

HandCheck check_hand(const HandTemplate& hand) {
  HandCheck out;
  out.scene = hand.scene;
  out.pairs = hand.drive.empty() ? hand.pairs() : hand.drive;
  out.wrapped = !hand.drive.empty();
  const fs::path temporary = io::temporary_folder();
  const io::CleanupGuard folder =
      io::make_private_folder(temporary, "graspcd-hand-check", temporary.string());

  // 1. A hand file's drive: the wrapper is written, or what the drive lacks is said.
  HandTemplate t = hand;
  if (!hand.drive.empty()) {
    try {
      t = write_hand_wrapper(hand, (folder.path() / "wrapped_hand").string());
    } catch (const io::InputError& e) {
      if (e.file() != hand.drive) throw;  // the hand file itself: bad input
      out.missing.push_back({e.file(), e.line(), e.message(), kHowDrive});
      return out;
    }
  }
  // 2. The template contract.
  for (const TemplateProblem& p : template_problems(t.scene)) {
    out.missing.push_back({p.file.empty() ? hand.scene : p.file, p.line, p.what, p.how});
  }
  // 3. The pair config.
  const CheckedConfig config = check_config(t.pairs(), out.pairs, out);
  // 4. A trial object placed as a run places one, and the scene loaded with it.
  if (out.missing.empty()) {
    const std::string cube = (folder.path() / "cube.obj").string();
    write_placeholder_object(cube);
    ObjectPlacement placement;
    placement.file = cube;
    try {
      const ObjectScene scene =
          write_object_scene(placement, t, (folder.path() / "trial").string());
      const mujoco::ModelPtr model = mujoco::load_model(scene.scene, scene.names);
      check_model(model.get(), config, out.pairs, out);
      if (out.missing.empty()) out.summary = summary(model.get(), config);
    } catch (const io::InputError& e) {
      out.missing.push_back({hand.scene, e.line(),
                             "with an object in it, the scene does not load: " + e.message(),
                             "fix what MuJoCo names (the hand's files, its meshdir)"});
    }
  }
  // Optional pieces.
  const std::set<std::string> given = numerics(t.scene);
  if (!given.count("graspcd_support")) {
    out.notes.push_back(
        "no <numeric name=\"graspcd_support\" data=\"X Y Z\"/>: an object's lowest point goes "
        "to where the object body stands (its pos)");
  }
  if (!given.count("graspcd_fit") && !t.fit) {
    out.notes.push_back(
        "no <numeric name=\"graspcd_fit\" data=\"WIDTH HEIGHT\"/>: --fit has no room to scale "
        "an object to");
  }
  return out;
}

}  // namespace graspcd::grasp
