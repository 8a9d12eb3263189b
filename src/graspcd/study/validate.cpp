#include "graspcd/study/validate.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <stdexcept>

#include "graspcd/core/clock.h"
#include "graspcd/exact/exact.h"
#include "graspcd/grasp/grasp.h"
#include "graspcd/mujoco/collision.h"
#include "graspcd/mujoco/collision_pose.h"
#include "graspcd/mujoco/registry.h"

namespace graspcd::study {

namespace {

class DetectorTester : public PairTester {
 public:
  DetectorTester(Method method, const DetectorOptions& options, std::size_t pairs)
      : detectors_(pairs, Detector(method, options)) {}
  bool tree_query(std::size_t pair, const ObbTree& a, const ObbTree& b, const Pose& b_in_a,
                  std::vector<TrianglePair>& tri_pairs) override {
    QueryCounters counters;
    tri_pairs.clear();
    return detectors_[pair]
        .collide(a, b, b_in_a, QueryMode::kAllContacts, counters, &tri_pairs)
        .intersect;
  }
  bool box_disjoint(std::size_t pair, const Obb& a, const Obb& b) override {
    QueryCounters counters;
    return detectors_[pair].box_disjoint(a, b, counters);
  }

 private:
  std::vector<Detector> detectors_;
};

std::string geom_label(const mjModel* m, int g) {
  const char* name = mj_id2name(m, mjOBJ_GEOM, g);
  return name && *name ? std::string(name) : "geom" + std::to_string(g);
}

// A served pair as MuJoCo calls it, and what the check needs of it.
struct CheckedPair {
  int geom1 = 0;
  int geom2 = 0;
  bool box_box = false;
  const mujoco::MeshTree* tree1 = nullptr;
  const mujoco::MeshTree* tree2 = nullptr;
  const std::vector<Triangle>* faces1 = nullptr;  // face order (the tree's face ids)
  const std::vector<Triangle>* faces2 = nullptr;
  Vec3 half1 = Vec3::Zero();  // box-box pairs: the geom boxes' half-extents
  Vec3 half2 = Vec3::Zero();
};

// Text of a double that reads back (strtod) as the same double.
std::string exact_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.17g", v);
  return buf;
}

std::string quoted(const std::string& s) { return "'" + s + "'"; }

// Writes the triangles as an OBJ with three vertices per face, so that face i of the file is
// face i of the tree, every coordinate printed so that it reads back as the same double.
void write_obj(const std::filesystem::path& path, const std::vector<Triangle>& faces,
               const std::string& comment) {
  std::ofstream out(path);
  out << "# " << comment << "\n";
  for (const Triangle& t : faces) {
    for (const Vec3& p : t.v) {
      out << "v " << exact_text(p.x()) << ' ' << exact_text(p.y()) << ' ' << exact_text(p.z())
          << '\n';
    }
  }
  for (std::size_t f = 0; f < faces.size(); ++f) {
    out << "f " << 3 * f + 1 << ' ' << 3 * f + 2 << ' ' << 3 * f + 3 << '\n';
  }
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
}

void append_matrix(std::string& line, const Mat3& R) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) line += ' ' + exact_text(R(i, j));
  }
}

void append_vector(std::string& line, const Vec3& v) {
  for (int i = 0; i < 3; ++i) line += ' ' + exact_text(v[i]);
}

void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
}

std::string file_stem(const std::string& method, const std::string& pair, const std::string& phase,
                      long step) {
  std::string s = method + "_" + pair + (phase == "closing" ? "" : "_" + phase) + "_step" +
                  std::to_string(step);
  for (char& c : s) {
    if (c == '/' || c == ' ') c = '-';
  }
  return s;
}

// Sizes of a \ b and b \ a of two sorted sequences.
std::pair<std::uint64_t, std::uint64_t> set_differences(const std::vector<TrianglePair>& a,
                                                        const std::vector<TrianglePair>& b) {
  std::uint64_t only_a = 0;
  std::uint64_t only_b = 0;
  std::size_t i = 0;
  std::size_t j = 0;
  while (i < a.size() || j < b.size()) {
    if (j == b.size() || (i < a.size() && a[i] < b[j])) {
      ++only_a;
      ++i;
    } else if (i == a.size() || b[j] < a[i]) {
      ++only_b;
      ++j;
    } else {
      ++i;
      ++j;
    }
  }
  return {only_a, only_b};
}

class Validator {
 public:
  Validator(const std::vector<TesterSpec>& specs, const ValidateOptions& options)
      : specs_(specs), options_(options) {}

  // After step `step` of `phase` (a closing grasp step, or a physics step of a later phase):
  // every pair of `registry` (built on the model `d` steps, or on a copy of it with the same geom
  // ids) at the poses of `d`.
  // `group` is the ValidatePhases name that counts it (the settling's states count in the
  // squeeze's), `phase` the grasp's phase that disagreements name.
  void check_step(const mujoco::Registry& registry, const mjData* d, const std::string& group,
                  const std::string& phase, long step) {
    if (pairs_.empty()) set_up(registry);
    phase_ = phase;
    bool any_contact = false;
    for (std::size_t i = 0; i < pairs_.size(); ++i) {
      const CheckedPair& p = pairs_[i];
      // A placement MuJoCo calls bad (NaN, inf, beyond 1e10), as the served path: not checked,
      // counted (neither the methods nor CGAL answer on a meaningless pose).
      if (mujoco::bad_geom_placement(d, p.geom1) || mujoco::bad_geom_placement(d, p.geom2)) {
        ++report_.nonfinite_skips;
        continue;
      }
      const Pose pose = mujoco::relative_pose(d, p.geom1, p.geom2);
      const bool truth = p.box_box ? check_boxes(i, pose, step) : check_trees(i, pose, step);
      any_contact = any_contact || truth;
    }
    PhaseChecks* checks = nullptr;
    for (PhaseChecks& c : report_.phases) {
      if (c.phase == group) checks = &c;
    }
    if (!checks) throw std::logic_error("validate: phase " + group + " was not asked for");
    ++checks->states;
    checks->with_contact += any_contact;
    if (group == "closing") {
      report_.steps = static_cast<int>(step);
      report_.steps_with_contact += any_contact;
    }
    if (options_.on_step) options_.on_step(phase, step);
  }

  ValidationReport finish(const grasp::GraspResult& grasp) {
    report_.grasp_method = grasp.method;
    report_.gripped = grasp.gripped;
    report_.held = grasp.held;
    report_.reason = grasp.reason;
    return std::move(report_);
  }

  ValidationReport& report() { return report_; }

 private:
  void set_up(const mujoco::Registry& registry) {
    const mjModel* m = registry.model();
    for (const mujoco::ServedPair& s : registry.pairs()) {
      CheckedPair p;
      // MuJoCo's order (mj_collision): the geom of the lower type first, then the lower id.
      const bool swap = m->geom_type[s.geom_lo] > m->geom_type[s.geom_hi];
      p.geom1 = swap ? s.geom_hi : s.geom_lo;
      p.geom2 = swap ? s.geom_lo : s.geom_hi;
      p.box_box = s.path == mujoco::PairPath::kBoxBox;
      if (p.box_box) {
        p.half1 = Vec3(m->geom_size[3 * p.geom1], m->geom_size[3 * p.geom1 + 1],
                       m->geom_size[3 * p.geom1 + 2]);
        p.half2 = Vec3(m->geom_size[3 * p.geom2], m->geom_size[3 * p.geom2 + 1],
                       m->geom_size[3 * p.geom2 + 2]);
      } else {
        p.tree1 = registry.geom_tree(p.geom1);
        p.tree2 = registry.geom_tree(p.geom2);
        if (!p.tree1 || !p.tree2) throw std::runtime_error("validate: a tree pair without trees");
        p.faces1 = &faces_of(*p.tree1);
        p.faces2 = &faces_of(*p.tree2);
      }
      pairs_.push_back(p);
    }
    for (const TesterSpec& spec : specs_) {
      testers_.push_back(spec.make(pairs_.size()));
      MethodTable table;
      table.method = spec.name;
      for (const CheckedPair& p : pairs_) {
        PairRow row;
        row.pair = geom_label(m, p.geom1) + "/" + geom_label(m, p.geom2);
        row.geom1 = p.geom1;
        row.geom2 = p.geom2;
        row.box_box = p.box_box;
        table.rows.push_back(row);
      }
      report_.methods.push_back(std::move(table));
    }
  }

  const std::vector<Triangle>& faces_of(const mujoco::MeshTree& tree) {
    auto it = faces_.find(&tree);
    if (it == faces_.end()) {
      std::vector<Triangle> f(tree.slot_of_face.size());
      for (std::size_t i = 0; i < f.size(); ++i) f[i] = tree.face(static_cast<std::int32_t>(i));
      it = faces_.emplace(&tree, std::move(f)).first;
    }
    return it->second;
  }

  // Checks pair i at this step with every tester; returns CGAL's answer (the pair intersects).
  bool check_trees(std::size_t i, const Pose& pose, long step) {
    const CheckedPair& p = pairs_[i];
    Clock::time_point start = Clock::now();
    std::vector<Triangle> moved = *p.faces2;
    for (Triangle& t : moved) t = apply_pose(pose, t);
    const std::vector<TrianglePair> truth = exact::mesh_mesh_pairs(*p.faces1, moved);
    report_.exact_seconds += seconds_since(start);
    for (std::size_t k = 0; k < testers_.size(); ++k) {
      start = Clock::now();
      const bool hit = testers_[k]->tree_query(i, p.tree1->tree, p.tree2->tree, pose, found_);
      add_time(k, start);
      std::sort(found_.begin(), found_.end());
      PairRow& row = report_.methods[k].rows[i];
      const auto [missed, extra] = set_differences(truth, found_);
      const bool agree = hit == !truth.empty() && missed == 0 && extra == 0;
      tally(row, !truth.empty(), hit, agree);
      row.missed_tri_pairs += missed;
      row.false_tri_pairs += extra;
      if (!agree && !row.disagreed) {
        row.disagreed = true;
        row.first =
            Disagreement{phase_, step, !truth.empty(), hit, truth.size(), found_.size(), {}, {}};
        if (!options_.out_dir.empty()) write_tree_case(k, row, p, pose, step);
      }
    }
    return !truth.empty();
  }

  bool check_boxes(std::size_t i, const Pose& pose, long step) {
    const CheckedPair& p = pairs_[i];
    Obb a;
    a.half = p.half1;
    Obb b_local;
    b_local.half = p.half2;
    const Obb b = transform(pose, b_local);
    Clock::time_point start = Clock::now();
    const bool truth = exact::box_box_overlap(a, b);
    report_.exact_seconds += seconds_since(start);
    for (std::size_t k = 0; k < testers_.size(); ++k) {
      start = Clock::now();
      const bool hit = !testers_[k]->box_disjoint(i, a, b);
      add_time(k, start);
      PairRow& row = report_.methods[k].rows[i];
      tally(row, truth, hit, hit == truth);
      if (hit != truth && !row.disagreed) {
        row.disagreed = true;
        row.first = Disagreement{phase_, step, truth, hit, 0, 0, {}, {}};
        if (!options_.out_dir.empty()) write_box_case(k, row, a, b, step);
      }
    }
    return truth;
  }

  void add_time(std::size_t k, Clock::time_point start) {
    const double s = seconds_since(start);
    report_.methods[k].seconds += s;
    report_.tester_seconds += s;
  }

  static void tally(PairRow& row, bool truth, bool hit, bool agree) {
    ++row.steps;
    row.agree += agree;
    row.truth_hits += truth;
    row.missed += truth && !hit;
    row.false_contacts += hit && !truth;
    row.pair_mismatch += truth && hit && !agree;
  }

  std::filesystem::path out_dir() const {
    const std::filesystem::path dir(options_.out_dir);
    std::filesystem::create_directories(dir);
    return dir;
  }

  // "closing grasp step 12", "squeeze physics step 40".
  std::string where(long step) const {
    return phase_ + (phase_ == "closing" ? " grasp step " : " physics step ") +
           std::to_string(step);
  }

  void write_tree_case(std::size_t k, PairRow& row, const CheckedPair& p, const Pose& pose,
                       long step) {
    const std::filesystem::path dir = out_dir();
    const std::string stem = file_stem(specs_[k].name, row.pair, phase_, step);
    const std::filesystem::path a = dir / (stem + "_a.obj");
    const std::filesystem::path b = dir / (stem + "_b.obj");
    const std::filesystem::path poses = dir / (stem + "_pose.txt");
    const std::string at = " at " + where(step) + " of " + report_.scene +
                           ": MuJoCo's vertices in the geom frame, face order "
                           "kept, each coordinate printed to read back as the same double";
    const std::string name1 = row.pair.substr(0, row.pair.find('/'));
    const std::string name2 = row.pair.substr(row.pair.find('/') + 1);
    write_obj(a, *p.faces1, "graspcd validate: geom " + name1 + at);
    write_obj(b, *p.faces2, "graspcd validate: geom " + name2 + at);
    std::string line;
    append_matrix(line, pose.R);
    append_vector(line, pose.t);
    write_text(poses, "# graspcd validate: " + name2 + " in " + name1 + "'s frame at " +
                          where(step) + ": R row-major (9), t (3)\n" + line.substr(1) + "\n");
    row.first.files = {a.string(), b.string(), poses.string()};
    row.first.command = "graspcd meshpair " + quoted(a.string()) + " " + quoted(b.string()) + " " +
                        specs_[k].cli_args + " --poses " + quoted(poses.string());
  }

  void write_box_case(std::size_t k, PairRow& row, const Obb& a, const Obb& b, long step) {
    const std::filesystem::path file =
        out_dir() / (file_stem(specs_[k].name, row.pair, phase_, step) + "_boxes.txt");
    std::string line;
    for (const Obb* box : {&a, &b}) {
      append_vector(line, box->center);
      append_matrix(line, box->axes);
      append_vector(line, box->half);
    }
    write_text(file, "# graspcd validate: the boxes of " + row.pair + " at " + where(step) +
                         " of " + report_.scene +
                         " in the first geom's frame: centre, R row-major, half-extents of each\n" +
                         line.substr(1) + "\n");
    row.first.files = {file.string()};
    row.first.command = "graspcd boxbox " + specs_[k].cli_args + " " + quoted(file.string());
  }

  const std::vector<TesterSpec>& specs_;
  const ValidateOptions& options_;
  ValidationReport report_;
  std::vector<CheckedPair> pairs_;
  std::vector<std::unique_ptr<PairTester>> testers_;
  std::map<const mujoco::MeshTree*, std::vector<Triangle>> faces_;
  std::vector<TrianglePair> found_;
  std::string phase_ = "closing";  // of the state being checked
};

}  // namespace

TesterSpec detector_tester(Method method, const DetectorOptions& options) {
  TesterSpec spec;
  spec.name = method_name(method);
  spec.cli_args = std::string("--method ") + method_name(method);
  if (uses_perceptron(method)) spec.cli_args += " --cap " + std::to_string(options.cap);
  if (method == Method::kNeuroSat || method == Method::kNeuroSatSticky) {
    spec.cli_args += " --switch " + std::to_string(options.switch_passes);
  }
  spec.make = [method, options](std::size_t pairs) -> std::unique_ptr<PairTester> {
    return std::make_unique<DetectorTester>(method, options, pairs);
  };
  return spec;
}

bool MethodTable::missed_any() const {
  return std::any_of(rows.begin(), rows.end(),
                     [](const PairRow& r) { return r.missed > 0 || r.missed_tri_pairs > 0; });
}

bool ValidationReport::missed_any() const {
  return std::any_of(methods.begin(), methods.end(),
                     [](const MethodTable& t) { return t.missed_any(); });
}

ValidatePhases parse_validate_phases(const std::string& text) {
  if (text == "all") return ValidatePhases{true, true, true, true};
  ValidatePhases phases{false, false, false, false};
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t comma = std::min(text.find(',', begin), text.size());
    const std::string name = text.substr(begin, comma - begin);
    bool* phase = name == "closing"   ? &phases.closing
                  : name == "squeeze" ? &phases.squeeze
                  : name == "lift"    ? &phases.lift
                  : name == "hold"    ? &phases.hold
                                      : nullptr;
    if (!phase) {
      throw std::invalid_argument("'" + name +
                                  "' is not a phase: give all, or some of closing, squeeze, lift, "
                                  "hold separated by commas");
    }
    if (*phase) throw std::invalid_argument("phase '" + name + "' is given twice");
    *phase = true;
    begin = comma + 1;
  }
  return phases;
}

int ValidationReport::states_with_contact() const {
  int n = 0;
  for (const PhaseChecks& c : phases) n += c.with_contact;
  return n;
}

namespace {

// The phases asked for, in the grasp's order, with the physics steps between two checks.
std::vector<PhaseChecks> asked_phases(const ValidatePhases& phases, int every) {
  std::vector<PhaseChecks> out;
  if (phases.closing) out.push_back({"closing", 0, 0, 0});
  if (phases.squeeze) out.push_back({"squeeze", 0, 0, every});
  if (phases.lift) out.push_back({"lift", 0, 0, every});
  if (phases.hold) out.push_back({"hold", 0, 0, every});
  return out;
}

// Whether the grasp's phase `record_phase` (GraspOptions::on_physics_step's name) is checked,
// and under which of ValidatePhases' names: the settling belongs to the squeeze.
const char* checked_phase(const ValidatePhases& phases, const std::string& record_phase) {
  if ((record_phase == "squeeze" || record_phase == "settle") && phases.squeeze) return "squeeze";
  if (record_phase == "lift" && phases.lift) return "lift";
  if (record_phase == "hold" && phases.hold) return "hold";
  return nullptr;
}

}  // namespace

ValidationReport validate_scene(const std::string& scene, const std::vector<TesterSpec>& testers,
                                const ValidateOptions& options) {
  Validator validator(testers, options);
  validator.report().scene = scene;
  grasp::GraspOptions grasp;
  grasp.config_path = options.config_path;
  grasp.max_steps = options.max_steps;
  grasp.names = options.names;
  const int every = std::max(1, grasp.physics_steps_per_grasp_step);
  validator.report().phases = asked_phases(options.phases, every);
  const std::string config =
      options.config_path.empty() ? mujoco::pair_config_path(scene) : options.config_path;
  // The registry whose pairs are checked, found on the first check: the served run's own, or for
  // a decomposed run (native, no registry) one of the config built, unattached, on a copy of its
  // model with the true object colliding.
  const bool decomposed = !options.decomposed_dir.empty();
  const mujoco::RegistryConfig registry_config =
      decomposed ? mujoco::load_registry_config(config) : mujoco::RegistryConfig{};
  mujoco::ModelPtr truth;
  std::unique_ptr<mujoco::Registry> own_registry;
  const auto registry_of = [&](const mjModel* m) -> const mujoco::Registry& {
    if (!decomposed) {
      const mujoco::Registry* registry = mujoco::find_registry(m);
      if (!registry) {
        throw std::runtime_error("validate: no pair registry is attached to the model");
      }
      return *registry;
    }
    if (!own_registry) {
      truth = grasp::true_object_model(m);
      own_registry = std::make_unique<mujoco::Registry>(truth.get(), registry_config, config);
    }
    return *own_registry;
  };
  if (options.phases.closing) {
    grasp.on_grasp_step = [&](const mjModel* m, const mjData* d, int step) {
      validator.check_step(registry_of(m), d, "closing", "closing", step);
    };
  }
  if (options.phases.squeeze || options.phases.lift || options.phases.hold) {
    grasp.on_physics_step = [&](const mjModel* m, const mjData* d, const std::string& phase,
                                long step) {
      const char* checked = checked_phase(options.phases, phase);
      if (checked && step % every == 0) {
        validator.check_step(registry_of(m), d, checked, phase, step);
      }
    };
  }
  grasp::DecomposedScene pieces;
  const grasp::GraspResult result =
      decomposed ? grasp::run_decomposed_grasp(scene, options.decomposed_dir, grasp, &pieces)
                 : grasp::run_grasp(scene, grasp);
  own_registry.reset();  // before its model
  ValidationReport report = validator.finish(result);
  report.config = config;
  report.max_steps = options.max_steps;
  report.cut_short = result.closing == "max_steps";
  if (decomposed) {
    report.decomposed_dir = options.decomposed_dir;
    report.decomposed = pieces;
  }
  return report;
}

}  // namespace graspcd::study
