#include "graspcd/mujoco/json_config.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "graspcd/mujoco/input_error.h"

namespace graspcd::mujoco {
namespace {

// The 1-based line of byte offset `at` (0 = before the first byte) of `text`.
std::size_t line_of(const std::string& text, std::size_t at) {
  at = std::min(at, text.size());
  return 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + at, '\n'));
}

// Refuses a key given twice in one object of `text`, which nlohmann has parsed: nlohmann keeps the
// last silently, and its SAX interface gives no positions, so the keys are found here by a scan
// that counts lines. A key that does not decode is no key to compare.
void refuse_duplicate_keys(const std::string& text, const std::string& source) {
  struct Frame {
    bool object = false;
    bool expecting_key = false;
    std::map<std::string, std::size_t> key_lines;
  };
  std::vector<Frame> frames;
  std::size_t line = 1;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
    } else if (c == '{' || c == '[') {
      frames.push_back(Frame{c == '{', c == '{', {}});
    } else if (c == '}' || c == ']') {
      if (!frames.empty()) frames.pop_back();
    } else if (c == ',') {
      if (!frames.empty() && frames.back().object) frames.back().expecting_key = true;
    } else if (c == '"') {
      const std::size_t begin = i;
      for (++i; i < text.size() && text[i] != '"'; ++i) {
        if (text[i] == '\\') ++i;
      }
      if (frames.empty() || !frames.back().object || !frames.back().expecting_key) continue;
      frames.back().expecting_key = false;
      const nlohmann::json decoded =
          nlohmann::json::parse(text.substr(begin, i + 1 - begin), nullptr, false);
      if (!decoded.is_string()) continue;
      const std::string key = decoded.get<std::string>();
      const auto [at, inserted] = frames.back().key_lines.emplace(key, line);
      if (!inserted) {
        throw io::InputError(source, line,
                             "duplicate key '" + key + "' (lines " + std::to_string(at->second) +
                                 " and " + std::to_string(line) + ")");
      }
    }
  }
}

}  // namespace

nlohmann::json parse_json_config(const std::string& text, const std::string& source) {
  // nlohmann's reader ends its input at a NUL byte and would take what comes after for nothing.
  if (const std::size_t nul = text.find('\0'); nul != std::string::npos) {
    throw io::InputError(source, line_of(text, nul),
                         "a NUL byte in the config (byte " + std::to_string(nul + 1) + ")");
  }
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    // "[json.exception.parse_error.101] parse error at line 2, column 5: MESSAGE": the id and
    // the position go, the line comes first.
    std::string message =
        std::regex_replace(e.what(), std::regex(R"(^\[json\.exception\.[^\]]*\] )"), "");
    message =
        std::regex_replace(message, std::regex(R"(^parse error at line \d+, column \d+: )"), "");
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
    throw io::InputError(source, line, "bad JSON: " + message);
  }
  refuse_duplicate_keys(text, source);
  return j;
}

std::string read_config_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec)) {
    throw io::InputError(path, 0, "not a regular file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw io::InputError(path, 0, "cannot open the config file");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace graspcd::mujoco
