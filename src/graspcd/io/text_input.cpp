#include "graspcd/io/text_input.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <new>
#include <sstream>
#include <streambuf>

#include "graspcd/core/tolerances.h"

namespace graspcd::io {

namespace {

bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

// A token as it appears in a message: quoted, control bytes escaped, long tokens shortened, so that
// the message stays one printable line whatever the input holds.
std::string quoted(const std::string& token) {
  constexpr std::size_t kMaxShown = 40;
  static const char* const kHex = "0123456789abcdef";
  std::string out = "\"";
  for (std::size_t i = 0; i < token.size() && i < kMaxShown; ++i) {
    const auto byte = static_cast<unsigned char>(token[i]);
    if (byte < 0x20 || byte >= 0x7f || byte == '"' || byte == '\\') {
      out += "\\x";
      out += kHex[byte >> 4];
      out += kHex[byte & 0xf];
    } else {
      out += static_cast<char>(byte);
    }
  }
  if (token.size() > kMaxShown) out += "...";
  out += '"';
  return out;
}

std::string range_text() {
  std::ostringstream out;
  out << tol::kMinCoordinate << " <= |x| <= " << tol::kMaxCoordinate;
  return out.str();
}

// Reads R row-major from 9 numbers.
Mat3 matrix_from_numbers(const double* v) {
  Mat3 R;
  R << v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8];
  return R;
}

void require_rotation(const Mat3& R, const std::string& name) {
  if (is_rotation(R, tol::kOrthonormalTol)) return;
  std::ostringstream out;
  out << name << ": R is not a rotation (R^T R must equal I to within " << tol::kOrthonormalTol
      << " entrywise, and det R > 0)";
  throw ValueError(out.str());
}

// A FIFO with a name in the file system (mkfifo), not the pipe of a shell's process substitution
// (/dev/fd/N, whose link names no file).
bool is_named_fifo(const std::string& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0 || !S_ISFIFO(info.st_mode)) return false;
  char* resolved = ::realpath(path.c_str(), nullptr);
  std::free(resolved);
  return resolved != nullptr;
}

// Opens a named FIFO without blocking on it (fopen waits until something opens it for writing, and
// so forever when nothing does), then waits kFifoWaitSeconds for its first byte or its end. Throws
// InputError when nothing comes; returns nullptr with errno set when it cannot be opened.
std::FILE* open_fifo(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK);
  if (fd < 0) return nullptr;
  pollfd wait{fd, POLLIN, 0};
  int ready = 0;
  do {
    ready = ::poll(&wait, 1, kFifoWaitSeconds * 1000);
  } while (ready < 0 && errno == EINTR);
  if (ready <= 0) {
    ::close(fd);
    throw InputError(path, 0,
                     "a FIFO that nothing wrote to in " + std::to_string(kFifoWaitSeconds) +
                         " s (give the input on standard input, -, instead)");
  }
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  std::FILE* file = ::fdopen(fd, "rb");
  if (file == nullptr) ::close(fd);
  return file;
}

}  // namespace

bool read_line(std::istream& in, std::string& line, const std::string& name,
               std::size_t line_number) {
  line.clear();
  std::streambuf* buffer = in.rdbuf();
  bool any = false;
  for (;;) {
    const auto c = buffer->sbumpc();
    if (std::char_traits<char>::eq_int_type(c, std::char_traits<char>::eof())) {
      in.setstate(std::ios::eofbit);
      if (!any) in.setstate(std::ios::failbit);
      return any;
    }
    any = true;
    if (c == '\n') return true;
    if (line.size() >= kMaxLineBytes) {
      throw InputError(name, line_number,
                       "line longer than " + std::to_string(kMaxLineBytes) + " bytes");
    }
    line.push_back(std::char_traits<char>::to_char_type(c));
  }
}

void require_regular_file(const std::string& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) return;
  if (S_ISREG(info.st_mode)) return;
  const char* kind = S_ISDIR(info.st_mode)    ? "a folder"
                     : S_ISFIFO(info.st_mode) ? "a FIFO"
                                              : "a device or special file";
  throw InputError(path, 0, std::string("not a regular file (") + kind + ")");
}

TextReader::TextReader(const std::string& path) {
  if (path == "-") {
    name_ = kStdinName;
    file_ = stdin;
    return;
  }
  name_ = path;
  if (is_named_fifo(path)) {
    file_ = open_fifo(path);
  } else {
    file_ = std::fopen(path.c_str(), "rb");
  }
  if (file_ == nullptr) {
    throw InputError(name_, 0, std::string("cannot open: ") + std::strerror(errno));
  }
  owns_file_ = true;
  // fopen succeeds on a directory; say so now rather than fail at the first read.
  struct stat info {};
  if (::fstat(::fileno(file_), &info) == 0 && S_ISDIR(info.st_mode)) {
    std::fclose(file_);
    owns_file_ = false;
    throw InputError(name_, 0, std::string("cannot open: ") + std::strerror(EISDIR));
  }
}

TextReader::~TextReader() {
  if (owns_file_) std::fclose(file_);
}

void TextReader::fail(const std::string& message) const { throw InputError(name_, line_, message); }

bool TextReader::next(std::size_t count, std::vector<double>& values) {
  values.clear();
  std::string token;
  for (;;) {
    // Read one physical line (up to '\n', which is dropped; a final line may lack it), at most
    // kMaxLineBytes long. Embedded NUL bytes are kept, which the number check then reports.
    buffer_.clear();
    bool any = false;
    int c = 0;
    try {
      while ((c = getc_unlocked(file_)) != EOF) {
        any = true;
        if (c == '\n') break;
        if (buffer_.size() >= kMaxLineBytes) {
          throw InputError(name_, line_ + 1,
                           "line longer than " + std::to_string(kMaxLineBytes) + " bytes");
        }
        buffer_.push_back(static_cast<char>(c));
      }
    } catch (const std::bad_alloc&) {
      buffer_ = std::string();
      throw InputError(name_, line_ + 1, "out of memory reading the line");
    }
    if (c == EOF && std::ferror(file_)) {
      throw InputError(name_, line_ + 1, std::string("read error: ") + std::strerror(errno));
    }
    if (!any) return false;
    ++line_;

    // Skip blank and comment lines ('\r' of CRLF counts as blank).
    std::size_t pos = 0;
    while (pos < buffer_.size() && is_blank(buffer_[pos])) ++pos;
    if (pos == buffer_.size() || buffer_[pos] == '#') continue;

    // Split into tokens and parse each.
    while (pos < buffer_.size()) {
      const std::size_t end = [&] {
        std::size_t e = pos;
        while (e < buffer_.size() && !is_blank(buffer_[e])) ++e;
        return e;
      }();
      token.assign(buffer_, pos, end - pos);
      try {
        values.push_back(parse_number(token));
      } catch (const ValueError& e) {
        fail(e.what());
      }
      pos = end;
      while (pos < buffer_.size() && is_blank(buffer_[pos])) ++pos;
    }
    if (values.size() != count) {
      std::ostringstream out;
      out << "expected " << count << " numbers, got " << values.size();
      fail(out.str());
    }
    return true;
  }
}

double parse_number(const std::string& token) {
  // strtod stops at an embedded NUL byte; the end check below then reports the token as malformed.
  const char* begin = token.c_str();
  char* end = nullptr;
  errno = 0;
  const double x = std::strtod(begin, &end);
  const bool range_error = errno == ERANGE;
  if (token.empty() || end != begin + token.size()) {
    throw ValueError("malformed number " + quoted(token));
  }
  if (range_error && std::fabs(x) > 1.0) {
    throw ValueError("number " + quoted(token) + " overflows a double");
  }
  if (!std::isfinite(x)) {
    throw ValueError("non-finite number " + quoted(token) + " (nan and inf are not accepted)");
  }
  // An underflowing literal (ERANGE with a tiny or zero result) was a nonzero value below the
  // range.
  if (range_error || (x != 0.0 && std::fabs(x) < tol::kMinCoordinate) ||
      std::fabs(x) > tol::kMaxCoordinate) {
    throw ValueError("number " + quoted(token) + " is outside the exact-arithmetic range (0 or " +
                     range_text() + ")");
  }
  return x;
}

Triangle triangle_from_numbers(const double* values) {
  Triangle t;
  for (int k = 0; k < 3; ++k) t.v[k] = Vec3(values[3 * k], values[3 * k + 1], values[3 * k + 2]);
  return t;
}

Obb obb_from_numbers(const double* values, const std::string& name) {
  Obb box;
  box.center = Vec3(values[0], values[1], values[2]);
  box.axes = matrix_from_numbers(values + 3);
  box.half = Vec3(values[12], values[13], values[14]);
  require_rotation(box.axes, name);
  for (int i = 0; i < 3; ++i) {
    if (box.half[i] < 0.0) {
      std::ostringstream out;
      out << name << ": half-extent " << i << " is negative (" << box.half[i]
          << "); half-extents must be >= 0";
      throw ValueError(out.str());
    }
  }
  return box;
}

Pose pose_from_numbers(const double* values, const std::string& name) {
  Pose pose;
  pose.R = matrix_from_numbers(values);
  pose.t = Vec3(values[9], values[10], values[11]);
  require_rotation(pose.R, name);
  return pose;
}

}  // namespace graspcd::io
