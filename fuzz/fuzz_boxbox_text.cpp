// libFuzzer target: the `graspcd boxbox` input (30 numbers a line: two boxes), each case through
// every box separator of core/separators.h (small caps, so a case stays cheap). Oracle: a method
// that proves two boxes disjoint must agree with CGAL's exact box test (exact/exact.h); "may
// overlap" is always allowed. Bad input must end in io::InputError or io::ValueError.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "graspcd/core/separators.h"
#include "graspcd/exact/exact.h"
#include "graspcd/io/text_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static graspcd::fuzz::InputFile file("boxbox.txt");
  constexpr std::size_t kNumbers = 30;
  graspcd::DetectorOptions options;
  options.cap = 50;
  options.switch_passes = 10;
  options.cache_slots = 64;
  try {
    graspcd::io::TextReader reader(file.write(data, size));
    std::vector<double> v;
    while (reader.next(kNumbers, v)) {
      graspcd::Obb a, b;
      try {
        a = graspcd::io::obb_from_numbers(v.data(), "box A");
        b = graspcd::io::obb_from_numbers(v.data() + 15, "box B");
      } catch (const graspcd::io::ValueError&) {
        continue;  // the command reports it at this line
      }
      const bool overlap = graspcd::exact::box_box_overlap(a, b);
      for (const graspcd::Method method : graspcd::all_methods()) {
        graspcd::Detector detector(method, options);
        graspcd::QueryCounters counters;
        if (detector.box_disjoint(a, b, counters) && overlap) {
          const std::string what =
              std::string(graspcd::method_name(method)) + " proves overlapping boxes disjoint";
          graspcd::fuzz::disagreement(what.c_str());
        }
      }
    }
  } catch (const graspcd::io::InputError&) {
  }
  return 0;
}
