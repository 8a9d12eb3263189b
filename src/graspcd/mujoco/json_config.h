// The JSON of graspcd's config files (the pair config, pair_config.h, and its "grasp" section,
// graspcd/grasp/drive_config.h), parsed in one place so that every syntax error reads the same:
// one line "SOURCE:LINE: bad JSON: MESSAGE" (docs/bad-input.md). Needs nlohmann-json
// (nlohmann-json3-dev), which is not part of the installed interface otherwise.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace graspcd::mujoco {

// Parses `text`. A syntax error, or a number that overflows a double, throws std::runtime_error
// "SOURCE:LINE: bad JSON: MESSAGE": LINE is 1-based (the line of nlohmann's byte position, or of
// the overflowing literal), MESSAGE nlohmann's without its exception id and position. A key given
// twice in one object (nlohmann would keep the last) throws "SOURCE:LINE: duplicate key 'K' (lines
// A and B)".
nlohmann::json parse_json_config(const std::string& text, const std::string& source);

// The text of the config file `path`, read in one place for the pair config and its "grasp"
// section. Throws InputError (input_error.h) "PATH: not a regular file" for a folder, a FIFO or a
// device, and "PATH: cannot open the config file".
std::string read_config_file(const std::string& path);

}  // namespace graspcd::mujoco
