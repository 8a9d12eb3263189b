// Checks the JSON envelope every graspcd document carries (graspcd/version/envelope.h;
// docs/design.md, "The command line"): the build's provenance and the warnings array.
#pragma once

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "graspcd/version/provenance.h"

namespace graspcd::testing {

// The document names this build (the test and the executable are built from one provenance)
// and carries a well-formed warnings array; `warnings` is how many distinct warnings it must hold
// (-1: any number).
inline void expect_envelope(const nlohmann::json& doc, int warnings = 0) {
  ASSERT_TRUE(doc.contains("graspcd")) << "no provenance in the document";
  const nlohmann::json& p = doc.at("graspcd");
  const Provenance& built = provenance();
  EXPECT_EQ(p.at("version").get<std::string>(), built.version);
  const std::string commit = p.at("commit").get<std::string>();
  EXPECT_EQ(commit, built.commit);
  EXPECT_FALSE(commit.empty());
  const bool dirty = p.at("dirty").get<bool>();
  const std::string suffix = "-dirty";
  const bool named_dirty =
      commit.size() > suffix.size() &&
      commit.compare(commit.size() - suffix.size(), suffix.size(), suffix) == 0;
  EXPECT_EQ(dirty, named_dirty) << commit;
  ASSERT_TRUE(doc.contains("warnings"));
  ASSERT_TRUE(doc.at("warnings").is_array());
  if (warnings >= 0) {
    EXPECT_EQ(doc.at("warnings").size(), static_cast<std::size_t>(warnings));
  }
  for (const nlohmann::json& w : doc.at("warnings")) {
    EXPECT_FALSE(w.at("code").get<std::string>().empty()) << w;
    const std::string source = w.at("source").get<std::string>();
    EXPECT_TRUE(source == "mujoco" || source == "mesh" || source == "config" || source == "scene" ||
                source == "graspcd")
        << w;
    EXPECT_FALSE(w.at("message").get<std::string>().empty()) << w;
    EXPECT_GE(w.at("count").get<long>(), 1) << w;
  }
}

}  // namespace graspcd::testing
