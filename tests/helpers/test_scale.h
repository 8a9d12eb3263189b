// GRASPCD_TEST_SCALE (default 1) scales the number of random cases of the heavy randomized tests;
// the sanitizer build runs them at 0.1 (docs/testing.md).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace graspcd::testing {

inline double test_scale() {
  const char* s = std::getenv("GRASPCD_TEST_SCALE");
  if (s == nullptr) return 1.0;
  const double v = std::strtod(s, nullptr);
  return v > 0 && std::isfinite(v) ? v : 1.0;
}

// n scaled, and never below `minimum`, so that a scaled-down run still means something.
inline int scaled(int n, int minimum = 8) {
  return std::max(minimum, static_cast<int>(std::lround(n * test_scale())));
}

}  // namespace graspcd::testing
