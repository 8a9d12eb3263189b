// The box-pair methods of docs/design.md ("Methods") on the command line.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "graspcd/core/separators.h"

namespace graspcd::cli {

// Command-line settings of a box-pair method (the methods and their names are core's:
// core/separators.h).
struct MethodOptions {
  std::string name = "sat";
  Method method = Method::kSat;
  int cap = tol::kPerceptronDefaultCap;             // --cap: most perceptron passes per box test
  int switch_passes = tol::kNeuroSatDefaultSwitch;  // --switch: Neuro-SAT's passes before SAT
};

// Where a subcommand's method settings come from when not given: MethodOptions' built-in values
// (boxbox, meshpair), or the scene's pair config (grasp, validate), which --help then says.
enum class MethodDefaults { kBuiltIn, kSceneConfig };

// Adds --method, --cap and --switch to a subcommand, storing into `options` (which must outlive
// the parse). Call finish_method_options() after parsing.
void add_method_options(CLI::App& app, MethodOptions& options,
                        MethodDefaults defaults = MethodDefaults::kBuiltIn);
void finish_method_options(MethodOptions& options);

// The detector of the chosen method; its caches carry over from one input line to the next.
Detector make_detector(const MethodOptions& options);

}  // namespace graspcd::cli
