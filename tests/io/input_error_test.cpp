#include "graspcd/io/input_error.h"

#include <gtest/gtest.h>

namespace graspcd::io {
namespace {

TEST(OneLine, JoinsTrimmedLinesWithSemicolons) {
  EXPECT_EQ(one_line("XML Error: bad\nElement 'x', line 3\n"),
            "XML Error: bad; Element 'x', line 3");
  EXPECT_EQ(one_line("  first \r\n\n\t second\t"), "first; second");
  EXPECT_EQ(one_line("one line"), "one line");
  EXPECT_EQ(one_line(""), "");
}

TEST(InputError, IsOneLineNamingTheFileAndLine) {
  const InputError located("a.obj", 3, "bad number\nthere");
  EXPECT_STREQ(located.what(), "a.obj:3: bad number; there");
  EXPECT_EQ(located.file(), "a.obj");
  EXPECT_EQ(located.line(), 3u);
  EXPECT_EQ(located.message(), "bad number; there");
  EXPECT_STREQ(InputError("s.xml", 0, "cannot open").what(), "s.xml: cannot open");
}

}  // namespace
}  // namespace graspcd::io
