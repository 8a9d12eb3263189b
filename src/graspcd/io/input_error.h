// Bad input, located at its file and line: the one error type of every layer that reads a file
// (meshes, scenes, pair configs, the command line's text input), and the one-line rule its
// messages follow. The command line prints what() on stderr and exits with code 2.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace graspcd::io {

// `text` on one line: each line trimmed of blanks, blank lines dropped, the rest joined by "; "
// (MuJoCo's multi-line errors, a library's message, a file name holding a line break), and every
// byte a terminal could take for a control (an escape sequence quoted from a file) written as
// \xNN: the C0 controls but the tab, DEL, the C1 controls and bytes that are not well-formed
// UTF-8. Every error and warning line is made by it; a second pass changes nothing.
std::string one_line(const std::string& text);

// what() is "FILE:LINE: MESSAGE", or "FILE: MESSAGE" when line() is 0 (the file as a whole),
// made one line (one_line), the file's name with it.
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::size_t line, std::string message);

  const std::string& file() const { return file_; }
  std::size_t line() const { return line_; }  // 1-based physical line; 0 = the file as a whole
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  std::size_t line_;
  std::string message_;
};

}  // namespace graspcd::io
