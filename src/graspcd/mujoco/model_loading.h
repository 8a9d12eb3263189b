// Loading an MJCF scene for graspcd: the checks before MuJoCo reads it (scene_check.h), MuJoCo's
// own reader with its messages captured, and the compiled numbers (model_check.h). Every refusal
// is an InputError that carries the file, the line and the message apart and prints as one line.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

#include "graspcd/mujoco/mujoco_ptr.h"

namespace graspcd::mujoco {

// A scene or config that cannot be used: what() is one line, "FILE: MESSAGE", or
// "FILE:LINE: MESSAGE" when the line is known (line() > 0).
class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, const std::string& message, std::size_t line = 0)
      : std::runtime_error(file + (line > 0 ? ":" + std::to_string(line) : "") + ": " + message),
        file_(file),
        message_(message),
        line_(line) {}
  const std::string& file() const { return file_; }
  const std::string& message() const { return message_; }
  std::size_t line() const { return line_; }

 private:
  std::string file_;
  std::string message_;
  std::size_t line_ = 0;
};

// Loads an MJCF file. A missing file or MuJoCo's error become an InputError whose message is
// "FILE: <MuJoCo's message on one line>" (mujoco-2.2-notes.md "Errors").
ModelPtr load_model(const std::string& path);

// Joins MuJoCo's multi-line error text into one line (line breaks become "; ", blanks trimmed).
std::string join_lines(const std::string& text);

}  // namespace graspcd::mujoco
