// The one clock of graspcd's timings: std::chrono::steady_clock, durations in whole nanoseconds.
#pragma once

#include <chrono>
#include <cstdint>

namespace graspcd {

using Clock = std::chrono::steady_clock;

// Nanoseconds from `from` to `to` (0 when `to` is not later).
inline std::uint64_t elapsed_ns(Clock::time_point from, Clock::time_point to) {
  const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(to - from).count();
  return ns > 0 ? static_cast<std::uint64_t>(ns) : 0;
}

// Nanoseconds since `from`.
inline std::uint64_t elapsed_ns(Clock::time_point from) { return elapsed_ns(from, Clock::now()); }

// Seconds since `from`.
inline double seconds_since(Clock::time_point from) {
  return std::chrono::duration<double>(Clock::now() - from).count();
}

}  // namespace graspcd
