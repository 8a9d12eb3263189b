#include "graspcd/grasp/drive_config.h"

#include <nlohmann/json.hpp>
#include <stdexcept>

#include "graspcd/mujoco/input_error.h"
#include "graspcd/mujoco/json_config.h"

namespace graspcd::grasp {
namespace {

DriveConfig parse_drive(const nlohmann::json& j, const std::string& source) {
  const auto where = [&](const std::string& what) { return "'grasp': " + what; };
  if (!j.is_object()) throw io::InputError(source, 0, where("must be an object"));
  const auto text = [&](const nlohmann::json& v, const std::string& name) {
    if (!v.is_string() || v.get<std::string>().empty()) {
      throw io::InputError(source, 0, where("'" + name + "' must be a non-empty string"));
    }
    return v.get<std::string>();
  };
  const auto number = [&](const nlohmann::json& v, const std::string& name) {
    if (!v.is_number()) throw io::InputError(source, 0, where("'" + name + "' must be a number"));
    return v.get<double>();
  };
  DriveConfig d;
  for (const auto& [field, value] : j.items()) {
    if (field == "object") {
      d.object = text(value, field);
    } else if (field == "hand") {
      d.hand = text(value, field);
    } else if (field == "support") {
      d.support = text(value, field);
    } else if (field == "close") {
      if (!value.is_array() || value.empty())
        throw io::InputError(source, 0, where("'close' must be a non-empty array"));
      for (const auto& c : value) {
        if (!c.is_object())
          throw io::InputError(source, 0, where("each entry of 'close' must be an object"));
        CloseDrive cd;
        for (const auto& [f, v] : c.items()) {
          if (f == "actuator") {
            cd.actuator = text(v, f);
          } else if (f == "step") {
            cd.step = number(v, f);
            if (!(cd.step > 0)) throw io::InputError(source, 0, where("'step' must be > 0"));
          } else if (f == "squeeze") {
            cd.squeeze = number(v, f);
          } else if (f == "touch") {
            if (!v.is_array() || v.empty())
              throw io::InputError(source, 0, where("'touch' must be a non-empty array"));
            for (const auto& t : v) cd.touch.push_back(text(t, "touch"));
          } else {
            throw io::InputError(source, 0, where("unknown field '" + f + "' in 'close'"));
          }
        }
        if (cd.actuator.empty() || cd.step <= 0 || cd.touch.empty()) {
          throw io::InputError(source, 0,
                               where("each entry of 'close' needs 'actuator', 'step' and 'touch'"));
        }
        d.close.push_back(cd);
      }
    } else if (field == "lift") {
      if (!value.is_object() || !value.contains("actuator") || !value.contains("by") ||
          value.size() != 2) {
        throw io::InputError(source, 0, where("'lift' must be {\"actuator\": NAME, \"by\": CTRL}"));
      }
      d.lift_actuator = text(value.at("actuator"), "actuator");
      d.lift_by = number(value.at("by"), "by");
    } else {
      throw io::InputError(source, 0, where("unknown field '" + field + "'"));
    }
  }
  if (d.hand.empty() || d.close.empty() || d.lift_actuator.empty()) {
    throw io::InputError(source, 0, where("needs 'hand', 'close' and 'lift'"));
  }
  return d;
}

}  // namespace

std::optional<DriveConfig> parse_drive_config(const std::string& json_text,
                                              const std::string& source) {
  const nlohmann::json j = mujoco::parse_json_config(json_text, source);
  if (!j.is_object() || !j.contains("grasp")) return std::nullopt;
  return parse_drive(j.at("grasp"), source);
}

std::optional<DriveConfig> load_drive_config(const std::string& path,
                                             const mujoco::SceneNames& names) {
  return parse_drive_config(mujoco::read_config_file(path), names.file(path));
}

}  // namespace graspcd::grasp
