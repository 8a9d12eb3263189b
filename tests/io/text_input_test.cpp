#include "graspcd/io/text_input.h"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "helpers/temp_dir.h"

namespace graspcd::io {
namespace {

namespace fs = std::filesystem;

// A fresh temporary folder per test, removed afterwards.
class TextInputTest : public testing::TempDirTest {
 protected:
};

// The message of the ValueError that parse_number throws, or "" if it accepts the token.
std::string parse_error(const std::string& token) {
  try {
    parse_number(token);
  } catch (const ValueError& e) {
    return e.what();
  }
  return "";
}

TEST(ParseNumber, AcceptsEveryStrtodFormInRange) {
  EXPECT_EQ(parse_number("1"), 1.0);
  EXPECT_EQ(parse_number("-2.5"), -2.5);
  EXPECT_EQ(parse_number("+1e-3"), 1e-3);
  EXPECT_EQ(parse_number("0x1p-4"), 0.0625);
  EXPECT_EQ(parse_number("0.1"), 0.1);
  EXPECT_EQ(parse_number("-0"), 0.0);
  EXPECT_EQ(parse_number("0e-400"), 0.0);
  EXPECT_EQ(parse_number("1e50"), 1e50);
  EXPECT_EQ(parse_number("-1e-50"), -1e-50);
}

TEST(ParseNumber, RejectsMalformedTokens) {
  EXPECT_EQ(parse_error("1.0abc"), "malformed number \"1.0abc\"");
  EXPECT_EQ(parse_error("abc"), "malformed number \"abc\"");
  EXPECT_EQ(parse_error("0x"), "malformed number \"0x\"");
  EXPECT_EQ(parse_error("1,5"), "malformed number \"1,5\"");
  EXPECT_EQ(parse_error(std::string("1\0002", 3)), "malformed number \"1\\x002\"");
  EXPECT_EQ(parse_error(std::string(60, '7') + "x").substr(0, 17), "malformed number ");
  EXPECT_NE(parse_error(std::string(60, '7') + "x").find("...\""), std::string::npos);
}

TEST(ParseNumber, RejectsNanAndInfInEverySpelling) {
  for (const char* token : {"nan", "NaN", "-nan", "+NAN", "nan(123)", "inf", "-INF", "Infinity",
                            "-infinity", "0x1p99999"}) {
    const std::string message = parse_error(token);
    EXPECT_FALSE(message.empty()) << token;
    EXPECT_TRUE(message.find("non-finite") != std::string::npos ||
                message.find("overflows") != std::string::npos)
        << token << ": " << message;
  }
  EXPECT_EQ(parse_error("nan"), "non-finite number \"nan\" (nan and inf are not accepted)");
  EXPECT_EQ(parse_error("-Infinity"),
            "non-finite number \"-Infinity\" (nan and inf are not accepted)");
}

TEST(ParseNumber, RejectsOverflowAndTheOutsideOfTheExactRange) {
  EXPECT_EQ(parse_error("1e400"), "number \"1e400\" overflows a double");
  EXPECT_EQ(parse_error("-1e400"), "number \"-1e400\" overflows a double");
  const std::string range = " is outside the exact-arithmetic range (0 or 1e-50 <= |x| <= 1e+50)";
  EXPECT_EQ(parse_error("2e50"), "number \"2e50\"" + range);
  EXPECT_EQ(parse_error("-1e51"), "number \"-1e51\"" + range);
  EXPECT_EQ(parse_error("1e-51"), "number \"1e-51\"" + range);
  EXPECT_EQ(parse_error("1e-400"), "number \"1e-400\"" + range);  // underflows to 0 in strtod
  EXPECT_EQ(parse_error("0x1p-1074"), "number \"0x1p-1074\"" + range);
}

TEST_F(TextInputTest, ReadsCasesSkippingCommentsAndBlankLinesWithCrlf) {
  const std::string path = write("cases.txt",
                                 "# header comment\r\n"
                                 "\r\n"
                                 "1 2 3\r\n"
                                 "   \t# indented comment\n"
                                 "\t-4  0x1p-1\t6e0   \n"
                                 "\n"
                                 "7 8 9");  // last line without newline
  TextReader reader(path);
  EXPECT_EQ(reader.name(), path);
  std::vector<double> v;
  ASSERT_TRUE(reader.next(3, v));
  EXPECT_EQ(v, (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(reader.line(), 3u);
  ASSERT_TRUE(reader.next(3, v));
  EXPECT_EQ(v, (std::vector<double>{-4, 0.5, 6}));
  EXPECT_EQ(reader.line(), 5u);
  ASSERT_TRUE(reader.next(3, v));
  EXPECT_EQ(v, (std::vector<double>{7, 8, 9}));
  EXPECT_EQ(reader.line(), 7u);
  EXPECT_FALSE(reader.next(3, v));
  EXPECT_FALSE(reader.next(3, v));
}

TEST_F(TextInputTest, EmptyAndCommentOnlyInputsHaveNoCases) {
  std::vector<double> v;
  TextReader empty(write("empty.txt", ""));
  EXPECT_FALSE(empty.next(18, v));
  TextReader comments(write("comments.txt", "# nothing\n\n  \r\n# more\n"));
  EXPECT_FALSE(comments.next(18, v));
}

TEST_F(TextInputTest, WrongCountIsLocatedAtItsPhysicalLine) {
  const std::string path = write("count.txt", "1 2 3\n# c\n\n4 5\n");
  TextReader reader(path);
  std::vector<double> v;
  ASSERT_TRUE(reader.next(3, v));
  try {
    reader.next(3, v);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), (path + ":4: expected 3 numbers, got 2").c_str());
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.line(), 4u);
    EXPECT_EQ(e.message(), "expected 3 numbers, got 2");
  }
}

TEST_F(TextInputTest, TooManyNumbersIsAnError) {
  const std::string path = write("many.txt", "1 2 3 4\n");
  TextReader reader(path);
  std::vector<double> v;
  try {
    reader.next(3, v);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), (path + ":1: expected 3 numbers, got 4").c_str());
  }
}

TEST_F(TextInputTest, BadNumbersAreLocated) {
  const std::string path = write("bad.txt", "1 2 3\r\n1 nan 3\r\n");
  TextReader reader(path);
  std::vector<double> v;
  ASSERT_TRUE(reader.next(3, v));
  try {
    reader.next(3, v);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 (path + ":2: non-finite number \"nan\" (nan and inf are not accepted)").c_str());
  }
}

TEST_F(TextInputTest, MissingFileAndDirectoryCannotBeOpened) {
  const std::string missing = (dir_ / "missing.txt").string();
  try {
    TextReader reader(missing);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), (missing + ": cannot open: No such file or directory").c_str());
    EXPECT_EQ(e.line(), 0u);
  }
  try {
    TextReader reader(dir_.string());
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), (dir_.string() + ": cannot open: Is a directory").c_str());
  }
}

TEST(TextReader, DashIsStdin) {
  TextReader reader("-");
  EXPECT_EQ(reader.name(), "<stdin>");
  EXPECT_EQ(reader.line(), 0u);
}

TEST(TextReader, FailThrowsAtTheCurrentLine) {
  TextReader reader("-");
  try {
    reader.fail("box A: bad");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "<stdin>: box A: bad");
  }
}

TEST(Builders, TriangleFromNumbers) {
  const std::vector<double> v = {1, 2, 3, 4, 5, 6, 7, 8, 9};
  const Triangle t = triangle_from_numbers(v.data());
  EXPECT_EQ(t.v[0], Vec3(1, 2, 3));
  EXPECT_EQ(t.v[1], Vec3(4, 5, 6));
  EXPECT_EQ(t.v[2], Vec3(7, 8, 9));
}

TEST(Builders, ObbFromNumbersReadsRRowMajor) {
  // R = rotation by 90 degrees about z: columns are the box axes (0,1,0), (-1,0,0), (0,0,1).
  const std::vector<double> v = {1, 2, 3, 0, -1, 0, 1, 0, 0, 0, 0, 1, 0.5, 0, 2};
  const Obb box = obb_from_numbers(v.data(), "box A");
  EXPECT_EQ(box.center, Vec3(1, 2, 3));
  EXPECT_EQ(box.axes.col(0), Vec3(0, 1, 0));
  EXPECT_EQ(box.axes.col(1), Vec3(-1, 0, 0));
  EXPECT_EQ(box.half, Vec3(0.5, 0, 2));  // a zero extent is a flat box, allowed
}

std::string obb_error(std::vector<double> v) {
  try {
    obb_from_numbers(v.data(), "box B");
  } catch (const ValueError& e) {
    return e.what();
  }
  return "";
}

TEST(Builders, ObbRejectsNonRotationsAndNegativeExtents) {
  const std::string not_rotation =
      "box B: R is not a rotation (R^T R must equal I to within 1e-09 entrywise, and det R > 0)";
  EXPECT_EQ(obb_error({0, 0, 0, 2, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1}), not_rotation);
  EXPECT_EQ(obb_error({0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, -1, 1, 1, 1}), not_rotation);  // reflection
  EXPECT_EQ(obb_error({0, 0, 0, 1, 1e-6, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1}), not_rotation);
  EXPECT_EQ(obb_error({0, 0, 0, 1, 1e-12, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1}), "");  // within 1e-9
  EXPECT_EQ(obb_error({0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, -0.5, 1}),
            "box B: half-extent 1 is negative (-0.5); half-extents must be >= 0");
}

TEST(Builders, PoseFromNumbers) {
  const std::vector<double> v = {0, 0, 1, 0, 1, 0, -1, 0, 0, 4, 5, 6};
  const Pose pose = pose_from_numbers(v.data(), "pose");
  EXPECT_EQ(pose.R(0, 2), 1.0);
  EXPECT_EQ(pose.R(2, 0), -1.0);
  EXPECT_EQ(pose.t, Vec3(4, 5, 6));
  const std::vector<double> scaled = {2, 0, 0, 0, 2, 0, 0, 0, 2, 0, 0, 0};
  try {
    pose_from_numbers(scaled.data(), "pose");
    FAIL() << "expected a ValueError";
  } catch (const ValueError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("pose: R is not a rotation", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace graspcd::io
