// libFuzzer target: the `graspcd tritri` input (the text grammar of io/text_input.h, 18 numbers a
// line), answered by the core's triangle test and checked against CGAL's (exact/exact.h) on every
// case that parses. Bad input must end in io::InputError, nothing else.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fuzz_support.h"
#include "graspcd/core/tritri.h"
#include "graspcd/exact/exact.h"
#include "graspcd/io/text_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static graspcd::fuzz::InputFile file("tritri.txt");
  constexpr std::size_t kNumbers = 18;
  try {
    graspcd::io::TextReader reader(file.write(data, size));
    std::vector<double> v;
    while (reader.next(kNumbers, v)) {
      const graspcd::Triangle t1 = graspcd::io::triangle_from_numbers(v.data());
      const graspcd::Triangle t2 = graspcd::io::triangle_from_numbers(v.data() + 9);
      if (graspcd::tri_tri_intersect(t1, t2) != graspcd::exact::tri_tri_intersect(t1, t2)) {
        graspcd::fuzz::disagreement("tri_tri_intersect disagrees with CGAL");
      }
    }
  } catch (const graspcd::io::InputError&) {
    // Bad input, reported as the command line would.
  }
  return 0;
}
