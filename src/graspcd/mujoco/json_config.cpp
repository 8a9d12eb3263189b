#include "graspcd/mujoco/json_config.h"

#include <algorithm>
#include <regex>
#include <stdexcept>

#include "graspcd/mujoco/input_error.h"

namespace graspcd::mujoco {
namespace {

// The 1-based line of byte offset `at` (0 = before the first byte) of `text`.
std::size_t line_of(const std::string& text, std::size_t at) {
  at = std::min(at, text.size());
  return 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + at, '\n'));
}

}  // namespace

nlohmann::json parse_json_config(const std::string& text, const std::string& source) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    // "[json.exception.parse_error.101] parse error at line 2, column 5: MESSAGE": the id and
    // the position go, the line comes first.
    std::string message =
        std::regex_replace(e.what(), std::regex(R"(^\[json\.exception\.[^\]]*\] )"), "");
    message =
        std::regex_replace(message, std::regex(R"(^parse error at line \d+, column \d+: )"), "");
    for (char& c : message) {
      if (c == '\n' || c == '\r') c = ' ';
    }
    std::size_t line = 0;
    if (const auto* parse = dynamic_cast<const nlohmann::json::parse_error*>(&e)) {
      // byte: 1-based position of the character that failed (0: unknown).
      if (parse->byte > 0) line = line_of(text, parse->byte - 1);
    } else {
      // out_of_range 406: "number overflow parsing '1e999'": the line of that literal.
      std::smatch literal;
      if (std::regex_search(message, literal, std::regex("'([^']+)'"))) {
        const std::size_t at = text.find(literal[1].str());
        if (at != std::string::npos) line = line_of(text, at);
      }
    }
    refuse(source, "bad JSON: " + message, line);
  }
}

}  // namespace graspcd::mujoco
