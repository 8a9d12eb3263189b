#include "graspcd/core/separators.h"

#include <stdexcept>

namespace graspcd {

bool SatCachedSeparator::disjoint(const Obb& a, const Obb& b, std::int32_t na, std::int32_t nb,
                                  QueryCounters& c) {
  const SatAxis first = hint(na, nb);
  const SatAxis axis = sat_separating_axis(a, b, first);
  if (axis == kSatNoAxis) return false;
  record(na, nb, axis, first, c);
  return true;
}

bool PerceptronSeparator::disjoint(const Obb& a, const Obb& b, std::int32_t, std::int32_t,
                                   QueryCounters& c) {
  const PerceptronResult r = perceptron_separate(a, b, options);
  c.perceptron_passes += static_cast<std::uint64_t>(r.passes);
  return r.disjoint;
}

bool PerceptronWarmSeparator::disjoint(const Obb& a, const Obb& b, std::int32_t na, std::int32_t nb,
                                       QueryCounters& c) {
  const SeparatingPlane* start = cache.find(na, nb);
  const PerceptronResult r = perceptron_separate(a, b, options, start);
  c.perceptron_passes += static_cast<std::uint64_t>(r.passes);
  if (start && r.disjoint && r.updates == 0) ++c.cache_hits;  // the old plane still separated
  if (r.converged) {
    cache.store(na, nb, r.plane);
  } else {
    cache.erase(na, nb);
  }
  return r.disjoint;
}

bool NeuroSatSeparator::disjoint(const Obb& a, const Obb& b, std::int32_t, std::int32_t,
                                 QueryCounters& c) {
  const PerceptronResult r =
      perceptron_separate(a, b, {switch_passes, PerceptronFrame::kDisplaced});
  c.perceptron_passes += static_cast<std::uint64_t>(r.passes);
  if (r.disjoint) return true;
  ++c.sat_fallbacks;
  return sat_separating_axis(a, b) != kSatNoAxis;
}

bool NeuroSatStickySeparator::disjoint(const Obb& a, const Obb& b, std::int32_t na, std::int32_t nb,
                                       QueryCounters& c) {
  if (switched.find(na, nb)) {
    ++c.cache_hits;
    ++c.sat_fallbacks;
    return sat_separating_axis(a, b) != kSatNoAxis;
  }
  const PerceptronResult r =
      perceptron_separate(a, b, {switch_passes, PerceptronFrame::kDisplaced});
  c.perceptron_passes += static_cast<std::uint64_t>(r.passes);
  if (r.disjoint) return true;
  switched.store(na, nb, true);
  ++c.sat_fallbacks;
  return sat_separating_axis(a, b) != kSatNoAxis;
}

namespace {

struct MethodInfo {
  Method method;
  const char* name;
};
constexpr MethodInfo kMethods[] = {
    {Method::kSat, "sat"},
    {Method::kSatCached, "sat-cached"},
    {Method::kPerceptron, "perceptron"},
    {Method::kPerceptronNoDisp, "perceptron-nodisp"},
    {Method::kPerceptronScaled, "perceptron-scaled"},
    {Method::kPerceptronWarm, "perceptron-warm"},
    {Method::kNeuroSat, "neurosat"},
    {Method::kNeuroSatSticky, "neurosat-sticky"},
};

}  // namespace

const char* method_name(Method m) {
  for (const MethodInfo& info : kMethods) {
    if (info.method == m) return info.name;
  }
  return "?";
}

std::optional<Method> parse_method(const std::string& name) {
  for (const MethodInfo& info : kMethods) {
    if (name == info.name) return info.method;
  }
  return std::nullopt;
}

const std::vector<Method>& all_methods() {
  static const std::vector<Method> methods = [] {
    std::vector<Method> v;
    for (const MethodInfo& info : kMethods) v.push_back(info.method);
    return v;
  }();
  return methods;
}

bool uses_perceptron(Method m) { return m != Method::kSat && m != Method::kSatCached; }

Detector::Detector(Method method, const DetectorOptions& options)
    : method_(method), options_(options), separator_(SatSeparator{}) {
  if (options.cap < 1) throw std::invalid_argument("perceptron cap must be >= 1");
  if (options.switch_passes < 1) throw std::invalid_argument("Neuro-SAT switch must be >= 1");
  separator_ = make_separator();
}

Detector::Separator Detector::make_separator() const {
  const PerceptronOptions displaced{options_.cap, PerceptronFrame::kDisplaced};
  switch (method_) {
    case Method::kSat:
      return SatSeparator{};
    case Method::kSatCached:
      return SatCachedSeparator{PairCache<SatAxis>(options_.cache_slots)};
    case Method::kPerceptron:
      return PerceptronSeparator{displaced};
    case Method::kPerceptronNoDisp:
      return PerceptronSeparator{{options_.cap, PerceptronFrame::kOriginal}};
    case Method::kPerceptronScaled:
      return PerceptronSeparator{{options_.cap, PerceptronFrame::kScaled}};
    case Method::kPerceptronWarm:
      return PerceptronWarmSeparator{displaced, PairCache<SeparatingPlane>(options_.cache_slots)};
    case Method::kNeuroSat:
      return NeuroSatSeparator{options_.switch_passes};
    case Method::kNeuroSatSticky:
      return NeuroSatStickySeparator{options_.switch_passes, PairCache<bool>(options_.cache_slots)};
  }
  return SatSeparator{};
}

QueryResult Detector::collide(const ObbTree& a, const ObbTree& b, const Pose& b_in_a,
                              QueryMode mode, QueryCounters& counters,
                              std::vector<TrianglePair>* pairs) {
  return std::visit(
      [&](auto& separator) {
        return graspcd::collide(a, b, b_in_a, mode, separator, counters, pairs);
      },
      separator_);
}

QueryResult Detector::collide_coherent(const ObbTree& a, const ObbTree& b, const Pose& b_in_a,
                                       QueryCounters& counters, std::vector<TrianglePair>* pairs,
                                       QueryFront& front) {
  return std::visit(
      [&](auto& separator) {
        return graspcd::collide_coherent(a, b, b_in_a, separator, counters, pairs, front);
      },
      separator_);
}

bool Detector::box_disjoint(const Obb& a, const Obb& b, QueryCounters& counters) {
  ++counters.box_tests;
  return std::visit([&](auto& separator) { return separator.disjoint(a, b, 0, 0, counters); },
                    separator_);
}

void Detector::reset() { separator_ = make_separator(); }

}  // namespace graspcd
