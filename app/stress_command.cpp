// graspcd stress [--quick] [--json] [--seed N] [--cases N]: the numerical stress suite
// (src/graspcd/study/stress.h): every method against CGAL on seeded degenerate and extreme cases.
#include <cstdint>
#include <iostream>
#include <limits>
#include <memory>
#include <string>

#include "command.h"
#include "graspcd/study/stress.h"

namespace graspcd::cli {

namespace {

struct StressCliOptions {
  study::StressOptions stress;
  bool json = false;
};

// The classes for the help text, one line each.
std::string class_list() {
  std::string text;
  for (const study::StressClass& cls : study::stress_classes()) {
    text += "  " + std::string(cls.name) + ": " + cls.description + " (" +
            std::to_string(cls.default_cases) + " cases)\n";
  }
  return text;
}

int run_stress_command(const StressCliOptions& o) {
  const auto log = [](const std::string& line) { std::cerr << "[stress] " << line << std::endl; };
  const study::StressReport report = study::run_stress(o.stress, log);
  std::cout << (o.json ? study::stress_json(report) : study::stress_table(report));
  log("done in " + std::to_string(static_cast<long>(report.seconds + 0.5)) + " s");
  if (report.contract_broken()) {
    log("a method separated overlapping geometry or left its tolerance band (see the table)");
    return 1;
  }
  return 0;
}

}  // namespace

Command add_stress_command(CLI::App& parent) {
  auto o = std::make_shared<StressCliOptions>();
  auto exit_code = std::make_shared<int>(0);
  CLI::App* app = parent.add_subcommand(
      "stress",
      "Numerical stress suite: every method against CGAL on extreme and degenerate cases");
  app->add_flag("--quick", o->stress.quick,
                "A fiftieth of the cases per class (at least 50): a few seconds");
  app->add_flag("--json", o->json, "Print the table as JSON instead of text");
  app->add_option("--seed", o->stress.seed, "Seed of the case generator")
      ->transform(decimal_integer(0, std::numeric_limits<std::uint64_t>::max()))
      ->capture_default_str();
  app->add_option("--cases", o->stress.cases,
                  "Cases per class (overrides the defaults and --quick)")
      ->transform(positive_integer());
  app->footer(wrap_help(
      "Generates seeded box pairs and triangle pairs, each built around a known contact (a "
      "vertex on a face, crossing edges, coplanar triangles touching) and then moved apart or "
      "into each other by a signed gap along the contact's normal, so that every class holds "
      "both overlapping and disjoint pairs. The truth is CGAL (the exact twin, src/graspcd/exact) "
      "on the doubles as generated. Box pairs go to every method of `boxbox` (a fresh detector per "
      "pair, so the warm and cached methods start cold, default cap and switch); triangle pairs "
      "to the core's tri_tri_intersect, its exact fallback tri_tri_intersect_predicates, and the "
      "two "
      "reference variants moller_naive (Moller's published epsilon) and moller_plain (no "
      "epsilon), which are expected to disagree.\n"
      "Classes (cases per class in the default run):\n" +
      class_list() +
      "Columns, one row per class and method: cases; overlapping (the truth says they overlap); "
      "false_separated (the method proved disjoint a pair that overlaps: must be 0); "
      "false_overlap (the method could not prove a disjoint pair disjoint); "
      "max_false_overlap_gap_rel (boxes: the largest exact gap among the false overlaps, "
      "exact::box_box_gap, divided by both boxes' half-extents summed plus |cB - cA|_1, the "
      "scale of kSatRelativeSlack); outside_band (false overlaps the documented tolerance does "
      "not explain: for the SAT family, sat, sat-cached and the Neuro-SATs, a pair whose exact "
      "gap on one of the 15 axes exceeds the slack of tolerances.h plus the SAT's rounding; for "
      "the exact triangle tests every false overlap; must be 0); perceptron_capped (tests that "
      "used all their passes, the cap or Neuro-SAT's switch, whatever the truth: overlapping "
      "boxes never converge).\n"
      "Prints the table (--json: the same as JSON) on stdout and one progress line per class "
      "on stderr. Exit code 1 when a method other than the reference variants has a false "
      "separation or a false overlap outside its band; 0 otherwise. The default run takes about "
      "a minute in a Release build, --quick a few seconds.\n"
      "Examples:\n"
      "  graspcd stress --quick\n"
      "  graspcd stress --json --seed 7 > stress.json"));
  return Command{app, [o, exit_code] { *exit_code = run_stress_command(*o); }, exit_code};
}

}  // namespace graspcd::cli
