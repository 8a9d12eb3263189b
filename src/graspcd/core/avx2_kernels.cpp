// Compiled with -mavx2 (src/CMakeLists.txt); called only when the processor has AVX2 (avx2.h).
#include <cstdlib>

#include "graspcd/core/avx2.h"

#if defined(__AVX2__)
#include <immintrin.h>
#endif

namespace graspcd {

#if defined(__AVX2__)
namespace {

// (x0, x1, x2, x2): three values in lanes 0-2; lane 3, which no answer reads (greater3), repeats
// lane 2 rather than holding a zero, which GCC builds with a register-to-register VMOVQ that
// valgrind (3.19) cannot run.
inline __m256d lanes3(double x0, double x1, double x2) { return _mm256_set_pd(x2, x2, x1, x0); }

// |x| lanewise: the sign bit cleared, as std::fabs does.
inline __m256d abs4(__m256d x) { return _mm256_andnot_pd(_mm256_set1_pd(-0.0), x); }

// Lanes (v[1], v[2], v[0], v[3]) and (v[2], v[0], v[1], v[3]): the cyclic successors j + 1 and
// j + 2 of lane j among the first three.
inline __m256d next1(__m256d v) { return _mm256_permute4x64_pd(v, _MM_SHUFFLE(3, 0, 2, 1)); }
inline __m256d next2(__m256d v) { return _mm256_permute4x64_pd(v, _MM_SHUFFLE(3, 1, 0, 2)); }

// Bits 0-2 of a lanewise x > y (ordered: false for a NaN, as the scalar comparison).
inline unsigned greater3(__m256d x, __m256d y) {
  return static_cast<unsigned>(_mm256_movemask_pd(_mm256_cmp_pd(x, y, _CMP_GT_OQ))) & 7u;
}

}  // namespace

// Gottschalk, Lin, Manocha 1996 (OBBTree), RAPID's 15 axes in A's frame as written in Ericson,
// Real-Time Collision Detection, 4.4.1; sat.h's scalar test with the three axes of a group in the
// lanes of one register: A's faces (lane i), B's faces (lane j), and for each i the three edge
// axes A_i x B_j (lane j). Each lane evaluates exactly the scalar expression of its axis.
int sat_separating_axis_in_a_avx2(const double* R, const double* T, const double* a,
                                  const double* b, double slack) {
  const __m256d s = _mm256_set1_pd(slack);
  const __m256d av = lanes3(a[0], a[1], a[2]);
  const __m256d bv = lanes3(b[0], b[1], b[2]);
  // Columns c_j = R(., j) and rows r_i = R(i, .) (lane 3 unread).
  __m256d col[3], row[3];
  for (int j = 0; j < 3; ++j) col[j] = lanes3(R[3 * j], R[3 * j + 1], R[3 * j + 2]);
  for (int i = 0; i < 3; ++i) row[i] = lanes3(R[i], R[i + 3], R[i + 6]);
  const __m256d acol0 = abs4(col[0]), acol1 = abs4(col[1]), acol2 = abs4(col[2]);
  const __m256d arow[3] = {abs4(row[0]), abs4(row[1]), abs4(row[2])};

  // L = A_i: |T_i| > (a_i + rb) + slack, rb = (b0 |R(i,0)| + b1 |R(i,1)|) + b2 |R(i,2)|.
  const __m256d rb_a = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(b[0]), acol0),
                                                   _mm256_mul_pd(_mm256_set1_pd(b[1]), acol1)),
                                     _mm256_mul_pd(_mm256_set1_pd(b[2]), acol2));
  const __m256d tv = lanes3(T[0], T[1], T[2]);
  unsigned mask = greater3(abs4(tv), _mm256_add_pd(_mm256_add_pd(av, rb_a), s));
  // L = B_j: |(T0 R(0,j) + T1 R(1,j)) + T2 R(2,j)| > (ra + b_j) + slack,
  // ra = (a0 |R(0,j)| + a1 |R(1,j)|) + a2 |R(2,j)|.
  const __m256d t0 = _mm256_set1_pd(T[0]), t1 = _mm256_set1_pd(T[1]), t2 = _mm256_set1_pd(T[2]);
  const __m256d ra_b = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(a[0]), arow[0]),
                                                   _mm256_mul_pd(_mm256_set1_pd(a[1]), arow[1])),
                                     _mm256_mul_pd(_mm256_set1_pd(a[2]), arow[2]));
  const __m256d dist_b =
      abs4(_mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(t0, row[0]), _mm256_mul_pd(t1, row[1])),
                         _mm256_mul_pd(t2, row[2])));
  mask |= greater3(dist_b, _mm256_add_pd(_mm256_add_pd(ra_b, bv), s)) << 3;
  if (mask != 0) return 1 + __builtin_ctz(mask);

  // L = A_i x B_j, i1, i2 = i + 1, i + 2 and j1, j2 = j + 1, j + 2 (mod 3):
  // |T_i2 R(i1,j) - T_i1 R(i2,j)| > (ra + rb) + slack, ra = a_i1 |R(i2,j)| + a_i2 |R(i1,j)|,
  // rb = b_j1 |R(i,j2)| + b_j2 |R(i,j1)|.
  const __m256d b_j1 = next1(bv), b_j2 = next2(bv);
  const __m256d tl[3] = {t0, t1, t2};
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    const __m256d dist =
        abs4(_mm256_sub_pd(_mm256_mul_pd(tl[i2], row[i1]), _mm256_mul_pd(tl[i1], row[i2])));
    const __m256d ra = _mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(a[i1]), arow[i2]),
                                     _mm256_mul_pd(_mm256_set1_pd(a[i2]), arow[i1]));
    const __m256d rb =
        _mm256_add_pd(_mm256_mul_pd(b_j1, next2(arow[i])), _mm256_mul_pd(b_j2, next1(arow[i])));
    mask |= greater3(dist, _mm256_add_pd(_mm256_add_pd(ra, rb), s)) << (3 * i);
  }
  if (mask != 0) return 7 + __builtin_ctz(mask);
  return 0;
}

// geometry.h's apply_pose with the three coordinates of a point in the lanes of one register:
// ((c0 x + c1 y) + c2 z) + t with c_j the columns of R, lane k evaluating coordinate k.
void apply_pose_avx2(const double* R, const double* t, const double* in, double* out) {
  const __m256d c0 = lanes3(R[0], R[1], R[2]), c1 = lanes3(R[3], R[4], R[5]),
                c2 = lanes3(R[6], R[7], R[8]), tv = lanes3(t[0], t[1], t[2]);
  __m256d p[3];
  for (int v = 0; v < 3; ++v) {
    const double* x = in + 3 * v;
    p[v] = _mm256_add_pd(_mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(c0, _mm256_set1_pd(x[0])),
                                                     _mm256_mul_pd(c1, _mm256_set1_pd(x[1]))),
                                       _mm256_mul_pd(c2, _mm256_set1_pd(x[2]))),
                         tv);
  }
  // The first two points four lanes wide (lane 3 overwritten by the next point), the last one as
  // two lanes and one.
  _mm256_storeu_pd(out, p[0]);
  _mm256_storeu_pd(out + 3, p[1]);
  _mm_storeu_pd(out + 6, _mm256_castpd256_pd128(p[2]));
  _mm_store_sd(out + 8, _mm256_extractf128_pd(p[2], 1));
}

#else

// Built without AVX2 (another processor family): never called, avx2_supported() is false.
int sat_separating_axis_in_a_avx2(const double*, const double*, const double*, const double*,
                                  double) {
  std::abort();
}

void apply_pose_avx2(const double*, const double*, const double*, double*) { std::abort(); }

#endif

}  // namespace graspcd
