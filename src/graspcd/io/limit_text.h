// A number shown beside the limit it broke, printed with enough digits to differ from the limit:
// a depth of 0.5004 mm is "0.5004 mm", never "0.5 mm", beside "at most 0.5 mm allowed".
#pragma once

#include <iomanip>
#include <sstream>
#include <string>

namespace graspcd::io {

// `value` with `decimals` decimals (std::fixed), or more, up to `decimals` + 8, while it prints
// as `limit` does with as many.
inline std::string fixed_beyond(double value, double limit, int decimals) {
  const auto text = [](double v, int d) {
    std::ostringstream out;
    out << std::fixed << std::setprecision(d) << v;
    return out.str();
  };
  int d = decimals;
  while (d < decimals + 8 && text(value, d) == text(limit, d)) ++d;
  return text(value, d);
}

// `value` with `digits` significant digits, or more, up to `digits` + 8, while it prints as
// `limit` does with as many.
inline std::string significant_beyond(double value, double limit, int digits) {
  const auto text = [](double v, int d) {
    std::ostringstream out;
    out << std::setprecision(d) << v;
    return out.str();
  };
  int d = digits;
  while (d < digits + 8 && text(value, d) == text(limit, d)) ++d;
  return text(value, d);
}

}  // namespace graspcd::io
