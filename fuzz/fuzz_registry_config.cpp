// libFuzzer target: the scene config (mujoco/pair_config.h: JSON parsed by parse_registry_config,
// then resolved against a model by the Registry). A small fixed model (a mesh, boxes, primitives,
// a plane, a visual-only geom), loaded once; every config that resolves is attached and the
// model's collision run once through graspcd's callback (mj_forward). Bad input must end in the
// one-line std::runtime_error that starts with the config's name.
#include <mujoco/mujoco.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <stdexcept>
#include <string>

#include "fuzz_support.h"
#include "graspcd/mujoco/collision.h"
#include "graspcd/mujoco/mujoco_ptr.h"
#include "graspcd/mujoco/registry.h"

namespace {

// Overlapping geoms of every served type, so that resolved configs reach the callback's paths.
const char* const kScene = R"(<mujoco>
  <asset><mesh name="tet" file="tet.obj"/></asset>
  <worldbody>
    <geom name="floor" type="plane" size="1 1 0.1"/>
    <body name="finger1" pos="0 0 0.2"><freejoint/>
      <geom name="f1_a" type="mesh" mesh="tet"/>
      <geom name="f1_b" type="box" size="0.02 0.02 0.05" pos="0.03 0 0"/></body>
    <body name="finger2" pos="0.05 0 0.2"><freejoint/>
      <geom name="f2_a" type="capsule" size="0.01 0.03"/>
      <geom name="f2_b" type="sphere" size="0.02" margin="0.001"/></body>
    <body name="object" pos="0.02 0 0.22"><freejoint/>
      <geom name="obj_box" type="box" size="0.03 0.03 0.03"/>
      <geom name="obj_cyl" type="cylinder" size="0.02 0.02" pos="0 0.02 0"/>
      <geom name="obj_ell" type="ellipsoid" size="0.02 0.03 0.01" pos="0 -0.02 0"/>
      <geom name="label" type="box" size="0.01 0.01 0.01" contype="0" conaffinity="0"/></body>
  </worldbody>
</mujoco>)";

const char* const kTetrahedron =
    "v 0 0 0\nv 0.05 0 0\nv 0 0.05 0\nv 0 0 0.05\n"
    "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

struct Scene {
  graspcd::fuzz::InputFile file{"scene.xml"};
  graspcd::mujoco::ModelPtr model;
  graspcd::mujoco::DataPtr data;

  Scene() {
    std::ofstream(file.dir() + "/tet.obj") << kTetrahedron;
    std::ofstream(file.path()) << kScene;
    char error[1024] = "";
    model.reset(mj_loadXML(file.path().c_str(), nullptr, error, sizeof(error)));
    if (!model) {
      std::fprintf(stderr, "graspcd fuzz: the fixed scene does not load: %s\n", error);
      std::abort();
    }
    data.reset(mj_makeData(model.get()));
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static Scene scene;
  static graspcd::mujoco::ScopedInstall install;
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string source = "fuzz.pairs.json";
  try {
    const graspcd::mujoco::RegistryConfig config =
        graspcd::mujoco::parse_registry_config(text, source);
    graspcd::mujoco::Registry registry(scene.model.get(), config, source);
    const graspcd::mujoco::Attachment attached = graspcd::mujoco::attach(registry);
    mj_resetData(scene.model.get(), scene.data.get());
    mj_forward(scene.model.get(), scene.data.get());
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    // "SOURCE: message", or "SOURCE:LINE: bad JSON: message" (json_config.h).
    static const std::regex named("^" + std::regex_replace(source, std::regex(R"([.])"), R"(\.)") +
                                  R"((:\d+)?: )");
    if (!std::regex_search(what, named) || what.find('\n') != std::string::npos) {
      graspcd::fuzz::disagreement(
          ("an error that is not one line naming the config: " + what).c_str());
    }
  }
  return 0;
}
