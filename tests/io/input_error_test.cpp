#include "graspcd/io/input_error.h"

#include <gtest/gtest.h>

#include <string>

namespace graspcd::io {
namespace {

TEST(OneLine, JoinsTrimmedLinesWithSemicolons) {
  EXPECT_EQ(one_line("XML Error: bad\nElement 'x', line 3\n"),
            "XML Error: bad; Element 'x', line 3");
  EXPECT_EQ(one_line("  first \r\n\n\t second\t"), "first; second");
  EXPECT_EQ(one_line("one line"), "one line");
  EXPECT_EQ(one_line(""), "");
}

// A terminal takes C0 and C1 controls, DEL and stray high bytes for commands: each is written
// \xNN, once; tabs and well-formed UTF-8 text stay as they are.
TEST(OneLine, EscapesControlBytesOnce) {
  EXPECT_EQ(one_line("\x1b]0;title\x07OFF"), "\\x1b]0;title\\x07OFF");
  EXPECT_EQ(one_line(one_line("\x1b[31m")), "\\x1b[31m");
  EXPECT_EQ(one_line("a\tb \x7f"), "a\tb \\x7f");
  EXPECT_EQ(one_line("caf\xc3\xa9 \xe2\x80\x94 \xf0\x9f\x99\x82"),
            "caf\xc3\xa9 \xe2\x80\x94 \xf0\x9f\x99\x82");
  // C1 CSI in UTF-8, then bytes that are not UTF-8 (the string is split where a hex digit follows).
  EXPECT_EQ(one_line(std::string("\xc2\x9b") + "2J"), "\\xc2\\x9b2J");
  EXPECT_EQ(one_line(std::string("\x9b") + "2J \xff \xc3"), "\\x9b2J \\xff \\xc3");
  EXPECT_EQ(one_line("\xed\xa0\x80"), "\\xed\\xa0\\x80");  // a surrogate
  EXPECT_STREQ(InputError("\x1b.obj", 2, "bad \x1b").what(), "\\x1b.obj:2: bad \\x1b");
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
