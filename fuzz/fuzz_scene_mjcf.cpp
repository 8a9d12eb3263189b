// libFuzzer target: the scene path. A small fixed MJCF (a mesh finger, a box object on a
// plane, a pair config) whose numeric attributes take their values from the input: line k of the
// input replaces attribute k of kAttributes (quotes and markup characters dropped, so the XML
// stays well formed); the lines after them are prepended to the finger's OBJ (a byte-order mark,
// a NaN vertex, a bad face...). The scene then goes through mujoco::load_model (graspcd's checks,
// MuJoCo's compiler, the model check), NonconvexContacts and a few mj_step.
// MuJoCo's errors (mju_error exits the process by default) are routed to exceptions and its
// warnings to the sink, as the command line does. Bad input must end in a mujoco::InputError that
// is one line naming a file of the scene, or a one-line MujocoError; a model that loads holds no
// non-finite number.
#include <mujoco/mujoco.h>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "graspcd/mujoco/model_check.h"
#include "graspcd/mujoco/model_loading.h"
#include "graspcd/mujoco/mujoco_messages.h"
#include "graspcd/mujoco/nonconvex_contacts.h"

namespace {

// The attributes the input sets, in order, with the value used when the input has fewer lines.
struct Attribute {
  const char* key;
  const char* fallback;
};
const Attribute kAttributes[] = {{"FINGER_POS", "0 0 0.12"}, {"FINGER_QUAT", "1 0 0 0"},
                                 {"OBJECT_POS", "0 0 0.05"}, {"OBJECT_SIZE", "0.03 0.03 0.03"},
                                 {"MESH_SCALE", "1 1 1"},    {"TIMESTEP", "0.002"},
                                 {"GRAVITY", "0 0 -9.81"},   {"MASS", "0.1"}};

const char* const kScene = R"(<mujoco>
  <option timestep="TIMESTEP" gravity="GRAVITY"/>
  <asset><mesh name="tet" file="tet.obj" scale="MESH_SCALE"/></asset>
  <worldbody>
    <geom name="floor" type="plane" size="1 1 0.1"/>
    <body name="finger" pos="FINGER_POS" quat="FINGER_QUAT"><freejoint/>
      <geom name="finger" type="mesh" mesh="tet"/></body>
    <body name="object" pos="OBJECT_POS"><freejoint/>
      <geom name="object" type="box" size="OBJECT_SIZE" mass="MASS"/></body>
  </worldbody>
</mujoco>)";

const char* const kTetrahedron =
    "v 0 0 0\nv 0.05 0 0\nv 0 0.05 0\nv 0 0 0.05\n"
    "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

const char* const kPairs = R"({"pairs": [{"a": "finger", "b": "object"}]})";

// An attribute value from an input line: no quote or markup character, no line break.
std::string attribute_value(const std::string& line) {
  std::string out;
  for (const char c : line) {
    if (c != '"' && c != '<' && c != '>' && c != '&' && c != '\r' && c != '\0') out += c;
  }
  return out;
}

void one_line(const std::string& what, const char* kind) {
  if (what.find('\n') != std::string::npos) {
    graspcd::fuzz::disagreement((std::string(kind) + " of more than one line: " + what).c_str());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static graspcd::fuzz::InputFile file("scene.xml");
  static const bool routed = [] {
    graspcd::mujoco::route_mujoco_warnings();
    graspcd::mujoco::route_mujoco_errors();
    std::ofstream(file.dir() + "/scene.pairs.json") << kPairs;
    return true;
  }();
  (void)routed;
  std::istringstream input(std::string(reinterpret_cast<const char*>(data), size));
  std::string xml = kScene;
  std::string line;
  for (const Attribute& a : kAttributes) {
    const std::string value = std::getline(input, line) ? attribute_value(line) : a.fallback;
    xml.replace(xml.find(a.key), std::string(a.key).size(), value);
  }
  std::string extra_obj_lines(std::istreambuf_iterator<char>(input), {});
  std::ofstream(file.dir() + "/tet.obj", std::ios::binary | std::ios::trunc)
      << extra_obj_lines << kTetrahedron;
  file.write(reinterpret_cast<const std::uint8_t*>(xml.data()), xml.size());

  const std::string scene = file.path();
  const std::string mesh = file.dir() + "/tet.obj";
  try {
    const graspcd::mujoco::ModelPtr model = graspcd::mujoco::load_model(scene);
    if (!graspcd::mujoco::find_non_finite(model.get()).empty()) {
      graspcd::fuzz::disagreement("load_model returned a model holding a non-finite number");
    }
    graspcd::mujoco::NonconvexContacts contacts(model.get(), file.dir() + "/scene.pairs.json");
    const graspcd::mujoco::DataPtr d(mj_makeData(model.get()));
    for (int step = 0; step < 5; ++step) mj_step(model.get(), d.get());
  } catch (const graspcd::mujoco::InputError& e) {
    one_line(e.what(), "a scene error");
    if (e.file() != scene && e.file() != mesh) {
      graspcd::fuzz::disagreement(("a scene error naming another file: " + e.file()).c_str());
    }
  } catch (const graspcd::mujoco::MujocoError& e) {
    one_line(e.what(), "a MuJoCo error");
  } catch (const std::runtime_error& e) {
    // The registry's errors name the pair config (registry.h).
    one_line(e.what(), "a config error");
    if (std::string(e.what()).rfind(file.dir() + "/scene.pairs.json: ", 0) != 0) {
      graspcd::fuzz::disagreement((std::string("an error naming nothing: ") + e.what()).c_str());
    }
  }
  return 0;
}
