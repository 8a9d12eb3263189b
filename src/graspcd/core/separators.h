// The box-pair separators of the tree query, as compile-time policies (no virtual call per box
// test), their bounded temporal-coherence cache, and Detector, which picks one at run time and
// dispatches once per query.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "graspcd/core/perceptron.h"
#include "graspcd/core/sat.h"
#include "graspcd/core/tree_query.h"

namespace graspcd {

// A direct-mapped cache keyed by node pair: a fixed number of slots (a power of two), each holding
// one pair's value; a newer pair that maps to an occupied slot replaces it. Memory is bounded by
// slots * sizeof(slot) whatever the trees, and reset() forgets everything.
template <class Value>
class PairCache {
 public:
  explicit PairCache(std::size_t slots = 1u << 16) : slots_(round_up(slots)) {}

  const Value* find(std::int32_t a, std::int32_t b) const {
    const Slot& s = slots_[index(a, b)];
    return s.key == key(a, b) ? &s.value : nullptr;
  }
  void store(std::int32_t a, std::int32_t b, const Value& value) {
    slots_[index(a, b)] = Slot{key(a, b), value};
  }
  void erase(std::int32_t a, std::int32_t b) {
    Slot& s = slots_[index(a, b)];
    if (s.key == key(a, b)) s.key = kEmpty;
  }
  void reset() {
    for (Slot& s : slots_) s.key = kEmpty;
  }
  std::size_t memory_bytes() const { return slots_.size() * sizeof(Slot); }

 private:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};
  struct Slot {
    std::uint64_t key = kEmpty;
    Value value{};
  };
  static std::size_t round_up(std::size_t n) {
    std::size_t p = 1;
    while (p < n) p <<= 1;
    return p;
  }
  static std::uint64_t key(std::int32_t a, std::int32_t b) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
           static_cast<std::uint32_t>(b);
  }
  std::size_t index(std::int32_t a, std::int32_t b) const {
    // Fibonacci hashing of the 64-bit key.
    return static_cast<std::size_t>((key(a, b) * 0x9E3779B97F4A7C15ull) >> 32) &
           (slots_.size() - 1);
  }
  std::vector<Slot> slots_;
};

// SAT that first tries the axis that separated the same node pair last time.
// hint() and record() make it an axis separator for the tree query (tree_query.h).
struct SatCachedSeparator {
  PairCache<SatAxis> cache;
  bool disjoint(const Obb& a, const Obb& b, std::int32_t na, std::int32_t nb, QueryCounters& c);
  SatAxis hint(std::int32_t na, std::int32_t nb) const {
    const SatAxis* last = cache.find(na, nb);
    return last ? *last : kSatNoAxis;
  }
  void record(std::int32_t na, std::int32_t nb, SatAxis axis, SatAxis hint, QueryCounters& c) {
    if (axis == hint) ++c.cache_hits;
    cache.store(na, nb, axis);
  }
};

// The perceptron alone (paper sections 5 and 11): "may overlap" when it hits its cap.
struct PerceptronSeparator {
  PerceptronOptions options;
  bool disjoint(const Obb& a, const Obb& b, std::int32_t na, std::int32_t nb, QueryCounters& c);
};

// The displaced perceptron warm-started from the plane it found for the same node pair last time.
struct PerceptronWarmSeparator {
  PerceptronOptions options;
  PairCache<SeparatingPlane> cache;
  bool disjoint(const Obb& a, const Obb& b, std::int32_t na, std::int32_t nb, QueryCounters& c);
};

// Neuro-SAT (section 10), first reading: the displaced perceptron for up to `switch_passes`
// passes, then SAT inside the same test.
struct NeuroSatSeparator {
  int switch_passes = tol::kNeuroSatDefaultSwitch;
  bool disjoint(const Obb& a, const Obb& b, std::int32_t na, std::int32_t nb, QueryCounters& c);
};

// Neuro-SAT, second reading: a node pair whose perceptron needed more than `switch_passes` passes
// uses SAT from then on (until reset, or until the bounded cache gives its slot to another pair).
struct NeuroSatStickySeparator {
  int switch_passes = tol::kNeuroSatDefaultSwitch;
  PairCache<bool> switched;
  bool disjoint(const Obb& a, const Obb& b, std::int32_t na, std::int32_t nb, QueryCounters& c);
};

enum class Method {
  kSat,
  kSatCached,
  kPerceptron,
  kPerceptronNoDisp,
  kPerceptronScaled,
  kPerceptronWarm,
  kNeuroSat,
  kNeuroSatSticky,
};

// Command-line names: sat, sat-cached, perceptron, perceptron-nodisp, perceptron-scaled,
// perceptron-warm, neurosat, neurosat-sticky.
const char* method_name(Method m);
// The method of a command-line name above; std::nullopt for any other string (no throw).
std::optional<Method> parse_method(const std::string& name);
// Every method, in the order of the enum.
const std::vector<Method>& all_methods();
// True for the methods that report perceptron passes.
bool uses_perceptron(Method m);

struct DetectorOptions {
  int cap = tol::kPerceptronDefaultCap;             // perceptron pass cap (>= 1)
  int switch_passes = tol::kNeuroSatDefaultSwitch;  // Neuro-SAT switch (>= 1)
  std::size_t cache_slots = 1u << 16;               // temporal-coherence cache size
};

// One method with its state (caches carry over from query to query until reset()).
class Detector {
 public:
  // Throws std::invalid_argument when options.cap or options.switch_passes is < 1.
  explicit Detector(Method method, const DetectorOptions& options = {});

  Method method() const { return method_; }

  // The tree query (tree_query.h) with this detector's separator; the method is dispatched once
  // per call, the box tests inside are direct calls.
  QueryResult collide(const ObbTree& a, const ObbTree& b, const Pose& b_in_a, QueryMode mode,
                      QueryCounters& counters, std::vector<TrianglePair>* pairs = nullptr);

  // The all-contacts query restarted from `front` when B moved little (tree_query.h,
  // collide_coherent): the same intersecting triangle pairs as collide() in kAllContacts mode.
  QueryResult collide_coherent(const ObbTree& a, const ObbTree& b, const Pose& b_in_a,
                               QueryCounters& counters, std::vector<TrianglePair>* pairs,
                               QueryFront& front);

  // One box pair (the `boxbox` command): true when proven disjoint. The pair is cached under node
  // ids (0, 0), so warm and cached methods carry their state from one call to the next.
  bool box_disjoint(const Obb& a, const Obb& b, QueryCounters& counters);

  // Forgets every cached plane, axis and switch.
  void reset();

 private:
  using Separator =
      std::variant<SatSeparator, SatCachedSeparator, PerceptronSeparator, PerceptronWarmSeparator,
                   NeuroSatSeparator, NeuroSatStickySeparator>;
  Method method_;
  DetectorOptions options_;
  Separator separator_;
  Separator make_separator() const;
};

}  // namespace graspcd
