// graspcd meshpair A B [--method M] [--first-contact] [--exact] [--poses FILE|-] [--leaf-size N]
// [--fit covariance|hull]: per pose of B in A's frame, prints "1|0 PAIRS NS".
#include <chrono>
#include <cstdint>
#include <functional>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <tuple>
#include <utility>

#include "command.h"
#include "graspcd/core/clock.h"
#include "graspcd/core/obb_tree.h"
#include "graspcd/core/separators.h"
#include "graspcd/exact/exact.h"
#include "graspcd/io/mesh_io.h"
#include "graspcd/io/text_input.h"
#include "graspcd/io/warnings.h"
#include "graspcd/version/envelope.h"
#include "method.h"
#include "object_placement.h"

namespace graspcd::cli {

namespace {

struct MeshpairOptions {
  MethodOptions method;
  std::string mesh_a;
  std::string mesh_b;
  std::string poses = "-";
  bool first_contact = false;
  bool exact = false;
  int leaf_size = 1;
  std::string fit = "covariance";
  bool json = false;
  double scale = 1;  // --scale S: both meshes' coordinates multiplied by S
};

// One pose's answer and the time of the query alone.
struct PoseAnswer {
  QueryResult result;
  std::int64_t nanoseconds = 0;
};

using MeshQuery = std::function<PoseAnswer(const Pose& b_in_a)>;

// The tree query of the chosen method; the detector is kept across poses (the cached and warm
// methods carry state from one pose line to the next).
MeshQuery make_tree_query(const MeshpairOptions& options, std::shared_ptr<const ObbTree> a,
                          std::shared_ptr<const ObbTree> b) {
  const QueryMode mode = options.first_contact ? QueryMode::kFirstContact : QueryMode::kAllContacts;
  auto detector = std::make_shared<Detector>(make_detector(options.method));
  return [a, b, mode, detector](const Pose& b_in_a) {
    QueryCounters counters;
    PoseAnswer answer;
    const Clock::time_point start = Clock::now();
    answer.result = detector->collide(*a, *b, b_in_a, mode, counters);
    answer.nanoseconds = static_cast<std::int64_t>(elapsed_ns(start));
    return answer;
  };
}

// The CGAL brute force over every triangle pair: the ground truth, timed the same way.
MeshQuery exact_query(const MeshpairOptions& options, const TriangleMesh& mesh_a,
                      std::shared_ptr<const TriangleMesh> mesh_b) {
  auto triangles_a = std::make_shared<std::vector<Triangle>>();
  triangles_a->reserve(mesh_a.faces.size());
  for (std::size_t f = 0; f < mesh_a.faces.size(); ++f) triangles_a->push_back(mesh_a.triangle(f));
  const bool first_contact = options.first_contact;
  return [triangles_a, mesh_b, first_contact](const Pose& b_in_a) {
    const std::vector<Triangle> triangles_b = posed_triangles(*mesh_b, b_in_a);
    PoseAnswer answer;
    const Clock::time_point start = Clock::now();
    const std::vector<TrianglePair> pairs =
        exact::mesh_mesh_pairs(*triangles_a, triangles_b, first_contact);
    answer.nanoseconds = static_cast<std::int64_t>(elapsed_ns(start));
    answer.result.intersect = !pairs.empty();
    answer.result.pair_count = pairs.size();
    return answer;
  };
}

void run_meshpair(MeshpairOptions& options) {
  finish_method_options(options.method);
  // Load both meshes first, then build, so that a bad file is reported before any work.
  io::MeshStats stats_a, stats_b;
  TriangleMesh loaded_a = io::load_mesh(options.mesh_a, &stats_a);
  TriangleMesh loaded_b = io::load_mesh(options.mesh_b, &stats_b);
  io::scale_mesh(options.mesh_a, options.scale, &loaded_a);
  io::scale_mesh(options.mesh_b, options.scale, &loaded_b);
  // Mesh hygiene findings that change the answers or MuJoCo's view of the file (dropped
  // zero-area faces, an OBJ with several objects), one line each in the run's warnings; a closed
  // mesh whose faces point inward is turned right way out (containment reads their direction).
  for (const auto& [path, stats, mesh] : {std::tuple{options.mesh_a, &stats_a, &loaded_a},
                                          std::tuple{options.mesh_b, &stats_b, &loaded_b}}) {
    for (const std::string& w : io::mesh_warnings(path, *stats, true)) {
      warnings().add("mesh_hygiene", w);
    }
    const std::string flipped = io::turn_right_way_out(path, *stats, mesh);
    if (!flipped.empty()) warnings().add("mesh_inside_out", flipped);
  }
  const TriangleMesh mesh_a = std::move(loaded_a);
  auto mesh_b = std::make_shared<const TriangleMesh>(std::move(loaded_b));
  MeshQuery query;
  if (options.exact) {
    query = exact_query(options, mesh_a, mesh_b);
  } else {
    ObbTreeOptions tree_options;
    tree_options.leaf_size = options.leaf_size;
    tree_options.fit = options.fit == "hull" ? ObbFit::kHullArea : ObbFit::kCovariance;
    auto tree_a = std::make_shared<const ObbTree>(ObbTree::build(mesh_a, tree_options));
    auto tree_b = std::make_shared<const ObbTree>(ObbTree::build(*mesh_b, tree_options));
    query = make_tree_query(options, std::move(tree_a), std::move(tree_b));
  }

  constexpr std::size_t kNumbers = 12;
  nlohmann::json answers = nlohmann::json::array();
  for_each_case(options.poses, kNumbers, [&](const std::vector<double>& v) {
    const Pose pose = io::pose_from_numbers(v.data(), "pose");
    const PoseAnswer answer = query(pose);
    if (options.json) {
      answers.push_back({{"intersect", answer.result.intersect},
                         {"pairs", answer.result.pair_count},
                         {"ns", answer.nanoseconds}});
      return;
    }
    std::cout << (answer.result.intersect ? '1' : '0') << ' ' << answer.result.pair_count << ' '
              << answer.nanoseconds << '\n';
  });
  if (options.json) {
    nlohmann::json doc = {{"a", options.mesh_a},
                          {"b", options.mesh_b},
                          {"method", options.exact ? "exact" : method_name(options.method.method)},
                          {"first_contact", options.first_contact},
                          {"answers", answers}};
    add_envelope(doc);
    std::cout << doc.dump(2) << '\n';
  }
}

}  // namespace

Command add_meshpair_command(CLI::App& parent) {
  auto options = std::make_shared<MeshpairOptions>();
  CLI::App* app =
      parent.add_subcommand("meshpair", "Mesh pairs with OBB trees: per pose, '1|0 PAIRS NS'");
  app->add_option("A", options->mesh_a,
                  "Mesh A: OBJ, STL, OFF, PLY, glTF/GLB or COLLADA (docs/objects.md)")
      ->required();
  app->add_option("B", options->mesh_b, "Mesh B: the same formats")->required();
  app->add_option("--scale", options->scale,
                  "Multiply both meshes' coordinates by S (file units to metres: 0.001 for "
                  "millimetres); the poses' translations are then in metres")
      ->type_name("S")
      ->check(number_in_range(kMinScale, kMaxScale));
  add_method_options(*app, options->method);
  app->add_flag("--first-contact", options->first_contact,
                "Stop at the first intersecting triangle pair (PAIRS is then 0 or 1)");
  app->add_flag("--exact", options->exact,
                "Answer with CGAL by brute force over all triangle pairs (NS is then its time)");
  app->add_option("--poses", options->poses, "Pose file, or - for stdin")->capture_default_str();
  app->add_option("--leaf-size", options->leaf_size, "Most triangles per tree leaf")
      ->transform(positive_integer())
      ->capture_default_str();
  app->add_option("--fit", options->fit,
                  "Box fit: covariance (paper eq. 1-3) or hull (area-weighted, Gottschalk 1996)")
      ->check(CLI::IsMember({"covariance", "hull"}))
      ->capture_default_str();
  app->add_flag("--json", options->json,
                "Print one JSON document after the last pose instead of a line per pose");
  app->footer(wrap_help(
      "Per pose of mesh B in mesh A's frame, prints '1|0 PAIRS NS': whether the surfaces "
      "intersect, the number of intersecting triangle pairs (0 or 1 with --first-contact), and "
      "the time of the query alone in nanoseconds (after loading and building).\n"
      "Meshes are read in their own file coordinates (times --scale), OBJ, STL and OFF in "
      "double precision, PLY, glTF and COLLADA through Assimp in single precision; polygons are "
      "triangulated and all objects or meshes of a file concatenated. On load, equal vertices are "
      "welded and "
      "zero-area faces (segments, points) dropped; dropped faces and an OBJ with several "
      "objects (MuJoCo 2.2 keeps only the first) are each one line 'warning: FILE: ...' on "
      "stderr.\n"
      "Poses: one per line, 12 numbers: R row-major (9), then t (3), placing B in A's frame "
      "(x_A = R x_B + t). R must be a rotation to within 1e-9.\n"
      "--json: one document after the last pose: a, b, method ('exact' with --exact), "
      "first_contact, answers (per pose: intersect, pairs, ns), and the envelope's warnings.\n" +
      number_grammar_help() +
      "Example (B shifted by 0.05 m along x):\n"
      "  echo '1 0 0 0 1 0 0 0 1  0.05 0 0' | graspcd meshpair a.obj b.obj"));
  return Command{app, [options] { run_meshpair(*options); }};
}

}  // namespace graspcd::cli
