// A ring mesh as OBJ text for tests of what a convex hull fills: a closed ring, or an arc of one
// closed by end caps (the pieces of a ring cut up).
#pragma once

#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace graspcd::testing {

// A ring about the z axis (OBJ, outward faces) with a square cross-section: radii r_in to r_out,
// z from -h to h, from angle a0 to a1 (radians) in `n` segments; a whole ring when a1 - a0 is
// 2 pi, else closed by end caps. Faces are turned outward: away from the cross-section's centre
// at the face's angle (for the caps: from the centre of the segment next to them).
inline std::string ring_obj(double r_in, double r_out, double h, double a0, double a1, int n) {
  const double kTwoPi = 2 * std::acos(-1.0);
  const bool whole = std::abs(a1 - a0 - kTwoPi) < 1e-9;
  const int rings = whole ? n : n + 1;  // cross-sections
  const double radius[4] = {r_out, r_out, r_in, r_in};
  const double height[4] = {-h, h, h, -h};
  std::vector<std::array<double, 3>> v;
  for (int i = 0; i < rings; ++i) {
    const double a = a0 + (a1 - a0) * i / n;
    for (int j = 0; j < 4; ++j) {
      v.push_back({radius[j] * std::cos(a), radius[j] * std::sin(a), height[j]});
    }
  }
  const double r_mid = (r_in + r_out) / 2;
  const auto centre = [&](double a) {
    return std::array<double, 3>{r_mid * std::cos(a), r_mid * std::sin(a), 0};
  };
  std::string faces;
  const auto face = [&](int p, int q, int r, const std::array<double, 3>& inside) {
    const auto& A = v[static_cast<std::size_t>(p)];
    const auto& B = v[static_cast<std::size_t>(q)];
    const auto& C = v[static_cast<std::size_t>(r)];
    const double u[3] = {B[0] - A[0], B[1] - A[1], B[2] - A[2]};
    const double w[3] = {C[0] - A[0], C[1] - A[1], C[2] - A[2]};
    const double nrm[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
                           u[0] * w[1] - u[1] * w[0]};
    double out = 0;
    for (int k = 0; k < 3; ++k) out += nrm[k] * ((A[k] + B[k] + C[k]) / 3 - inside[k]);
    if (out < 0) std::swap(q, r);
    faces += "f " + std::to_string(p + 1) + ' ' + std::to_string(q + 1) + ' ' +
             std::to_string(r + 1) + '\n';
  };
  for (int i = 0; i < n; ++i) {
    const int next = (i + 1) % rings;
    const auto inside = centre(a0 + (a1 - a0) * (i + 0.5) / n);
    for (int j = 0; j < 4; ++j) {
      const int a = 4 * i + j, b = 4 * next + j, c = 4 * next + (j + 1) % 4,
                d = 4 * i + (j + 1) % 4;
      face(a, b, c, inside);
      face(a, c, d, inside);
    }
  }
  if (!whole) {
    const auto first = centre(a0 + (a1 - a0) * 0.5 / n);
    const auto last = centre(a0 + (a1 - a0) * (n - 0.5) / n);
    face(0, 1, 2, first);
    face(0, 2, 3, first);
    face(4 * n, 4 * n + 1, 4 * n + 2, last);
    face(4 * n, 4 * n + 2, 4 * n + 3, last);
  }
  std::string out;
  for (const auto& p : v) {
    out += "v " + std::to_string(p[0]) + ' ' + std::to_string(p[1]) + ' ' + std::to_string(p[2]) +
           '\n';
  }
  return out + faces;
}

}  // namespace graspcd::testing
