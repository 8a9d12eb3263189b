#include "graspcd/io/warnings.h"

#include <gtest/gtest.h>

#include <thread>
#include <vector>

namespace graspcd {
namespace {

TEST(WarningSink, RepeatsRaiseTheCountAndKeepTheFirstOrder) {
  WarningSink sink;
  EXPECT_TRUE(sink.empty());
  sink.add("b_code", "second kind");
  sink.add("a_code", "first kind");
  sink.add("b_code", "second kind");
  sink.add("b_code", "another message under the same code");
  const std::vector<Warning> list = sink.list();
  ASSERT_EQ(list.size(), 3u);
  EXPECT_EQ(list[0].code, "b_code");
  EXPECT_EQ(list[0].count, 2);
  EXPECT_EQ(list[1].code, "a_code");
  EXPECT_EQ(list[1].count, 1);
  EXPECT_EQ(list[2].message, "another message under the same code");
  EXPECT_EQ(warning_line(list[0]), "second kind (2 times)");
  EXPECT_EQ(warning_line(list[1]), "first kind");
  sink.clear();
  EXPECT_TRUE(sink.empty());
}

// The study replays grasps on several threads: no add is lost.
TEST(WarningSink, ConcurrentAddsAreAllCounted) {
  WarningSink sink;
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&sink, t] {
      for (int i = 0; i < 1000; ++i) sink.add("shared", "the same warning");
      sink.add("own", "thread " + std::to_string(t));
    });
  }
  for (std::thread& th : threads) th.join();
  const std::vector<Warning> list = sink.list();
  ASSERT_EQ(list.size(), 5u);
  EXPECT_EQ(list[0].count, 4000);
}

}  // namespace
}  // namespace graspcd
