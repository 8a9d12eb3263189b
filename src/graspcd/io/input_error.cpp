#include "graspcd/io/input_error.h"

#include <utility>

namespace graspcd::io {

namespace {

std::string located(const std::string& file, std::size_t line, const std::string& message) {
  return file + (line > 0 ? ":" + std::to_string(line) : "") + ": " + message;
}

}  // namespace

std::string one_line(const std::string& text) {
  std::string out;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    std::size_t end = text.find_first_of("\r\n", pos);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(pos, end - pos);
    const std::size_t first = line.find_first_not_of(" \t");
    if (first != std::string::npos) {
      if (!out.empty()) out += "; ";
      out += line.substr(first, line.find_last_not_of(" \t") - first + 1);
    }
    pos = end + 1;
  }
  return out;
}

InputError::InputError(std::string file, std::size_t line, std::string message)
    : std::runtime_error(located(file, line, one_line(message))),
      file_(std::move(file)),
      line_(line),
      message_(one_line(message)) {}

}  // namespace graspcd::io
