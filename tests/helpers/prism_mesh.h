// A closed prism about the z axis as OBJ text, for tests that grasp a new object: a star (points
// and notches at two radii, non-convex) or, with one radius, a regular polygon's prism standing
// for a cylinder.
#pragma once

#include <cmath>
#include <sstream>
#include <string>

namespace graspcd::testing {

// `n` points around the z axis, the even ones at radius r_out and the odd ones at r_in, from
// z = 0 to h, capped at both ends (each cap a fan about its centre); outward faces, every
// coordinate printed with 17 digits.
inline std::string prism_obj(double r_out, double r_in, double h, int n) {
  std::ostringstream obj;
  obj.precision(17);
  for (double z : {0.0, h}) {
    for (int i = 0; i < n; ++i) {
      const double a = 2 * 3.14159265358979323846 * i / n;
      const double r = i % 2 == 0 ? r_out : r_in;
      obj << "v " << r * std::cos(a) << ' ' << r * std::sin(a) << ' ' << z << '\n';
    }
  }
  obj << "v 0 0 0\nv 0 0 " << h << '\n';  // the caps' centres: vertices 2n+1 and 2n+2
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    const int b0 = i + 1, b1 = j + 1, t0 = n + i + 1, t1 = n + j + 1;
    obj << "f " << b0 << ' ' << b1 << ' ' << t1 << "\nf " << b0 << ' ' << t1 << ' ' << t0 << '\n';
    obj << "f " << 2 * n + 1 << ' ' << b1 << ' ' << b0 << "\nf " << 2 * n + 2 << ' ' << t0 << ' '
        << t1 << '\n';
  }
  return obj.str();
}

}  // namespace graspcd::testing
