// The pair config's parser (pair_config.h).
#include "graspcd/mujoco/pair_config.h"

#include <mujoco/mujoco.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "graspcd/mujoco/input_error.h"
#include "graspcd/mujoco/json_config.h"

namespace graspcd::mujoco {
namespace {

// A contact budget of the config: an integer in 1 .. mjMAXCONPAIR (what MuJoCo takes per pair).
int contact_budget(const nlohmann::json& v, const std::string& field, const std::string& source) {
  if (!v.is_number_integer() || v.get<long long>() < 1 || v.get<long long>() > mjMAXCONPAIR) {
    throw io::InputError(
        source, 0, "'" + field + "' must be an integer from 1 to " + std::to_string(mjMAXCONPAIR));
  }
  return v.get<int>();
}

// The "pairs" array: one PairPattern per entry, with the entry's own contact budget.
std::vector<PairPattern> parse_pairs(const nlohmann::json& value, const std::string& source) {
  if (!value.is_array()) throw io::InputError(source, 0, "'pairs' must be an array");
  std::vector<PairPattern> out;
  for (const auto& p : value) {
    if (!p.is_object() || !p.contains("a") || !p.contains("b") || !p.at("a").is_string() ||
        !p.at("b").is_string()) {
      throw io::InputError(
          source, 0, "each entry of 'pairs' must be {\"a\": \"pattern\", \"b\": \"pattern\"}");
    }
    PairPattern pattern{p.at("a").get<std::string>(), p.at("b").get<std::string>(), {}, {}};
    for (const auto& [key, v] : p.items()) {
      if (key == "max_contacts") {
        pattern.max_contacts = contact_budget(v, "max_contacts", source);
      } else if (key == "max_patch_contacts") {
        pattern.max_patch_contacts = contact_budget(v, "max_patch_contacts", source);
      } else if (key != "a" && key != "b") {
        throw io::InputError(source, 0, "unknown field '" + key + "' in an entry of 'pairs'");
      }
    }
    out.push_back(std::move(pattern));
  }
  return out;
}

}  // namespace

RegistryConfig parse_registry_config(const std::string& json_text, const std::string& source) {
  const nlohmann::json j = parse_json_config(json_text, source);
  if (!j.is_object()) throw io::InputError(source, 0, "the config must be a JSON object");
  RegistryConfig c;
  const auto positive_int = [&](const char* field) {
    const auto& v = j.at(field);
    if (!v.is_number_integer() || v.get<long long>() < 1 || v.get<long long>() > (1ll << 30)) {
      throw io::InputError(source, 0, std::string("'") + field + "' must be an integer >= 1");
    }
    return v.get<int>();
  };
  for (const auto& [field, value] : j.items()) {
    if (field == "method") {
      if (!value.is_string()) throw io::InputError(source, 0, "'method' must be a string");
      const auto m = parse_method(value.get<std::string>());
      if (!m) throw io::InputError(source, 0, "unknown method '" + value.get<std::string>() + "'");
      c.method = *m;
    } else if (field == "cap") {
      c.detector.cap = positive_int("cap");
    } else if (field == "switch") {
      c.detector.switch_passes = positive_int("switch");
    } else if (field == "cache_slots") {
      c.detector.cache_slots = static_cast<std::size_t>(positive_int("cache_slots"));
    } else if (field == "max_depth") {
      if (!value.is_number() || !(value.get<double>() > 0)) {
        throw io::InputError(source, 0, "'max_depth' must be a number > 0");
      }
      c.max_depth = value.get<double>();
    } else if (field == "max_contacts") {
      c.manifold.max_per_pair = contact_budget(value, "max_contacts", source);
    } else if (field == "max_patch_contacts") {
      c.manifold.max_per_patch = contact_budget(value, "max_patch_contacts", source);
    } else if (field == "reduction") {
      if (!value.is_string() || (value != "support" && value != "moment" && value != "force")) {
        throw io::InputError(source, 0, "'reduction' must be \"support\", \"moment\" or \"force\"");
      }
      c.manifold.reduction = value == "moment"  ? ManifoldReduction::kMoment
                             : value == "force" ? ManifoldReduction::kForce
                                                : ManifoldReduction::kSupport;
    } else if (field == "front_list") {
      if (!value.is_boolean())
        throw io::InputError(source, 0, "'front_list' must be true or false");
      c.front_list = value.get<bool>();
    } else if (field == "contact_reuse") {
      if (!value.is_number() || !(value.get<double>() >= 0) ||
          !(value.get<double>() <= RegistryConfig::kMaxContactReuse)) {
        throw io::InputError(source, 0, "'contact_reuse' must be a number of metres in [0, 0.001]");
      }
      c.contact_reuse = value.get<double>();
    } else if (field == "grasp") {
      // The grasp experiment's section: read from the file by graspcd_grasp (graspcd/grasp/
      // drive_config.h), accepted unread here.
    } else if (field == "pairs") {
      c.patterns = parse_pairs(value, source);
    } else {
      throw io::InputError(source, 0, "unknown field '" + field + "'");
    }
  }
  if (!j.contains("pairs")) throw io::InputError(source, 0, "missing field 'pairs'");
  if (c.patterns.empty())
    throw io::InputError(source, 0, "'pairs' is empty: the config would serve no pair");
  return c;
}

std::string pair_config_path(const std::string& scene_path) {
  std::filesystem::path p(scene_path);
  p.replace_extension(".pairs.json");
  return p.string();
}

RegistryConfig load_registry_config(const std::string& path, const SceneNames& names) {
  return parse_registry_config(read_config_file(path), names.file(path));
}

}  // namespace graspcd::mujoco
