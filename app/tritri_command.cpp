// graspcd tritri [--exact] [FILE|-]: one triangle pair per line, prints 1 (intersect) or 0.
#include <iostream>
#include <memory>

#include "command.h"
#include "graspcd/core/tritri.h"
#include "graspcd/exact/exact.h"
#include "graspcd/io/text_input.h"

namespace graspcd::cli {

namespace {

struct TritriOptions {
  std::string input = "-";
  bool exact = false;
};

void run_tritri(const TritriOptions& options) {
  constexpr std::size_t kNumbers = 18;
  for_each_case(options.input, kNumbers, [&](const std::vector<double>& v) {
    const Triangle t1 = io::triangle_from_numbers(v.data());
    const Triangle t2 = io::triangle_from_numbers(v.data() + 9);
    const bool hit =
        options.exact ? exact::tri_tri_intersect(t1, t2) : graspcd::tri_tri_intersect(t1, t2);
    std::cout << (hit ? '1' : '0') << '\n';
  });
}

}  // namespace

Command add_tritri_command(CLI::App& parent) {
  auto options = std::make_shared<TritriOptions>();
  CLI::App* app = parent.add_subcommand(
      "tritri", "Triangle pairs: 1 if the closed triangles intersect, else 0");
  app->add_flag("--exact", options->exact, "Answer with CGAL (the exact twin) instead of the core");
  app->add_option("FILE", options->input, "Input file, or - for stdin")->capture_default_str();
  app->footer(wrap_help(
      "Prints 1 if the two closed triangles intersect (touching counts), else 0, one line per "
      "case, in input order.\n"
      "Input: one case per line, 18 numbers: the vertices p0 p1 p2 of triangle 1, then of "
      "triangle 2 (x y z each). A zero-area triangle is the segment or point it spans.\n" +
      number_grammar_help() +
      "Example (a shared vertex, prints 1):\n"
      "  echo '0 0 0  1 0 0  0 1 0   0 0 0  0 0 1  1 0 1' | graspcd tritri"));
  return Command{app, [options] { run_tritri(*options); }};
}

}  // namespace graspcd::cli
