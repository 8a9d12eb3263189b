#include "graspcd/study/object_set.h"

#include <sys/stat.h>
#include <sys/types.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "graspcd/exact/exact.h"
#include "graspcd/grasp/object_run.h"
#include "graspcd/io/text_input.h"
#include "graspcd/io/warnings.h"
#include "graspcd/version/envelope.h"

namespace graspcd::study {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

bool is_object_file(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  // The formats io::load_mesh reads (a glTF's .bin buffers are not objects).
  for (const char* known : {".obj", ".stl", ".off", ".ply", ".gltf", ".glb", ".dae"}) {
    if (ext == known) return true;
  }
  return false;
}

json settings_json(const ObjectSetOptions& o, const std::vector<TesterSpec>& testers) {
  json methods = json::array();
  for (const TesterSpec& t : testers) methods.push_back(t.name);
  const grasp::ObjectPlacement& p = o.placement;
  return {{"scale", p.fit ? json() : json(p.scale)},
          {"fit", p.fit},
          {"up", p.pose ? json() : json(p.up)},
          {"yaw", p.pose ? json() : json(p.yaw_degrees)},
          {"pose", p.pose ? json(*p.pose) : json()},
          {"max_steps", o.max_steps},
          {"methods", methods}};
}

json refused_row(const std::string& object, const std::string& error) {
  return {{"object", object}, {"status", "refused"}, {"error", error}};
}

// The row of a checked object from its scene and its validation.
json checked_row(const std::string& object, const grasp::ObjectScene& scene,
                 const ValidationReport& report) {
  // CGAL's hits are the truth, the same in every method's table: read from the first.
  int cgal_hits = 0;
  if (!report.methods.empty()) {
    for (const PairRow& r : report.methods.front().rows) cgal_hits += r.truth_hits;
  }
  json methods = json::array();
  for (const MethodTable& t : report.methods) {
    int checks = 0, agree = 0, missed = 0, false_contacts = 0;
    std::uint64_t missed_tri = 0, false_tri = 0;
    for (const PairRow& r : t.rows) {
      checks += r.steps;
      agree += r.agree;
      missed += r.missed;
      false_contacts += r.false_contacts;
      missed_tri += r.missed_tri_pairs;
      false_tri += r.false_tri_pairs;
    }
    methods.push_back({{"method", t.method},
                       {"checks", checks},
                       {"agree", agree},
                       {"missed", missed},
                       {"false_contacts", false_contacts},
                       {"missed_tri_pairs", missed_tri},
                       {"false_tri_pairs", false_tri}});
  }
  int states = 0;  // every phase's (the closing's grasp steps and the squeeze's states)
  for (const PhaseChecks& c : report.phases) states += c.states;
  return {
      {"object", object},       {"status", "checked"},
      {"error", nullptr},       {"scale", scene.scale},
      {"fitted", scene.fitted}, {"size", scene.size},
      {"steps", report.steps},  {"steps_with_contact", report.steps_with_contact},
      {"states", states},       {"states_with_contact", report.states_with_contact()},
      {"cgal_hits", cgal_hits}, {"gripped", report.gripped},
      {"held", report.held},    {"reason", report.reason.empty() ? json() : json(report.reason)},
      {"methods", methods}};
}

// Whether some method of the row counted a check or triangle pair under `checks` or `tri_pairs`
// (missed: "missed", "missed_tri_pairs"; false: "false_contacts", "false_tri_pairs").
bool row_has(const json& row, const char* checks, const char* tri_pairs) {
  if (!row.contains("methods")) return false;
  return std::any_of(row["methods"].begin(), row["methods"].end(), [&](const json& m) {
    return m[checks].get<int>() > 0 || m[tri_pairs].get<std::uint64_t>() > 0;
  });
}

// The set's verdicts over its rows: missed_any, false_any (some method missed a collision, or
// gave a false one, on some object) and refused (the objects refused).
void set_verdicts(json& doc) {
  const json& rows = doc["rows"];
  const auto any = [&rows](const char* checks, const char* tri_pairs) {
    return std::any_of(rows.begin(), rows.end(),
                       [&](const json& r) { return row_has(r, checks, tri_pairs); });
  };
  const bool missed = any("missed", "missed_tri_pairs");
  const bool false_any = any("false_contacts", "false_tri_pairs");
  const auto refused = std::count_if(rows.begin(), rows.end(),
                                     [](const json& r) { return r["status"] == "refused"; });
  doc["missed_any"] = missed;  // `rows` is not used past here: adding keys may move it
  doc["false_any"] = false_any;
  doc["refused"] = refused;
}

std::string shard_name(int index, int count) {
  return "objects.shard-" + std::to_string(index) + "-of-" + std::to_string(count) + ".json";
}

// An object set's verdict column: held, or gripped/not gripped with the reason, or refused.
std::string verdict_text(const json& row) {
  if (row["status"] != "checked") return "refused";
  if (row["held"].get<bool>()) return "held";
  const std::string reason = row["reason"].is_string() ? row["reason"].get<std::string>() : "";
  return std::string(row["gripped"].get<bool>() ? "gripped, not held" : "not gripped") +
         (reason.empty() ? "" : ": " + reason);
}

// One row of the table: the object, its scale, steps, steps with contact, CGAL's hits, each
// method's missed/false, the verdict ('-' for a refused object).
void object_row(std::ostream& out, const json& r, std::size_t width, std::size_t methods) {
  out << std::left << std::setw(static_cast<int>(width) + 2) << r["object"].get<std::string>()
      << std::right;
  if (r["status"] == "checked") {
    std::ostringstream scale;
    scale << std::setprecision(4) << r["scale"].get<double>();
    out << std::setw(9) << scale.str() << std::setw(7) << r["steps"].get<int>() << std::setw(9)
        << r["steps_with_contact"].get<int>() << std::setw(7) << r["cgal_hits"].get<int>();
    for (const json& m : r["methods"]) {
      out << std::setw(22)
          << std::to_string(m["missed"].get<int>()) + "/" +
                 std::to_string(m["false_contacts"].get<int>());
    }
  } else {
    out << std::setw(9) << "-" << std::setw(7) << "-" << std::setw(9) << "-" << std::setw(7) << "-";
    for (std::size_t k = 0; k < methods; ++k) out << std::setw(22) << "-";
  }
  out << "  " << verdict_text(r) << '\n';
}

}  // namespace

std::vector<std::string> find_object_files(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw io::InputError(dir, 0, "not a folder of objects");
  const fs::path root = fs::canonical(dir, ec);
  if (ec) throw io::InputError(dir, 0, "cannot read the folder: " + ec.message());
  // Inside the root: what a symbolic link names must lie under it (a link that leads out, or up
  // into a loop, is not followed), and each folder is read once, known by device and inode.
  const auto inside = [&root](const fs::path& p) {
    std::error_code e;
    const fs::path target = fs::canonical(p, e);
    if (e) return false;
    const auto [r, t] = std::mismatch(root.begin(), root.end(), target.begin(), target.end());
    return r == root.end();
  };
  std::set<std::pair<dev_t, ino_t>> seen;
  const auto first_visit = [&seen](const fs::path& p) {
    struct stat info {};
    if (::stat(p.c_str(), &info) != 0) return false;
    return seen.emplace(info.st_dev, info.st_ino).second;
  };
  std::vector<std::string> files;
  std::vector<fs::path> folders{fs::path(dir)};
  first_visit(dir);
  while (!folders.empty()) {
    const fs::path folder = folders.back();
    folders.pop_back();
    fs::directory_iterator it(folder, ec);
    if (ec) throw io::InputError(folder.string(), 0, "cannot read the folder: " + ec.message());
    for (const fs::directory_entry& e : it) {
      if (e.is_symlink(ec) && !inside(e.path())) {
        // Not followed; a mesh's name is not left out without a word.
        if (is_object_file(e.path())) {
          warnings().add("object_skipped",
                         e.path().string() +
                             ": a link that leads out of the folder of objects (or nowhere): "
                             "skipped",
                         "scene");
        }
        continue;
      }
      if (e.is_directory(ec)) {
        if (first_visit(e.path())) folders.push_back(e.path());
      } else if (is_object_file(e.path())) {
        // A regular file, or a FIFO or device of a mesh's name: its row says why it is refused.
        files.push_back(fs::relative(e.path(), dir).generic_string());
      }
    }
  }
  if (files.empty())
    throw io::InputError(dir, 0,
                         "no mesh file in the folder (.obj, .stl, .off, .ply, .gltf, .glb, .dae)");
  std::sort(files.begin(), files.end());
  files.erase(std::unique(files.begin(), files.end()), files.end());
  return files;
}

json validate_object_set(const ObjectSetOptions& options, const std::vector<TesterSpec>& testers) {
  const std::vector<std::string> objects = find_object_files(options.dir);
  const Shard shard = options.shard.value_or(Shard{});
  json doc = {{"objects_dir", options.dir},
              {"hand", options.hand.name},
              {"template", options.hand.scene},
              {"settings", settings_json(options, testers)},
              {"objects", objects},
              {"shard", {{"index", shard.index}, {"count", shard.count}}},
              {"rows", json::array()}};
  json& rows = doc["rows"];
  const std::size_t first = static_cast<std::size_t>(shard.index);
  const std::size_t stride = static_cast<std::size_t>(shard.count);
  for (std::size_t i = first; i < objects.size(); i += stride) {
    const std::string& object = objects[i];
    const std::string file = (fs::path(options.dir) / object).string();
    if (options.log) {
      options.log("object " + std::to_string(i + 1) + " of " + std::to_string(objects.size()) +
                  ": " + object);
    }
    grasp::ObjectRunOptions run_options;
    run_options.file = file;
    run_options.hand = options.hand;
    grasp::ObjectRun run(run_options);
    grasp::ObjectPlacement placement = options.placement;
    placement.file = file;
    // A bad object is its row and a warning; a bad --up (std::invalid_argument) stops the set.
    try {
      run.write(placement);
      ValidateOptions validate;
      validate.max_steps = options.max_steps;
      validate.names = run.names();
      if (!options.out_dir.empty()) {
        validate.out_dir =
            (fs::path(options.out_dir) / fs::path(object).replace_extension()).string();
      }
      const ValidationReport report = validate_scene(run.scene(), testers, validate);
      if (report.states_with_contact() == 0) {
        warnings().add("validate_no_contact",
                       file + ": no checked state had a contact to check (no pair ever touched)",
                       "scene");
      }
      rows.push_back(checked_row(object, run.description().scene, report));
    } catch (const io::InputError& e) {
      rows.push_back(refused_row(object, e.what()));
      warnings().add("object_refused", e.what(), "scene");
    }
    if (options.on_row) options.on_row(doc, rows.back());
  }
  set_verdicts(doc);
  return doc;
}

json merge_object_shards(const std::vector<std::string>& files) {
  if (files.empty()) throw std::runtime_error("--merge needs at least one shard file");
  json merged;
  std::map<int, std::string> file_of_shard;
  std::map<std::string, json> rows_by_object;
  int count = 0;
  for (const std::string& f : files) {
    json j =
        read_shard_file(f, "an object-set shard", {"rows", "objects", "settings", "hand", "shard"});
    const int index = j["shard"]["index"].get<int>();
    if (merged.is_null()) {
      merged = j;
      count = j["shard"]["count"].get<int>();
    } else {
      if (j["objects"] != merged["objects"] || j["objects_dir"] != merged["objects_dir"]) {
        throw std::runtime_error(f + ": a shard of another object set (its objects differ)");
      }
      if (j["settings"] != merged["settings"] || j["hand"] != merged["hand"] ||
          j["template"] != merged["template"]) {
        throw std::runtime_error(f + ": run with other settings (hand, placement, methods)");
      }
      if (j["shard"]["count"].get<int>() != count) {
        throw std::runtime_error(f + ": a shard of another split (" +
                                 std::to_string(j["shard"]["count"].get<int>()) + " shards, not " +
                                 std::to_string(count) + ")");
      }
    }
    if (file_of_shard.count(index) > 0) {
      throw std::runtime_error(f + ": shard " + std::to_string(index) + " of " +
                               std::to_string(count) + " appears twice (also " +
                               file_of_shard[index] + ")");
    }
    file_of_shard[index] = f;
    // The shards' warnings (objects refused, nothing to check) go into this process's sink, so
    // the merged document's envelope carries them.
    if (j.contains("warnings") && j["warnings"].is_array()) {
      for (const json& w : j["warnings"]) {
        warnings().add(w.value("code", std::string()), w.value("message", std::string()),
                       w.value("source", std::string()));
      }
    }
    for (const json& row : j["rows"]) rows_by_object[row["object"].get<std::string>()] = row;
  }
  for (int i = 0; i < count; ++i) {
    if (file_of_shard.count(i) > 0) continue;
    std::string names;
    const json& objects = merged["objects"];
    for (std::size_t k = static_cast<std::size_t>(i); k < objects.size();
         k += static_cast<std::size_t>(count)) {
      names += (names.empty() ? "" : ", ") + objects[k].get<std::string>();
    }
    throw std::runtime_error("shard " + std::to_string(i) + " of " + std::to_string(count) + " (" +
                             shard_name(i, count) + ") is missing: its objects " + names +
                             " are in no file given");
  }
  json rows = json::array();
  for (const json& object : merged["objects"]) {
    const auto it = rows_by_object.find(object.get<std::string>());
    if (it == rows_by_object.end()) {
      throw std::runtime_error(object.get<std::string>() + ": in no row of the shards given");
    }
    rows.push_back(it->second);
  }
  merged["rows"] = rows;
  merged["shard"] = {{"index", 0}, {"count", 1}};
  merged["merged_from"] = files.size();
  set_verdicts(merged);
  merged.erase("graspcd");
  merged.erase("warnings");
  return merged;
}

namespace {

// The width of the object column: the longest name among the shard's objects.
std::size_t object_width(const json& doc) {
  const std::size_t first = doc["shard"]["index"].get<std::size_t>();
  const std::size_t stride = doc["shard"]["count"].get<std::size_t>();
  std::size_t width = 6;
  const json& objects = doc["objects"];
  for (std::size_t i = first; i < objects.size(); i += stride) {
    width = std::max(width, objects[i].get<std::string>().size());
  }
  return width;
}

}  // namespace

std::string object_set_head(const json& doc) {
  std::ostringstream out;
  const json& settings = doc["settings"];
  const std::size_t count = doc["shard"]["count"].get<std::size_t>();
  const std::size_t index = doc["shard"]["index"].get<std::size_t>();
  const std::size_t objects = doc["objects"].size();
  const std::size_t in_shard = objects > index ? (objects - index + count - 1) / count : 0;
  out << "# graspcd validate --objects " << doc["objects_dir"].get<std::string>() << ": "
      << in_shard << " of " << objects << " objects";
  if (count > 1) out << " (shard " << index << " of " << count << ")";
  out << " in the " << doc["hand"].get<std::string>() << " template, "
      << (settings["fit"].get<bool>() ? "fitted" : "at the given scale") << "; truth: CGAL "
      << exact::cgal_version() << '\n';
  out << std::left << std::setw(static_cast<int>(object_width(doc)) + 2) << "object" << std::right
      << std::setw(9) << "scale" << std::setw(7) << "steps" << std::setw(9) << "contact"
      << std::setw(7) << "cgal";
  for (const json& m : settings["methods"]) {
    out << std::setw(22) << m.get<std::string>() + " missed/false";
  }
  out << "  verdict\n";
  return out.str();
}

std::string object_set_row(const json& doc, const json& row) {
  std::ostringstream out;
  object_row(out, row, object_width(doc), doc["settings"]["methods"].size());
  return out.str();
}

std::string object_set_tail(const json& doc) {
  std::ostringstream out;
  const json& rows = doc["rows"];
  int refused = 0;
  for (const json& r : rows) {
    if (r["status"] == "checked") continue;
    ++refused;
    out << "# refused: " << r["error"].get<std::string>() << '\n';
  }
  const std::size_t checked = rows.size() - static_cast<std::size_t>(refused);
  const bool missed = doc["missed_any"].get<bool>(), false_any = doc["false_any"].get<bool>();
  out << "# result: "
      << (missed && false_any ? "MISSED AND FALSE COLLISIONS"
          : missed            ? "MISSED COLLISIONS"
          : false_any         ? "FALSE COLLISIONS"
                              : "no missed or false collision")
      << "; " << checked << (checked == 1 ? " object" : " objects") << " checked, " << refused
      << " refused\n";
  return out.str();
}

std::string object_set_text(const json& doc) {
  std::string text = object_set_head(doc);
  for (const json& r : doc["rows"]) text += object_set_row(doc, r);
  return text + object_set_tail(doc);
}

void write_object_set(const std::string& out_dir, json doc) {
  const int index = doc["shard"]["index"].get<int>(), count = doc["shard"]["count"].get<int>();
  const fs::path path = fs::path(out_dir) / (count > 1 ? shard_name(index, count) : "objects.json");
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  if (ec) {
    throw io::InputError(path.parent_path().string(), 0,
                         "cannot create the output folder: " + ec.message());
  }
  add_envelope(doc);
  std::ofstream out(path);
  out << doc.dump(1) << '\n';
  out.flush();
  if (!out) throw io::InputError(path.string(), 0, "cannot write the file");
}

}  // namespace graspcd::study
