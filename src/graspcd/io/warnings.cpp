#include "graspcd/io/warnings.h"

#include <utility>

#include "graspcd/io/input_error.h"

namespace graspcd {

void WarningSink::add(const std::string& code, const std::string& message,
                      const std::string& source) {
  const std::lock_guard<std::mutex> lock(mutex_);
  for (Warning& w : warnings_) {
    if (w.code == code && w.message == message) {
      ++w.count;
      return;
    }
  }
  warnings_.push_back(Warning{code, message, 1, source});
}

void WarningSink::add(const std::string& code, const std::string& message) {
  static const std::pair<const char*, const char*> kSources[] = {
      {"mujoco_", "mujoco"}, {"mesh_", "mesh"}, {"served_", "config"}, {"start_", "scene"}};
  std::string source = "graspcd";
  for (const auto& [prefix, name] : kSources) {
    if (code.rfind(prefix, 0) == 0) source = name;
  }
  add(code, message, source);
}

std::vector<Warning> WarningSink::list() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return warnings_;
}

bool WarningSink::empty() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return warnings_.empty();
}

void WarningSink::clear() {
  const std::lock_guard<std::mutex> lock(mutex_);
  warnings_.clear();
}

WarningSink& warnings() {
  static WarningSink sink;
  return sink;
}

std::string warning_line(const Warning& w) {
  if (w.count <= 1) return io::one_line(w.message);
  return io::one_line(w.message) + " (" + std::to_string(w.count) + " times)";
}

}  // namespace graspcd
