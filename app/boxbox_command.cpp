// graspcd boxbox [--method M] [--cap N] [--switch N] [--exact] [FILE|-]: one box pair per line,
// prints 1 (may overlap) or 0 (separated), then the passes for the iterative methods.
#include <functional>
#include <iostream>
#include <memory>

#include "command.h"
#include "graspcd/core/separators.h"
#include "graspcd/exact/exact.h"
#include "graspcd/io/text_input.h"
#include "method.h"

namespace graspcd::cli {

namespace {

struct BoxboxOptions {
  MethodOptions method;
  std::string input = "-";
  bool exact = false;
};

// One answer: 1/0, and for the perceptron methods and Neuro-SAT the passes used (< 0: none).
struct BoxAnswer {
  bool may_overlap = true;
  long passes = -1;
};

using BoxTest = std::function<BoxAnswer(const Obb& a, const Obb& b)>;

// The box test of a method, with whatever state it carries from one input line to the next.
BoxTest make_box_test(const MethodOptions& options) {
  auto detector = std::make_shared<Detector>(make_detector(options));
  const bool report_passes = uses_perceptron(options.method);
  return [detector, report_passes](const Obb& a, const Obb& b) {
    QueryCounters counters;
    const bool disjoint = detector->box_disjoint(a, b, counters);
    return BoxAnswer{!disjoint, report_passes ? static_cast<long>(counters.perceptron_passes) : -1};
  };
}

void run_boxbox(BoxboxOptions& options) {
  finish_method_options(options.method);
  BoxTest test;
  if (options.exact) {
    test = [](const Obb& a, const Obb& b) { return BoxAnswer{exact::box_box_overlap(a, b), -1}; };
  } else {
    test = make_box_test(options.method);
  }
  constexpr std::size_t kNumbers = 30;
  for_each_case(options.input, kNumbers, [&](const std::vector<double>& v) {
    const Obb a = io::obb_from_numbers(v.data(), "box A");
    const Obb b = io::obb_from_numbers(v.data() + 15, "box B");
    const BoxAnswer answer = test(a, b);
    std::cout << (answer.may_overlap ? '1' : '0');
    if (answer.passes >= 0) std::cout << ' ' << answer.passes;
    std::cout << '\n';
  });
}

}  // namespace

Command add_boxbox_command(CLI::App& parent) {
  auto options = std::make_shared<BoxboxOptions>();
  CLI::App* app = parent.add_subcommand(
      "boxbox", "Oriented box pairs: 1 if they may overlap, 0 if proven separated");
  add_method_options(*app, options->method);
  app->add_flag("--exact", options->exact,
                "Answer exactly with CGAL instead of the method (--method is then ignored)");
  app->add_option("FILE", options->input, "Input file, or - for stdin")->capture_default_str();
  app->footer(wrap_help(
      "Prints 1 if the boxes may overlap, 0 if the method proves them separated (with --exact: 1 "
      "if and only if they overlap), one line per case; the perceptron methods and Neuro-SAT add "
      "a space and the passes used. The cached and warm methods carry their state from one line "
      "to the next.\n"
      "Input: one case per line, 30 numbers: box A then box B, each as centre (3), R row-major "
      "(9), half-extents (3). A box is c + R diag(e) u with |u|_inf <= 1 (R's columns are its "
      "axes); R must be a rotation to within 1e-9, half-extents >= 0 (zero allowed).\n" +
      number_grammar_help() +
      "Example (unit cubes 2.5 apart along x, prints 0):\n"
      "  echo '0 0 0 1 0 0 0 1 0 0 0 1 1 1 1  2.5 0 0 1 0 0 0 1 0 0 0 1 1 1 1' | graspcd boxbox"));
  return Command{app, [options] { run_boxbox(*options); }};
}

}  // namespace graspcd::cli
