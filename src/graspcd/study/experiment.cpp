#include "graspcd/study/experiment.h"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace graspcd::study {

using json = nlohmann::json;

std::string fmt(double v, int digits) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(digits);
  s << v;
  return s.str();
}

json counters_json(const QueryCounters& c) {
  return {{"box_tests", c.box_tests},         {"perceptron_passes", c.perceptron_passes},
          {"sat_fallbacks", c.sat_fallbacks}, {"cache_hits", c.cache_hits},
          {"tri_tests", c.tri_tests},         {"tri_pairs", c.tri_pairs}};
}

json timing_json(const std::vector<double>& ns) {
  return {{"median_ms", median(ns) / 1e6},
          {"min_ms", *std::min_element(ns.begin(), ns.end()) / 1e6},
          {"max_ms", *std::max_element(ns.begin(), ns.end()) / 1e6},
          {"repeats_ms", [&] {
             std::vector<double> ms;
             for (double v : ns) ms.push_back(v / 1e6);
             return ms;
           }()}};
}

void write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
}

}  // namespace graspcd::study
