// The one seeded generator of graspcd: scalars, vectors and rotations drawn from an explicitly
// seeded std::mt19937_64, used by the tests, the benchmarks, the stress suite and the fuzz targets.
//
// Only <random>'s engine is relied on: its output is fixed by the standard, while the
// distributions (std::uniform_real_distribution, std::normal_distribution, std::shuffle) are not
// specified bit for bit and differ between standard libraries. Every draw is its own statement or
// an element of a braced list, which C++ evaluates left to right: two draws as the arguments of
// one call (`Vec3(normal(rng), normal(rng), normal(rng))`) or the operands of one operator come in
// an unspecified order, and the data would differ between compilers. The functions below take
// that care so their callers need not; callers drawing several values at once use uniform_vec3
// or a braced list.
//
// The stress suite's JSON is a contract (docs/stress.md): these functions reproduce its sequence
// of draws exactly, so changing any of them changes every stress case.
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <random>
#include <type_traits>
#include <utility>

#include "graspcd/core/geometry.h"

namespace graspcd::seeded {

using Rng = std::mt19937_64;

inline constexpr double kPi = 3.14159265358979323846;

// Uniform in [0, 1) with 53 random bits.
inline double uniform01(Rng& rng) { return static_cast<double>(rng() >> 11) * 0x1p-53; }

inline double uniform(Rng& rng, double lo, double hi) { return lo + (hi - lo) * uniform01(rng); }

// Log-uniform in [lo, hi] (both > 0).
inline double log_uniform(Rng& rng, double lo, double hi) {
  return std::exp(uniform(rng, std::log(lo), std::log(hi)));
}

// Uniform integer in [lo, hi], of lo's type (the modulo bias is below 2^-40 for the small ranges
// used here).
template <class Int>
Int uniform_int(Rng& rng, Int lo, typename std::common_type<Int>::type hi) {
  static_assert(std::is_integral<Int>::value, "uniform_int draws integers");
  const auto span = static_cast<std::uint64_t>(hi - lo) + 1;
  return static_cast<Int>(lo + static_cast<Int>(rng() % span));
}

// +1 or -1, each half the time (one draw, its lowest bit).
inline double random_sign(Rng& rng) { return rng() & 1u ? 1.0 : -1.0; }

// True with probability p.
inline bool chance(Rng& rng, double p) { return uniform01(rng) < p; }

// Box and Muller 1958: a standard normal from two uniforms.
inline double normal(Rng& rng) {
  const double u1 = 1.0 - uniform01(rng);  // (0, 1]
  const double u2 = uniform01(rng);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
}

// A vector with coordinates uniform in [lo, hi], drawn x, then y, then z.
inline Vec3 uniform_vec3(Rng& rng, double lo, double hi) {
  const double x = uniform(rng, lo, hi);
  const double y = uniform(rng, lo, hi);
  const double z = uniform(rng, lo, hi);
  return Vec3(x, y, z);
}

// A point uniform in the axis-aligned box [lo, hi] (per axis), drawn x, then y, then z.
inline Vec3 uniform_in_box(Rng& rng, const Vec3& lo, const Vec3& hi) {
  const double x = uniform(rng, lo[0], hi[0]);
  const double y = uniform(rng, lo[1], hi[1]);
  const double z = uniform(rng, lo[2], hi[2]);
  return Vec3(x, y, z);
}

// A point uniform in the cube of half-side `half` about `center`.
inline Vec3 random_in_cube(Rng& rng, const Vec3& center, double half) {
  return center + uniform_vec3(rng, -half, half);
}

// A direction uniform on the unit sphere: a normalised Gaussian vector.
inline Vec3 random_unit(Rng& rng) {
  Vec3 v;
  do {
    const double x = normal(rng);
    const double y = normal(rng);
    const double z = normal(rng);
    v = Vec3(x, y, z);
  } while (v.norm() < 1e-6);
  return v.normalized();
}

// Shoemake 1992 (Graphics Gems III, "Uniform random rotations"): a normalised Gaussian
// quaternion is uniform on S^3, and its matrix uniform on SO(3).
inline Mat3 random_rotation(Rng& rng) {
  Eigen::Quaterniond q;
  do {
    const double w = normal(rng);
    const double x = normal(rng);
    const double y = normal(rng);
    const double z = normal(rng);
    q = Eigen::Quaterniond(w, x, y, z);
  } while (q.norm() < 1e-6);
  return q.normalized().toRotationMatrix();
}

// Rodrigues' formula: the rotation by `angle` radians about the unit vector `axis`. About the z
// axis its third row and column are exactly (0, 0, 1).
inline Mat3 rotation_about(const Vec3& axis, double angle) {
  Mat3 K;
  K << 0, -axis[2], axis[1], axis[2], 0, -axis[0], -axis[1], axis[0], 0;
  return Mat3::Identity() + std::sin(angle) * K + (1 - std::cos(angle)) * K * K;
}

// Fisher and Yates (Durstenfeld 1964) with uniform_int (std::shuffle's use of the engine is
// unspecified).
template <class Container>
void shuffle(Container& a, Rng& rng) {
  for (std::size_t i = a.size(); i > 1; --i) {
    const auto j = uniform_int<std::size_t>(rng, 0, i - 1);
    std::swap(a[i - 1], a[j]);
  }
}

}  // namespace graspcd::seeded
