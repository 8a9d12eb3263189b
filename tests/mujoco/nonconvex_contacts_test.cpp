// NonconvexContacts, the public entry point (issue 11): it attaches its registry and installs the
// collision function for as long as it lives, counts installs across instances, leaves a
// program's own install alone, installs nothing when the config is bad, and its statistics are
// the served pairs' work of each step.
#include "graspcd/mujoco/nonconvex_contacts.h"

#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>

#include "graspcd/grasp/grasp.h"
#include "graspcd/mujoco/mujoco_ptr.h"

namespace graspcd::bridge {
namespace {

const std::string kMjcf = GRASPCD_MJCF_DIR;

struct Scene {
  ModelPtr model;
  DataPtr data;
  explicit Scene(const std::string& name)
      : model(load_model(kMjcf + "/" + name + ".xml")), data(mj_makeData(model.get())) {}
  std::string config(const std::string& name) const { return kMjcf + "/" + name + ".pairs.json"; }
};

TEST(NonconvexContacts, AttachesAndInstallsWhileAlive) {
  Scene s("example1");
  ASSERT_FALSE(installed());
  {
    NonconvexContacts contacts(s.model.get(), s.config("example1"));
    EXPECT_TRUE(installed());
    EXPECT_EQ(find_registry(s.model.get()), &contacts.registry());
    EXPECT_GT(contacts.served_pairs(), 0u);
    EXPECT_EQ(contacts.method(), Method::kSat);  // the config's
  }
  EXPECT_FALSE(installed());
  EXPECT_EQ(find_registry(s.model.get()), nullptr);
}

TEST(NonconvexContacts, MethodOverridesTheConfig) {
  Scene s("example1");
  NonconvexContacts contacts(s.model.get(), s.config("example1"), Method::kNeuroSat);
  EXPECT_EQ(contacts.method(), Method::kNeuroSat);
  for (const ServedPair& p : contacts.registry().pairs()) {
    ASSERT_TRUE(p.detector);
    EXPECT_EQ(p.detector->method(), Method::kNeuroSat);
  }
}

TEST(NonconvexContacts, InstallLastsUntilTheLastInstanceGoes) {
  Scene a("example1");
  Scene b("hand_triangles");
  auto first = std::make_unique<NonconvexContacts>(a.model.get(), a.config("example1"));
  auto second = std::make_unique<NonconvexContacts>(b.model.get(), b.config("hand_triangles"));
  first.reset();
  EXPECT_TRUE(installed());
  EXPECT_EQ(find_registry(a.model.get()), nullptr);
  EXPECT_EQ(find_registry(b.model.get()), &second->registry());
  second.reset();
  EXPECT_FALSE(installed());
}

TEST(NonconvexContacts, LeavesTheProgramsOwnInstallInPlace) {
  Scene s("example1");
  ScopedInstall program_install;
  { NonconvexContacts contacts(s.model.get(), s.config("example1")); }
  EXPECT_TRUE(installed());
}

TEST(NonconvexContacts, BadConfigThrowsAndInstallsNothing) {
  Scene s("example1");
  const std::string missing = kMjcf + "/no-such.pairs.json";
  try {
    NonconvexContacts contacts(s.model.get(), missing);
    FAIL() << "no error for a missing config";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind(missing, 0), 0u) << e.what();
  }
  RegistryConfig config;
  config.patterns.push_back({"geom:no_such_geom*", "body:object"});
  EXPECT_THROW(NonconvexContacts(s.model.get(), config), std::runtime_error);
  EXPECT_FALSE(installed());
  EXPECT_EQ(find_registry(s.model.get()), nullptr);
}

// The hand sinks onto the cup under gravity (zero controls): every step's statistics are that
// step's served calls, and the contacts they report are among MuJoCo's contacts of the step.
TEST(NonconvexContacts, StatisticsArePerStep) {
  Scene s("example1");
  NonconvexContacts contacts(s.model.get(), s.config("example1"));
  std::uint64_t total_contacts = 0;
  for (int step = 0; step < 100; ++step) {
    mj_step(s.model.get(), s.data.get());
    const BridgeStats st = contacts.take_stats();
    EXPECT_GT(st.calls, 0u);
    EXPECT_LE(st.calls, contacts.served_pairs());  // one collision pass per mj_step
    EXPECT_LE(st.contacts, static_cast<std::uint64_t>(s.data->ncon));
    total_contacts += st.contacts;
    EXPECT_EQ(contacts.stats().calls, 0u);  // taken
  }
  EXPECT_GT(total_contacts, 0u);
}

}  // namespace
}  // namespace graspcd::bridge
