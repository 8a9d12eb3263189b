// The error of a scene or config that cannot be used, with its file, line and message apart
// (model_loading.h, scene_check.h, and the grasp experiment's configs).
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

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

// Refuses a scene or config: throws InputError(file, message, line).
[[noreturn]] inline void refuse(const std::string& file, const std::string& message,
                                std::size_t line = 0) {
  throw InputError(file, message, line);
}

}  // namespace graspcd::mujoco
