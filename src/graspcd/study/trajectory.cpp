#include "graspcd/study/trajectory.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <system_error>

#include "graspcd/grasp/drive_config.h"
#include "graspcd/grasp/grasp.h"
#include "graspcd/io/input_error.h"
#include "graspcd/io/output_files.h"
#include "graspcd/io/text_input.h"
#include "graspcd/mujoco/model_loading.h"
#include "graspcd/mujoco/mujoco_messages.h"
#include "graspcd/mujoco/pair_config.h"
#include "graspcd/mujoco/scene_check.h"
#include "graspcd/study/replay.h"
#include "graspcd/version/envelope.h"

namespace graspcd::study {

namespace {

using json = nlohmann::json;

constexpr double kRound = 1e6;  // 1e-6 m, 1e-6 for rotations and normals

double rounded(double v) { return std::round(v * kRound) / kRound; }

template <class It>
json rounded_array(It first, It last) {
  json a = json::array();
  for (It it = first; it != last; ++it) a.push_back(rounded(static_cast<double>(*it)));
  return a;
}

std::string geom_type_name(int type) {
  switch (type) {
    case mjGEOM_MESH:
      return "mesh";
    case mjGEOM_BOX:
      return "box";
    case mjGEOM_CAPSULE:
      return "capsule";
    case mjGEOM_CYLINDER:
      return "cylinder";
    case mjGEOM_SPHERE:
      return "sphere";
    case mjGEOM_ELLIPSOID:
      return "ellipsoid";
    default:
      return "";  // planes and height fields are not drawn
  }
}

// "A", "B" or "C" for a finger segment geom (finger<k>_<letter>), "" otherwise.
std::string segment_letter(const std::string& name) {
  for (const std::string& s : grasp::finger_segment_names()) {
    if (s == name) return name.substr(name.size() - 1);
  }
  return "";
}

json obb_json(const Obb& box) {
  json axes = json::array();  // row-major, as the poses
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) axes.push_back(rounded(box.axes(r, c)));
  return {{"center", rounded_array(box.center.data(), box.center.data() + 3)},
          {"axes", axes},
          {"half", rounded_array(box.half.data(), box.half.data() + 3)}};
}

json contacts_json(const std::vector<RecordedContact>& contacts, const std::vector<int>& drawn) {
  json out = json::array();
  for (const RecordedContact& c : contacts) {
    const int g1 = drawn[static_cast<std::size_t>(c.geom1)];
    const int g2 = drawn[static_cast<std::size_t>(c.geom2)];
    if (g1 < 0 || g2 < 0) continue;  // a plane
    out.push_back({{"geoms", {g1, g2}},
                   {"pos", rounded_array(c.pos.begin(), c.pos.end())},
                   {"normal", rounded_array(c.normal.begin(), c.normal.end())},
                   {"dist", rounded(c.dist)}});
  }
  return out;
}

// The support body of the scene's "grasp" section (drive_config.h), -1 when it names none (the
// examples stand on a floor plane, which is not drawn).
int support_body(const mjModel* m, const std::string& scene) {
  const std::string config = mujoco::pair_config_path(scene);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(config, ec)) return -1;
  const std::optional<grasp::DriveConfig> drive = grasp::load_drive_config(config);
  if (!drive || drive->support.empty()) return -1;
  return mj_name2id(m, mjOBJ_BODY, drive->support.c_str());
}

// Whether body b is `root` (not the world) or below it.
bool in_subtree(const mjModel* m, int b, int root) {
  for (; b > 0; b = m->body_parentid[b])
    if (b == root) return true;
  return false;
}

}  // namespace

std::vector<Obb> boxes_at_depth(const ObbTree& tree, int depth) {
  std::vector<Obb> out;
  // Depth-first: the first child of an internal node is the next node, the second `right`.
  std::vector<std::pair<int, int>> stack = {{0, 0}};
  const auto& nodes = tree.nodes();
  while (!stack.empty()) {
    const auto [i, d] = stack.back();
    stack.pop_back();
    const ObbNode& n = nodes[static_cast<std::size_t>(i)];
    if (d == depth || n.is_leaf()) {
      out.push_back(n.box);
      continue;
    }
    stack.emplace_back(n.right, d + 1);
    stack.emplace_back(i + 1, d + 1);
  }
  return out;
}

std::vector<double> step_medians(const std::vector<std::vector<double>>& step_ns) {
  std::vector<double> out;
  if (step_ns.empty()) return out;
  for (std::size_t s = 0; s < step_ns.front().size(); ++s) {
    std::vector<double> v;
    for (const auto& repeat : step_ns) v.push_back(repeat[s]);
    out.push_back(median(v));
  }
  return out;
}

void write_trajectory(const std::string& path, const Recording& r, const MeshScene* scene,
                      const StepTimes& times, const std::string& named) {
  const mujoco::ModelPtr model = mujoco::load_model(r.scene);
  const mjModel* m = model.get();
  if (r.ngeom != m->ngeom || r.qpos.size() != r.xpos.size() || r.contacts.size() != r.xpos.size())
    throw std::runtime_error(r.scene + ": the recording does not match the scene");

  // The drawn geoms (all but planes and height fields) and the meshes they use, renumbered.
  std::vector<int> drawn(static_cast<std::size_t>(m->ngeom), -1);
  std::vector<int> geom_ids;
  std::vector<int> mesh_index(static_cast<std::size_t>(m->nmesh), -1);
  json meshes = json::array();
  json geoms = json::array();
  const int object_body = mj_name2id(m, mjOBJ_BODY, "object");
  const int support = support_body(m, r.scene);
  for (int g = 0; g < m->ngeom; ++g) {
    const std::string type = geom_type_name(m->geom_type[g]);
    if (type.empty()) continue;
    const char* raw_name = mj_id2name(m, mjOBJ_GEOM, g);
    const std::string name = raw_name ? raw_name : "geom" + std::to_string(g);
    const std::string letter = segment_letter(name);
    const int body = m->geom_bodyid[g];
    json j = {{"name", name},
              {"type", type},
              {"size", rounded_array(m->geom_size + 3 * g, m->geom_size + 3 * g + 3)},
              {"role", !letter.empty()                ? "segment"
                       : body == object_body          ? "object"
                       : in_subtree(m, body, support) ? "support"
                                                      : "hand"},
              {"segment", letter},
              {"collides", m->geom_contype[g] != 0 || m->geom_conaffinity[g] != 0}};
    const int mesh = m->geom_dataid[g];
    if (m->geom_type[g] == mjGEOM_MESH && mesh >= 0) {
      auto& index = mesh_index[static_cast<std::size_t>(mesh)];
      if (index < 0) {
        index = static_cast<int>(meshes.size());
        const int v0 = m->mesh_vertadr[mesh];
        const int f0 = m->mesh_faceadr[mesh];
        const char* mesh_name = mj_id2name(m, mjOBJ_MESH, mesh);
        json mj = {
            {"name", mesh_name ? mesh_name : "mesh" + std::to_string(mesh)},
            {"vertices",
             rounded_array(m->mesh_vert + 3 * v0, m->mesh_vert + 3 * (v0 + m->mesh_vertnum[mesh]))},
            {"faces", json(std::vector<int>(m->mesh_face + 3 * f0,
                                            m->mesh_face + 3 * (f0 + m->mesh_facenum[mesh])))}};
        // The OBB tree the study built for this mesh, when a served pair uses it.
        if (scene && std::count(scene->meshes().begin(), scene->meshes().end(), mesh)) {
          json levels = json::array();
          for (int depth = 0; depth < kObbLevels; ++depth) {
            json level = json::array();
            for (const Obb& box : boxes_at_depth(scene->tree(mesh), depth))
              level.push_back(obb_json(box));
            levels.push_back(level);
          }
          mj["obb_levels"] = levels;
        }
        meshes.push_back(mj);
      }
      j["mesh"] = index;
    }
    drawn[static_cast<std::size_t>(g)] = static_cast<int>(geom_ids.size());
    geom_ids.push_back(g);
    geoms.push_back(j);
  }

  // Per step: poses, our contacts, and MuJoCo's native ones at the same joint positions (the
  // collision function is not installed here: record_grasp's grasp has uninstalled it).
  const mujoco::DataPtr data(mj_makeData(m));
  mjData* d = data.get();
  json steps = json::array();
  for (std::size_t s = 0; s < r.xpos.size(); ++s) {
    json pos = json::array();
    json rot = json::array();
    for (int g : geom_ids) {
      const auto k = static_cast<std::size_t>(g);
      for (std::size_t i = 0; i < 3; ++i) pos.push_back(rounded(r.xpos[s][3 * k + i]));
      for (std::size_t i = 0; i < 9; ++i) rot.push_back(rounded(r.xmat[s][9 * k + i]));
    }
    std::copy(r.qpos[s].begin(), r.qpos[s].end(), d->qpos);
    mj_forward(m, d);
    steps.push_back({{"pos", pos},
                     {"rot", rot},
                     {"contacts", contacts_json(r.contacts[s], drawn)},
                     {"native_contacts", contacts_json(recorded_contacts(d), drawn)}});
  }
  json times_json = json::object();
  for (const auto& [method, ns] : times) times_json[method] = ns;
  json out = {{"schema", 1},
              {"name", r.name},
              {"scene", r.scene},
              {"recorded_with", r.native ? "native" : "graspcd, " + r.grasp.method},
              {"grasp_steps", r.steps()},
              {"first_contact", r.grasp.first_contact},
              {"segment_names", grasp::finger_segment_names()},
              {"held", r.grasp.held},
              {"gravity", rounded_array(m->opt.gravity, m->opt.gravity + 3)},
              {"meshes", meshes},
              {"geoms", geoms},
              {"steps", steps},
              {"times_ns", times_json}};
  add_envelope(out);
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);
  std::ofstream file(path);
  file << out.dump() << "\n";
  if (!file) throw io::InputError(named.empty() ? path : named, 0, "cannot write");
}

bool is_trajectory_file(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return false;
  std::ifstream in(path, std::ios::binary);
  const json doc = json::parse(in, nullptr, false);
  if (!doc.is_object()) return false;
  const auto graspcd = doc.find("graspcd");
  return graspcd != doc.end() && graspcd->is_object() && graspcd->contains("version") &&
         doc.contains("schema") && doc.contains("meshes") && doc.contains("geoms") &&
         doc.contains("steps") && doc["steps"].is_array();
}

void check_trajectory_target(const std::string& out, const std::string& scene, bool force) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(out, ec)) return;
  const std::string config = mujoco::pair_config_path(scene);
  const auto refuse = [&out](const std::string& what) {
    return io::InputError(out, 0,
                          "is " + what +
                              " this run reads: not overwritten (write the trajectory "
                              "elsewhere)");
  };
  if (io::same_file(out, scene)) throw refuse("the scene");
  if (io::same_file(out, config)) throw refuse("the pair config");
  for (const std::string& input : mujoco::scene_files(scene)) {
    if (io::same_file(out, input)) throw refuse("a file the scene names (" + input + "), which");
  }
  if (!fs::is_regular_file(out, ec)) return;  // a device (/dev/stdout) is written directly
  if (!force && !is_trajectory_file(out)) {
    throw io::InputError(out, 0,
                         "exists and is not a trajectory graspcd wrote: not overwritten; --force "
                         "replaces it");
  }
}

void export_grasp(const std::string& scene, const std::string& path,
                  const TrajectoryOptions& options) {
  const mujoco::ScopedMujocoErrors mujoco_errors(scene);  // MuJoCo's errors name the scene
  const Recording r =
      record_grasp(std::filesystem::path(scene).stem().string(), scene, false, options.max_steps);
  const mujoco::ModelPtr model = mujoco::load_model(scene);
  const int finger = mj_name2id(model.get(), mjOBJ_GEOM, "finger1_A");
  if (finger < 0 || model->geom_type[finger] != mjGEOM_MESH) {
    write_trajectory(path, r, nullptr, {}, options.out_name);
    return;
  }
  const MeshScene mesh_scene(scene);
  StepTimes times;
  for (Method m : options.methods) {
    const auto querier = make_detector_querier(m, DetectorOptions{}, QueryMode::kAllContacts);
    const ReplayStats st = replay(mesh_scene, r, *querier, options.repeats);
    times.emplace_back(method_name(m), step_medians(st.step_ns));
  }
  write_trajectory(path, r, &mesh_scene, times, options.out_name);
}

}  // namespace graspcd::study
