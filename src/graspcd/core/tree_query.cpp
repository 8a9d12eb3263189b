#include "graspcd/core/tree_query.h"

namespace graspcd {

QueryCounters& QueryCounters::operator+=(const QueryCounters& o) {
  box_tests += o.box_tests;
  perceptron_passes += o.perceptron_passes;
  sat_fallbacks += o.sat_fallbacks;
  cache_hits += o.cache_hits;
  tri_tests += o.tri_tests;
  tri_pairs += o.tri_pairs;
  return *this;
}

}  // namespace graspcd
