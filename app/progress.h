// The progress of a long command (decompose, trajectory, validate, study) on stderr, whether or
// not stderr is a terminal (docs/design.md, "The command line"):
//  - on a terminal (isatty), one line "[TAG] text, 12 s, about 30 s left" rewritten as the work
//    goes (at most four times a second, and every second for the clock);
//  - otherwise (a log file, a pipe, a Slurm job's output) one such line every few seconds,
//    GRASPCD_PROGRESS_SECONDS apart (default kProgressSeconds; 0: at every update), so that a
//    long run shows it is alive and how far it got without filling the log;
// and, either way, one final line "[TAG] text" when the work is done. The estimate of the time
// left comes from the share of the work done, when the command knows it: the time so far times
// (1 - share) / share ("about"; "at most" when the share is a lower bound, e.g. a closing that
// may end before --max-steps). A background thread prints the lines, so that a single long call
// (HACD, CGAL's Hausdorff distance, V-HACD in node) still shows its clock.
#pragma once

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace graspcd::cli {

// The seconds between two progress lines when stderr is not a terminal, by default.
inline constexpr double kProgressSeconds = 5.0;

class Progress {
 public:
  explicit Progress(std::string tag);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  bool terminal() const { return tty_; }
  // The work's state now: what is being done and, when known, the share of the work done (0 to
  // 1; negative: unknown, no estimate). `at_least`: the share is a lower bound, so the estimate
  // of the time left is an upper bound ("at most").
  void update(const std::string& text, double share = -1, bool at_least = false);
  // The final line (always printed); the progress lines stop.
  void done(const std::string& text);
  // A line of its own on stderr while the work goes on (e.g. an object refused), printed between
  // progress lines.
  void note(const std::string& line);
  // Text on stdout while the work goes on (e.g. a table's rows as they are made), flushed at
  // once; on a terminal the progress line is cleared first and drawn again after.
  void print(const std::string& text);

  // "12 s", "3 min 20 s", "1 h 5 min": a duration as a progress line says it.
  static std::string duration(double seconds);

 private:
  using Clock = std::chrono::steady_clock;
  void run();
  void print_locked();
  std::string line_locked() const;

  std::string tag_;
  bool tty_;
  double period_;  // seconds between lines when stderr is not a terminal
  Clock::time_point start_ = Clock::now();
  Clock::time_point printed_ = Clock::now();
  std::mutex mutex_;
  std::condition_variable wake_;
  std::string text_;
  double share_ = -1;
  bool at_least_ = false;
  bool changed_ = false;
  bool shown_ = false;  // a terminal line is on screen
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace graspcd::cli
