// The progress lines of a long command (progress.h).
#include "progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <utility>

namespace graspcd::cli {

namespace {

// GRASPCD_PROGRESS_SECONDS when it is a number >= 0, else kProgressSeconds.
double progress_period() {
  const char* text = std::getenv("GRASPCD_PROGRESS_SECONDS");
  if (text == nullptr) return kProgressSeconds;
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  return end != text && *end == '\0' && std::isfinite(v) && v >= 0 ? v : kProgressSeconds;
}

// How often the thread looks at the state: a terminal's line is redrawn at most this often.
constexpr std::chrono::milliseconds kTick{250};

}  // namespace

Progress::Progress(std::string tag)
    : tag_(std::move(tag)), tty_(isatty(STDERR_FILENO) == 1), period_(progress_period()) {
  thread_ = std::thread([this] { run(); });
}

Progress::~Progress() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
  if (shown_) std::cerr << "\r\033[K" << std::flush;
}

std::string Progress::duration(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  if (s < 60) return std::to_string(s) + " s";
  if (s < 3600) {
    return std::to_string(s / 60) + " min" + (s % 60 ? " " + std::to_string(s % 60) + " s" : "");
  }
  const long minutes = (s + 30) / 60;
  return std::to_string(minutes / 60) + " h" +
         (minutes % 60 ? " " + std::to_string(minutes % 60) + " min" : "");
}

std::string Progress::line_locked() const {
  const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
  std::string line = "[" + tag_ + "] " + text_ + "; " + duration(elapsed) + " so far";
  if (share_ > 0 && share_ <= 1) {
    line += std::string(at_least_ ? ", at most " : ", about ") +
            duration(elapsed * (1 - share_) / share_) + " left";
  }
  return line;
}

void Progress::print_locked() {
  if (text_.empty()) return;
  if (tty_) {
    std::cerr << "\r\033[K" << line_locked() << std::flush;
    shown_ = true;
  } else {
    std::cerr << line_locked() << std::endl;
  }
  printed_ = Clock::now();
  changed_ = false;
}

void Progress::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop_) {
    wake_.wait_for(lock, kTick);
    if (stop_) break;
    const double since = std::chrono::duration<double>(Clock::now() - printed_).count();
    if (tty_ ? changed_ || since >= 1.0 : since >= period_ && period_ > 0) print_locked();
  }
}

void Progress::update(const std::string& text, double share, bool at_least) {
  const std::lock_guard<std::mutex> lock(mutex_);
  text_ = text;
  share_ = share;
  at_least_ = at_least;
  changed_ = true;
  if (!tty_ && period_ == 0) print_locked();
}

void Progress::note(const std::string& line) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (shown_) std::cerr << "\r\033[K";
  shown_ = false;
  std::cerr << line << std::endl;
  changed_ = true;
}

void Progress::print(const std::string& text) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (shown_) std::cerr << "\r\033[K" << std::flush;
  shown_ = false;
  std::cout << text << std::flush;
  changed_ = true;
}

void Progress::done(const std::string& text) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
  if (shown_) std::cerr << "\r\033[K";
  shown_ = false;
  std::cerr << '[' << tag_ << "] " << text << std::endl;
}

}  // namespace graspcd::cli
