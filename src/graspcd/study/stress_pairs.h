// The stress suite's cases (stress.h): its classes and the box and triangle pairs they generate.
// Shared by the suite and its generators (stress_cases.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "graspcd/core/geometry.h"
#include "graspcd/core/obb.h"

namespace graspcd::study {

enum class StressKind { kBoxes, kTriangles };

struct StressClass {
  const char* name;
  StressKind kind;
  const char* description;  // one line, for --help and the report
  int default_cases;        // cases per class in the default run
};

// The classes, boxes first, in the order of the table.
const std::vector<StressClass>& stress_classes();

struct BoxPairCase {
  Obb a, b;
};
struct TrianglePairCase {
  Triangle t1, t2;
};

// The `count` cases of class `index` (into stress_classes()) for `seed`: the same numbers on every
// run and platform with the same libm (the engine is std::mt19937_64, the distributions are
// written out in stress_box_cases.cpp and stress_triangle_cases.cpp). Each class draws from its own
// stream, so a class's cases do not depend on the other classes or on their counts.
std::vector<BoxPairCase> make_box_cases(std::size_t index, int count, std::uint64_t seed);
std::vector<TrianglePairCase> make_triangle_cases(std::size_t index, int count, std::uint64_t seed);

}  // namespace graspcd::study
