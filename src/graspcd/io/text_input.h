// The text grammar of the command line (docs/design.md, "The command line"): one case per line, a
// fixed count of whitespace-separated numbers; blank lines and '#' comment lines skipped; CRLF
// accepted. Every number is read by strtod (decimal or hex float) and must be finite and inside the
// range in which the exact predicates stay exact (tolerances.h): 0, or kMinCoordinate <= |x| <=
// kMaxCoordinate. Bad input is reported as an InputError located at its file and physical line.
#pragma once

#include <cstddef>
#include <cstdio>
#include <istream>
#include <stdexcept>
#include <string>
#include <vector>

#include "graspcd/core/geometry.h"
#include "graspcd/core/obb.h"
#include "graspcd/io/input_error.h"

namespace graspcd::io {

// A value that is well formed as numbers but not as the object they describe (a non-orthonormal R,
// a negative half-extent). Carries no location: the caller knows the line and rethrows it as an
// InputError (see TextReader::fail).
class ValueError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// The longest line a line-oriented text input (the cases of tritri, boxbox and meshpair --poses, an
// OBJ file) may hold, without its '\n': a longer line is "FILE:LINE: line longer than N bytes",
// read no further, so that an endless line (/dev/zero) never exhausts memory.
inline constexpr std::size_t kMaxLineBytes = std::size_t{16} << 20;

// Reads one line of `in` into `line`, without its '\n' (a last line may lack it). Returns false at
// the end of the input. Throws InputError "NAME:LINE_NUMBER: line longer than N bytes" when the
// line exceeds kMaxLineBytes.
bool read_line(std::istream& in, std::string& line, const std::string& name,
               std::size_t line_number);

// Throws InputError "FILE: not a regular file" unless `path` names a regular file (or a symlink to
// one): a folder, a FIFO or a device is refused at once, before anything opens it (opening a FIFO
// blocks until something writes to it). A path that does not exist passes: opening it reports that.
void require_regular_file(const std::string& path);

// The name of standard input in messages.
inline constexpr const char* kStdinName = "<stdin>";

// How long TextReader waits for the first byte of a named FIFO (mkfifo) before it refuses it.
inline constexpr int kFifoWaitSeconds = 10;

// Reads cases from a file, or from standard input when the path is "-".
class TextReader {
 public:
  // Opens `path` ("-" = stdin). Throws InputError "FILE: cannot open: <reason>" on failure, and
  // for a named FIFO that nothing writes to within kFifoWaitSeconds (a pipe of the shell, `-` or
  // /dev/fd/N, is read as it comes).
  explicit TextReader(const std::string& path);
  ~TextReader();
  TextReader(const TextReader&) = delete;
  TextReader& operator=(const TextReader&) = delete;

  // Reads the next case line into `values`: exactly `count` numbers. Returns false at the end of
  // the input. Throws InputError on a malformed, non-finite or out-of-range number, on a wrong
  // count, on a line longer than kMaxLineBytes, on a read error and when memory runs out.
  bool next(std::size_t count, std::vector<double>& values);

  // The file name used in messages ("<stdin>" for "-").
  const std::string& name() const { return name_; }
  // The physical line (1-based) of the case last returned by next(); 0 before the first.
  std::size_t line() const { return line_; }

  // Throws InputError with `message` at the current line.
  [[noreturn]] void fail(const std::string& message) const;

 private:
  std::string name_;
  std::FILE* file_ = nullptr;
  bool owns_file_ = false;
  std::size_t line_ = 0;
  std::string buffer_;
};

// Parses one number token as the grammar demands. Throws ValueError (no location) with a message
// naming the token on: a malformed number or trailing garbage, nan or inf in any spelling,
// overflow, and a nonzero magnitude outside [tol::kMinCoordinate, tol::kMaxCoordinate].
double parse_number(const std::string& token);

// Builders from a case's numbers. Each reads the stated count starting at `values` and throws
// ValueError (message prefixed with `name`) when the object is invalid.
//   18 numbers: p0 p1 p2 (x y z each).
Triangle triangle_from_numbers(const double* values);
//   15 numbers: centre (3), R row-major (9), half-extents (3). R must be a rotation to within
//   tol::kOrthonormalTol (graspcd::is_rotation); half-extents must be >= 0.
Obb obb_from_numbers(const double* values, const std::string& name);
//   12 numbers: R row-major (9), t (3). R must be a rotation to within tol::kOrthonormalTol.
Pose pose_from_numbers(const double* values, const std::string& name);

}  // namespace graspcd::io
