// The tree query's AVX2 kernels, chosen at run time: the 15-axis box test (sat.h) and the placing
// of a triangle by a pose (geometry.h, apply_pose). Plain doubles only: the kernels' translation
// unit (avx2_kernels.cpp) is compiled with -mavx2 (and no -mfma), and keeping every inline function
// of the project and of Eigen out of it keeps AVX2 code from reaching a caller on a machine
// without it. Each kernel performs the same products, sums and comparisons as its scalar twin, in
// the same order, one scalar evaluation per lane (IEEE arithmetic rounds each lane as it rounds a
// scalar; the build keeps -ffp-contract=off and the kernels use no fused multiply-add), so its
// answers are the scalar ones bit for bit (tests/core/avx2_test.cpp).
#pragma once

#include <atomic>

namespace graspcd {

// Whether the processor has AVX2 (__builtin_cpu_supports), and whether the kernels are used: on
// from the start where supported. use_avx2(false) keeps the scalar code, use_avx2(true) takes AVX2
// where supported; it returns whether AVX2 is then used. Only a matter of speed. Process-wide.
bool avx2_supported();
bool use_avx2(bool on);
namespace detail {
extern std::atomic<bool> avx2_on;
inline bool avx2_active() { return avx2_on.load(std::memory_order_relaxed); }
}  // namespace detail

// sat_separating_axis_in_a without a hint (Gottschalk, Lin, Manocha 1996; Ericson 4.4.1), on raw
// doubles: R (3x3, column-major, as Eigen stores a Mat3), T, a, b (3 each). Requires AVX2.
int sat_separating_axis_in_a_avx2(const double* R, const double* T, const double* a,
                                  const double* b, double slack);

// apply_pose on the three vertices of a triangle: `in` and `out` hold 9 doubles each (three
// points, x y z), R is 3x3 column-major, t 3 doubles; out_k = ((R_k0 x + R_k1 y) + R_k2 z) + t_k,
// as apply_pose rounds it. Requires AVX2.
void apply_pose_avx2(const double* R, const double* t, const double* in, double* out);

}  // namespace graspcd
