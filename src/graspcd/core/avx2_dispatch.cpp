// The run-time choice of the AVX2 kernels (avx2.h). Compiled without -mavx2: it runs everywhere.
#include "graspcd/core/avx2.h"

namespace graspcd {
namespace {

bool detect_avx2() {
#if defined(__x86_64__) || defined(__i386__)
  return __builtin_cpu_supports("avx2");
#else
  return false;
#endif
}

}  // namespace

// False (the scalar code) until this dynamic initialisation runs: any call before it is scalar.
std::atomic<bool> detail::avx2_on{detect_avx2()};

bool avx2_supported() {
  static const bool supported = detect_avx2();
  return supported;
}

bool use_avx2(bool on) {
  const bool used = on && avx2_supported();
  detail::avx2_on.store(used, std::memory_order_relaxed);
  return used;
}

}  // namespace graspcd
