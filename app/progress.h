// The progress of a long command (decompose, trajectory, validate, study) on stderr: on a terminal
// (isatty), each update rewrites one line "[TAG] text"; otherwise the updates are left out and only
// the final line is printed (a log stays short). docs/design.md, "The command line".
#pragma once

#include <unistd.h>

#include <iostream>
#include <string>
#include <utility>

namespace graspcd::cli {

class Progress {
 public:
  explicit Progress(std::string tag) : tag_(std::move(tag)), tty_(isatty(STDERR_FILENO) == 1) {}
  ~Progress() {
    if (shown_) std::cerr << "\r\033[K" << std::flush;
  }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  bool terminal() const { return tty_; }
  // On a terminal only: the line rewritten.
  void update(const std::string& text) {
    if (!tty_) return;
    std::cerr << "\r\033[K[" << tag_ << "] " << text << std::flush;
    shown_ = true;
  }
  // Always: the final line.
  void done(const std::string& text) {
    if (shown_) std::cerr << "\r\033[K";
    shown_ = false;
    std::cerr << '[' << tag_ << "] " << text << std::endl;
  }

 private:
  std::string tag_;
  bool tty_;
  bool shown_ = false;
};

}  // namespace graspcd::cli
