// libFuzzer target: the core's triangle test (core/tritri.h: Moller with a proven error bound and
// the exact fallback) against CGAL's (exact/exact.h) and against the core's own all-predicates
// test, on 18 coordinates decoded from the input. Any disagreement aborts.
//
// Decoding: the first byte picks how the coordinates are read, so that the fuzzer reaches both
// generic and degenerate pairs (coplanar, touching, zero-area) often:
//   0: raw IEEE doubles, 8 bytes each (little endian);
//   1: signed bytes, each a coordinate on the integer grid -128..127;
//   2: signed 16-bit integers times 2^-k, k from the second byte (0..63): fine grids at any scale;
//   3: a shared vertex: as 2, then T2's p0 is T1's p0 (touching pairs);
//   4: a seed: the next 8 bytes seed the project's generator (graspcd/support/random_geometry.h),
//      which builds one of its adversarial pairs (the class and placement from the next two bytes),
//      the same constructions the tests use, now explored by the fuzzer's choice of seeds.
// Missing bytes read as zero. A coordinate outside the exact-arithmetic range of tolerances.h
// (non-finite, or nonzero with |x| outside [kMinCoordinate, kMaxCoordinate]) is input the parsers
// reject, so the case is skipped.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "fuzz_support.h"
#include "graspcd/core/tolerances.h"
#include "graspcd/core/tritri.h"
#include "graspcd/exact/exact.h"
#include "graspcd/support/random_geometry.h"

namespace {

constexpr int kCoordinates = 18;

class Bytes {
 public:
  Bytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::uint8_t next() { return pos_ < size_ ? data_[pos_++] : 0; }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

bool in_exact_range(double x) {
  const double m = std::fabs(x);
  return x == 0.0 || (m >= graspcd::tol::kMinCoordinate && m <= graspcd::tol::kMaxCoordinate);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Bytes bytes(data, size);
  const int mode = bytes.next() % 5;
  double c[kCoordinates];
  int expected = -1;  // known by construction (mode 4), else -1
  if (mode == 4) {
    std::uint64_t seed = 0;
    for (int k = 0; k < 8; ++k) seed |= static_cast<std::uint64_t>(bytes.next()) << (8 * k);
    namespace gt = graspcd::testing;
    const auto cls = static_cast<gt::PairClass>(bytes.next() % gt::kPairClassCount);
    const auto placement = static_cast<gt::Placement>(bytes.next() % 4);
    gt::Rng rng(seed);
    const gt::AdversarialPair pair = gt::make_adversarial(cls, placement, 1.0, rng);
    expected = pair.expected;
    for (int k = 0; k < 9; ++k) {
      c[k] = pair.t1.v[k / 3][k % 3];
      c[9 + k] = pair.t2.v[k / 3][k % 3];
    }
  } else if (mode == 0) {
    for (double& x : c) {
      std::uint64_t bits = 0;
      for (int k = 0; k < 8; ++k) bits |= static_cast<std::uint64_t>(bytes.next()) << (8 * k);
      std::memcpy(&x, &bits, sizeof(x));
    }
  } else if (mode == 1) {
    for (double& x : c) x = static_cast<std::int8_t>(bytes.next());
  } else {
    const int k = bytes.next() % 64;
    for (double& x : c) {
      const auto lo = static_cast<std::uint16_t>(bytes.next());
      const auto hi = static_cast<std::uint16_t>(bytes.next());
      x = std::ldexp(static_cast<std::int16_t>(static_cast<std::uint16_t>(lo | hi << 8)), -k);
    }
    if (mode == 3) {
      for (int i = 0; i < 3; ++i) c[9 + i] = c[i];
    }
  }
  for (const double x : c) {
    if (!in_exact_range(x)) return 0;
  }

  graspcd::Triangle t1, t2;
  for (int k = 0; k < 3; ++k) {
    t1.v[k] = graspcd::Vec3(c[3 * k], c[3 * k + 1], c[3 * k + 2]);
    t2.v[k] = graspcd::Vec3(c[9 + 3 * k], c[9 + 3 * k + 1], c[9 + 3 * k + 2]);
  }
  const bool fast = graspcd::tri_tri_intersect(t1, t2);
  if (fast != graspcd::exact::tri_tri_intersect(t1, t2)) {
    graspcd::fuzz::disagreement("tri_tri_intersect disagrees with CGAL");
  }
  if (expected >= 0 && fast != (expected == 1)) {
    graspcd::fuzz::disagreement("tri_tri_intersect disagrees with the pair's known answer");
  }
  if (fast != graspcd::tri_tri_intersect_predicates(t1, t2)) {
    graspcd::fuzz::disagreement("tri_tri_intersect disagrees with tri_tri_intersect_predicates");
  }
  // The answer is symmetric and does not depend on the order of the vertices.
  if (fast != graspcd::tri_tri_intersect(t2, t1)) {
    graspcd::fuzz::disagreement("tri_tri_intersect(t1, t2) != tri_tri_intersect(t2, t1)");
  }
  const graspcd::Triangle r1{{t1.v[1], t1.v[2], t1.v[0]}};
  const graspcd::Triangle f2{{t2.v[0], t2.v[2], t2.v[1]}};
  if (fast != graspcd::tri_tri_intersect(r1, f2)) {
    graspcd::fuzz::disagreement("tri_tri_intersect depends on the order of the vertices");
  }
  return 0;
}
