// nonconvex_contacts: a plain MuJoCo 2.2 program that gets graspcd's non-convex contacts from the
// installed package (find_package(graspcd), graspcd::mujoco). It loads a scene, serves the geom
// pairs of the pair config beside it (SCENE.pairs.json), steps with zero controls and prints, every
// 100 steps and at the end, MuJoCo's contacts and graspcd's per-step statistics.
//
// Usage: nonconvex_contacts SCENE.xml [STEPS] [METHOD]   (STEPS default 500, METHOD default: the
// config's). Output: "step S time T ncon N graspcd_contacts C served_calls K detection_us U" lines,
// then one summary line "summary steps ... served_pairs ... served_calls ... graspcd_contacts ...
// max_ncon ...". Any error: one line on stderr and exit code 2.
#include <mujoco/mujoco.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "graspcd/mujoco/nonconvex_contacts.h"

namespace {

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};

int run(int argc, char** argv) {
  if (argc < 2 || argc > 4) {
    throw std::invalid_argument("usage: nonconvex_contacts SCENE.xml [STEPS] [METHOD]");
  }
  const std::string scene = argv[1];
  long steps = 500;
  if (argc >= 3) {
    char* end = nullptr;
    steps = std::strtol(argv[2], &end, 10);
    if (*argv[2] == '\0' || *end != '\0' || steps < 1) {
      throw std::invalid_argument(std::string("STEPS must be a positive integer, not '") + argv[2] +
                                  "'");
    }
  }
  std::optional<graspcd::Method> method;
  if (argc == 4) {
    method = graspcd::parse_method(argv[3]);
    if (!method) throw std::invalid_argument(std::string("unknown method '") + argv[3] + "'");
  }

  // Load the scene as any MuJoCo program does.
  char error[1000] = "";
  std::unique_ptr<mjModel, ModelDeleter> m(mj_loadXML(scene.c_str(), nullptr, error, sizeof error));
  if (!m) {
    std::string message = error;  // MuJoCo's message may span lines: keep the error on one
    for (char& c : message) {
      if (c == '\n') c = ' ';
    }
    throw std::runtime_error(scene + ": " + message);
  }
  std::unique_ptr<mjData, DataDeleter> d(mj_makeData(m.get()));

  // graspcd's contacts for the config's pairs, until `contacts` goes out of scope.
  graspcd::mujoco::NonconvexContacts contacts(m.get(), graspcd::mujoco::pair_config_path(scene),
                                              method);
  for (const std::string& w : contacts.warnings()) std::fprintf(stderr, "warning: %s\n", w.c_str());

  // Step as usual; read graspcd's statistics once per step.
  std::uint64_t calls = 0, served_contacts = 0, detection_ns = 0;
  int max_ncon = 0;
  for (long s = 1; s <= steps; ++s) {
    mj_step(m.get(), d.get());
    const graspcd::mujoco::BridgeStats st = contacts.take_stats();
    calls += st.calls;
    served_contacts += st.contacts;
    detection_ns += st.detection_ns;
    if (d->ncon > max_ncon) max_ncon = d->ncon;
    if (s % 100 == 0 || s == steps) {
      std::printf(
          "step %ld time %.3f ncon %d graspcd_contacts %llu served_calls %llu "
          "detection_us %.1f\n",
          s, d->time, d->ncon, static_cast<unsigned long long>(st.contacts),
          static_cast<unsigned long long>(st.calls), static_cast<double>(st.detection_ns) / 1e3);
    }
  }
  std::printf(
      "summary steps %ld method %s served_pairs %zu served_calls %llu graspcd_contacts %llu "
      "max_ncon %d detection_ms %.3f\n",
      steps, graspcd::method_name(contacts.method()), contacts.served_pairs(),
      static_cast<unsigned long long>(calls), static_cast<unsigned long long>(served_contacts),
      max_ncon, static_cast<double>(detection_ns) / 1e6);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nonconvex_contacts: %s\n", e.what());
    return 2;
  }
}
