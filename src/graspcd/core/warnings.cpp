#include "graspcd/core/warnings.h"

namespace graspcd {

void WarningSink::add(const std::string& code, const std::string& message) {
  const std::lock_guard<std::mutex> lock(mutex_);
  for (Warning& w : warnings_) {
    if (w.code == code && w.message == message) {
      ++w.count;
      return;
    }
  }
  warnings_.push_back(Warning{code, message, 1});
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
  if (w.count <= 1) return w.message;
  return w.message + " (" + std::to_string(w.count) + " times)";
}

}  // namespace graspcd
