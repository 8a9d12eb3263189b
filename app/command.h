// The pieces shared by the subcommands of `graspcd` (docs/design.md, "The command line").
#pragma once

#include <CLI/CLI.hpp>
#include <cstddef>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace graspcd::cli {

// A usage error found after CLI11's parse (e.g. a method that is not implemented yet). main()
// prints "graspcd: <message>" and exits with code 2, like a CLI11 usage error.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A subcommand: its CLI11 app, what to run when it was the one given and, for a command whose
// findings set the exit code (`stress`: 1 when a method broke its contract; `validate`: 1 on a
// missed collision), where run() leaves that code for main() to return.
struct Command {
  CLI::App* app = nullptr;
  std::function<void()> run;
  std::shared_ptr<int> exit_code = nullptr;
};

Command add_tritri_command(CLI::App& parent);
Command add_boxbox_command(CLI::App& parent);
Command add_meshpair_command(CLI::App& parent);
Command add_grasp_command(CLI::App& parent);
Command add_study_command(CLI::App& parent);
Command add_stress_command(CLI::App& parent);
Command add_validate_command(CLI::App& parent);
Command add_trajectory_command(CLI::App& parent);
Command add_decompose_command(CLI::App& parent);
Command add_judge_command(CLI::App& parent);

// The text of `graspcd grasp --help` after the options (grasp_help.cpp).
extern const char* const kGraspHelp;

// CLI11 validators of a numeric option: a finite number > 0 (positive_number) or >= 0
// (non_negative_number). CLI11's PositiveNumber passes nan and says "Value 0 not in range 0.000000
// to 1797693134862...": these say "Value 0 is not > 0", "Value nan is not a finite number".
CLI::Validator positive_number();
CLI::Validator non_negative_number();

// A CLI11 validator of a finite number in [lo, hi]: "Value 0.01 is not in [0, 0.001]", "Value nan
// is not a finite number".
CLI::Validator number_in_range(double lo, double hi);

// A CLI11 validator of an integer option in [lo, hi]: "Value abc is not an integer", "Value 0 is
// not in 4 .. 100000000" (CLI11's Range says "Value abc not in range" of a non-number).
CLI::Validator integer_in_range(long long lo, long long hi);

// The paragraphs on the number grammar and the errors that every subcommand's help repeats.
std::string number_grammar_help();

// Word-wraps help text to `width` columns; '\n' ends a paragraph, and a line starting with two
// spaces (an example command) is kept as is.
std::string wrap_help(const std::string& text, std::size_t width = 100);

// Reads the cases of `path` ("-" = stdin), each exactly `count` numbers, and calls `answer` on
// each in input order. A graspcd::io::ValueError thrown by `answer` (an invalid box or pose) is
// rethrown as an io::InputError located at the case's line. When the input is a pipe or a
// terminal, stdout is flushed after every case, so that a driver waiting on each answer does not
// deadlock; for a regular file it is flushed at the end only.
void for_each_case(const std::string& path, std::size_t count,
                   const std::function<void(const std::vector<double>&)>& answer);

}  // namespace graspcd::cli
