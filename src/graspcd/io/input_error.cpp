#include "graspcd/io/input_error.h"

#include <utility>

namespace graspcd::io {

namespace {

std::string located(const std::string& file, std::size_t line, const std::string& message) {
  return file + (line > 0 ? ":" + std::to_string(line) : "") + ": " + message;
}

// `text` with every byte a terminal could take for a control written as \xNN (lower-case hex):
// the C0 controls but the tab, DEL, the C1 controls (U+0080 to U+009F, two bytes in UTF-8) and
// every byte that is not part of a well-formed UTF-8 sequence (RFC 3629, table 3-7 of the Unicode
// standard), which a terminal in an 8-bit mode reads as a C1 control. An escape holds no control,
// so escaping twice changes nothing.
std::string escape_controls(const std::string& text) {
  static const char kHex[] = "0123456789abcdef";
  std::string out;
  out.reserve(text.size());
  const auto escape = [&](unsigned char c) {
    out += "\\x";
    out += kHex[c >> 4];
    out += kHex[c & 15];
  };
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  for (std::size_t i = 0; i < text.size();) {
    const unsigned char c = byte(i);
    if (c < 0x80) {
      if ((c < 0x20 && c != '\t') || c == 0x7f) {
        escape(c);
      } else {
        out += static_cast<char>(c);
      }
      ++i;
      continue;
    }
    // The length of a well-formed sequence starting at i (0: none), and its second byte's range.
    std::size_t length = 0;
    unsigned char low = 0x80;
    unsigned char high = 0xbf;
    if (c >= 0xc2 && c <= 0xdf) {
      length = 2;
    } else if (c >= 0xe0 && c <= 0xef) {
      length = 3;
      if (c == 0xe0) low = 0xa0;
      if (c == 0xed) high = 0x9f;
    } else if (c >= 0xf0 && c <= 0xf4) {
      length = 4;
      if (c == 0xf0) low = 0x90;
      if (c == 0xf4) high = 0x8f;
    }
    bool well_formed =
        length > 0 && i + length <= text.size() && byte(i + 1) >= low && byte(i + 1) <= high;
    for (std::size_t k = 2; well_formed && k < length; ++k) {
      well_formed = byte(i + k) >= 0x80 && byte(i + k) <= 0xbf;
    }
    const bool c1 = well_formed && c == 0xc2 && byte(i + 1) <= 0x9f;
    if (!well_formed || c1) {
      for (std::size_t k = 0; k < (c1 ? 2 : 1); ++k) escape(byte(i + k));
      i += c1 ? 2 : 1;
      continue;
    }
    out.append(text, i, length);
    i += length;
  }
  return out;
}

}  // namespace

std::string one_line(const std::string& text) {
  std::string out;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    std::size_t end = text.find_first_of("\r\n", pos);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(pos, end - pos);
    const std::size_t first = line.find_first_not_of(" \t");
    if (first != std::string::npos) {
      if (!out.empty()) out += "; ";
      out += line.substr(first, line.find_last_not_of(" \t") - first + 1);
    }
    pos = end + 1;
  }
  return escape_controls(out);
}

InputError::InputError(std::string file, std::size_t line, std::string message)
    : std::runtime_error(one_line(located(file, line, message))),
      file_(std::move(file)),
      line_(line),
      message_(one_line(message)) {}

}  // namespace graspcd::io
