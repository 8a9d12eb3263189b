// The 15-axis box test of sat.h batched four lanes at a time with AVX2, chosen at run time.
// Plain doubles only: the kernel's translation unit is compiled with -mavx2 (and no -mfma), and
// keeping every inline function of the project and of Eigen out of it keeps AVX2 code from
// reaching a caller on a machine without it.
#pragma once

namespace graspcd {

// sat_separating_axis_in_a without a hint, on raw doubles: R (3x3, column-major, as Eigen stores
// a Mat3), T, a, b (3 each). Requires a processor with AVX2 (sat_avx2_supported()). The same
// products, sums and comparisons as the scalar test, in the same order, one axis per lane (IEEE
// arithmetic rounds each lane as it rounds a scalar; the build keeps -ffp-contract=off and the
// kernel uses no fused multiply-add), so the answer is the scalar one bit for bit.
int sat_separating_axis_in_a_avx2(const double* R, const double* T, const double* a,
                                  const double* b, double slack);

}  // namespace graspcd
