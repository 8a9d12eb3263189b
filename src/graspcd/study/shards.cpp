// The sweep's shards (study.h): reading a shard file, parsing --shard i/n, and merging the shard
// files of one split into sweep.json and sweep.csv.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "graspcd/io/text_input.h"
#include "graspcd/study/experiment.h"
#include "graspcd/study/study.h"
#include "graspcd/study/sweep.h"
#include "graspcd/version/envelope.h"

namespace graspcd::study {

using json = nlohmann::json;

json read_shard_file(const std::string& file, const std::string& kind,
                     const std::vector<std::string>& keys) {
  if (file.empty()) throw io::InputError("--merge", 0, "an empty file name (give the shard files)");
  std::error_code ec;
  if (file[0] == '-' && !std::filesystem::exists(file, ec)) {
    // `--merge --out DIR`: the option was taken for the first file.
    throw io::InputError("--merge", 0,
                         "'" + file + "' is no shard file (give the shard files after --merge)");
  }
  io::require_regular_file(file);
  std::ifstream in(file);
  if (!in) throw io::InputError(file, 0, "cannot open the shard file");
  json j;
  try {
    in >> j;
  } catch (const json::exception& e) {
    throw io::InputError(file, 0, "not " + kind + " (" + e.what() + ")");
  }
  const bool complete = j.is_object() && std::all_of(keys.begin(), keys.end(),
                                                     [&j](const auto& k) { return j.contains(k); });
  if (!complete) {
    std::string names;
    for (std::size_t i = 0; i < keys.size(); ++i) {
      names += (i == 0 ? "" : i + 1 == keys.size() ? " or " : ", ") + keys[i];
    }
    throw io::InputError(file, 0, "not " + kind + " (no " + names + ")");
  }
  return j;
}

Shard parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  std::size_t p1 = 0;
  std::size_t p2 = 0;
  Shard s;
  try {
    if (slash == std::string::npos) throw std::invalid_argument("");
    s.index = std::stoi(text.substr(0, slash), &p1);
    s.count = std::stoi(text.substr(slash + 1), &p2);
  } catch (const std::exception&) {
    throw std::invalid_argument("--shard expects i/n, e.g. 0/4, not '" + text + "'");
  }
  if (p1 != slash || p2 != text.size() - slash - 1 || s.count < 1 || s.index < 0 ||
      s.index >= s.count)
    throw std::invalid_argument("--shard expects i/n with 0 <= i < n, not '" + text + "'");
  return s;
}

void merge_shards(const std::vector<std::string>& files, const std::string& out_dir,
                  const Log& log) {
  if (files.empty()) throw std::runtime_error("--merge needs at least one shard file");
  json merged;
  std::map<int, json> by_index;
  int count = -1;
  for (const std::string& f : files) {
    json j = read_shard_file(f, "a sweep shard", {"configs", "config_names", "shard"});
    if (merged.is_null()) {
      merged = j;
      merged["configs"] = json::array();
      count = j["shard"]["count"].get<int>();
    } else {
      if (j["config_names"] != merged["config_names"])
        throw std::runtime_error(f + ": another sweep (its configuration list differs)");
      if (j["recordings"] != merged["recordings"])
        throw std::runtime_error(f + ": recorded other grasps (pose hashes differ)");
      if (j["repeats"] != merged["repeats"] || j["quick"] != merged["quick"] ||
          j["full"] != merged["full"])
        throw std::runtime_error(f + ": run with other --repeats, --quick or --full-sweep");
      if (j["shard"]["count"].get<int>() != count)
        throw std::runtime_error(f + ": a shard of another split");
    }
    for (const json& c : j["configs"]) {
      const int i = c["index"].get<int>();
      if (by_index.count(i))
        throw std::runtime_error(f + ": configuration " + std::to_string(i) + " appears twice");
      by_index[i] = c;
    }
  }
  const std::size_t n = merged["config_names"].size();
  for (std::size_t i = 0; i < n; ++i) {
    if (by_index.count(static_cast<int>(i))) continue;
    // Shard k of n holds configurations k, k + n, ...: name the shard file that is missing.
    const int shard = static_cast<int>(i % static_cast<std::size_t>(count));
    throw std::runtime_error(
        "shard " + std::to_string(shard) + " of " + std::to_string(count) + " (sweep.shard-" +
        std::to_string(shard) + "-of-" + std::to_string(count) +
        ".json) is missing: configuration " + std::to_string(i) + " (" +
        merged["config_names"][i].get<std::string>() + ") is in no shard given");
  }
  for (auto& [i, c] : by_index) merged["configs"].push_back(c);
  merged["shard"] = {{"index", 0}, {"count", 1}};
  merged["merged_from"] = files.size();
  const std::filesystem::path out(out_dir);
  std::filesystem::create_directories(out);
  add_envelope(merged);
  write_file(out / "sweep.json", merged.dump(1) + "\n");
  write_file(out / "sweep.csv", sweep_csv(merged));
  log("merged " + std::to_string(files.size()) + " shards (" + std::to_string(n) +
      " configurations) into " + (out / "sweep.json").string());
}

}  // namespace graspcd::study
