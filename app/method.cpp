#include "method.h"

#include "command.h"

namespace graspcd::cli {

namespace {

std::vector<std::string> method_names() {
  std::vector<std::string> names;
  for (Method m : all_methods()) names.emplace_back(method_name(m));
  return names;
}

}  // namespace

void add_method_options(CLI::App& app, MethodOptions& options, MethodDefaults defaults) {
  CLI::Option* options_added[] = {
      app.add_option("--method", options.name,
                     "Box-pair method: sat, sat-cached, perceptron, perceptron-nodisp, "
                     "perceptron-scaled, perceptron-warm, neurosat or neurosat-sticky")
          ->check(CLI::IsMember(method_names())),
      app.add_option("--cap", options.cap, "Perceptron: most passes per box test (positive)")
          ->transform(positive_integer()),
      app.add_option("--switch", options.switch_passes,
                     "Neuro-SAT: passes before SAT takes over (positive)")
          ->transform(positive_integer())};
  for (CLI::Option* option : options_added) {
    option->capture_default_str();
    if (defaults == MethodDefaults::kSceneConfig) {
      option->default_str("the scene config's, else " + option->get_default_str());
    }
  }
}

void finish_method_options(MethodOptions& options) {
  const std::optional<Method> m = parse_method(options.name);
  if (!m) throw UsageError("unknown method " + options.name);
  options.method = *m;
}

Detector make_detector(const MethodOptions& options) {
  DetectorOptions d;
  d.cap = options.cap;
  d.switch_passes = options.switch_passes;
  return Detector(options.method, d);
}

}  // namespace graspcd::cli
