#include "command.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <sstream>
#include <string>

#include "graspcd/io/text_input.h"

namespace graspcd::cli {

namespace {

// True when standard input is a pipe or a terminal rather than a regular file.
bool stdin_is_stream() {
  struct stat info {};
  return ::fstat(STDIN_FILENO, &info) != 0 || !S_ISREG(info.st_mode);
}

// A validator of a finite number for which `ok` holds; `bound` says what ok means ("> 0").
CLI::Validator finite_number(std::function<bool(double)> ok, const std::string& bound,
                             const std::string& name) {
  return CLI::Validator(
      [ok, bound](std::string& input) -> std::string {
        double x = 0;
        if (!CLI::detail::lexical_cast(input, x) || !std::isfinite(x)) {
          return "Value " + input + " is not a finite number";
        }
        return ok(x) ? "" : "Value " + input + " is not " + bound;
      },
      name);
}

}  // namespace

CLI::Validator positive_number() {
  return finite_number([](double x) { return x > 0; }, "> 0", "POSITIVE");
}

CLI::Validator non_negative_number() {
  return finite_number([](double x) { return x >= 0; }, ">= 0", "NONNEGATIVE");
}

CLI::Validator number_in_range(double lo, double hi) {
  std::ostringstream range;
  range << "in [" << lo << ", " << hi << "]";
  return finite_number([lo, hi](double x) { return x >= lo && x <= hi; }, range.str(),
                       "FLOAT " + range.str());
}

namespace {

// The decimal integer validator of [lo, hi]: `below` and `above` word the range in the errors of
// a value below lo and above hi ("in 4 .. 100", "> 0"), `name` in the help.
CLI::Validator integer_validator(long long lo, unsigned long long hi, const std::string& below,
                                 const std::string& above, const std::string& name) {
  return CLI::Validator(
      [lo, hi, below, above](std::string& input) -> std::string {
        std::size_t i = 0;
        const bool negative = !input.empty() && input[0] == '-';
        if (!input.empty() && (input[0] == '-' || input[0] == '+')) ++i;
        if (i == input.size() || input.find_first_not_of("0123456789", i) != std::string::npos) {
          return "Value " + input + " is not a decimal integer";
        }
        const std::string digits =
            input.substr(std::min(input.find_first_not_of('0', i), input.size() - 1));
        // 19 digits hold every bound (2^63 has 19); more are out of range.
        const bool fits = digits.size() <= 19;
        const unsigned long long magnitude = fits ? std::stoull(digits) : 0;
        const unsigned long long least =
            lo < 0 ? 0 : static_cast<unsigned long long>(lo);  // for a non-negative value
        const unsigned long long most_negative =
            lo < 0 ? static_cast<unsigned long long>(-(lo + 1)) + 1 : 0;
        const bool below_zero = negative && (!fits || magnitude > 0);
        const bool low =
            below_zero ? !fits || magnitude > most_negative : fits && magnitude < least;
        const bool high = !below_zero && (!fits || magnitude > hi);
        if (low || high) return "Value " + input + " is not " + (low ? below : above);
        input = (negative && magnitude > 0 ? "-" : "") + digits;
        return "";
      },
      name);
}

}  // namespace

CLI::Validator integer_in_range(long long lo, unsigned long long hi) {
  const std::string range = std::to_string(lo) + " .. " + std::to_string(hi);
  return integer_validator(lo, hi, "in " + range, "in " + range, "INT in " + range);
}

CLI::Validator positive_integer(unsigned long long hi) {
  return integer_validator(1, hi, "> 0", "<= " + std::to_string(hi), "POSITIVE");
}

CLI::Validator non_negative_integer(unsigned long long hi) {
  return integer_validator(0, hi, ">= 0", "<= " + std::to_string(hi), "NONNEGATIVE");
}

CLI::Validator decimal_integer(long long lo, unsigned long long hi) {
  const std::string range = "in " + std::to_string(lo) + " .. " + std::to_string(hi);
  return integer_validator(lo, hi, range, range, "");
}

void for_each_case(const std::string& path, std::size_t count,
                   const std::function<void(const std::vector<double>&)>& answer) {
  io::TextReader reader(path);
  const bool flush_each = path == "-" && stdin_is_stream();
  std::vector<double> values;
  while (reader.next(count, values)) {
    try {
      answer(values);
    } catch (const io::ValueError& e) {
      reader.fail(e.what());
    }
    if (flush_each) std::cout.flush();
  }
  std::cout.flush();
}

std::string number_grammar_help() {
  return "Numbers: whitespace-separated, in any form strtod reads (1, -2.5, 1e-3, 0x1p-4); nan and "
         "inf are errors, and a nonzero value must satisfy 1e-50 <= |x| <= 1e50 (the range in "
         "which the exact predicates stay exact). Blank lines and lines starting with '#' are "
         "skipped; CRLF line ends are accepted.\n"
         "Errors: one line 'FILE:LINE: message' on stderr (FILE is <stdin> for -), exit code 2; "
         "answers printed for earlier lines stay printed.\n";
}

std::string wrap_help(const std::string& text, std::size_t width) {
  std::istringstream paragraphs(text);
  std::string out;
  for (std::string paragraph; std::getline(paragraphs, paragraph);) {
    if (paragraph.rfind("  ", 0) == 0) {
      out += paragraph + '\n';
      continue;
    }
    std::istringstream words(paragraph);
    std::size_t column = 0;
    for (std::string word; words >> word;) {
      if (column > 0 && column + 1 + word.size() > width) {
        out += '\n';
        column = 0;
      }
      if (column > 0) {
        out += ' ';
        ++column;
      }
      out += word;
      column += word.size();
    }
    out += '\n';
  }
  return out;
}

}  // namespace graspcd::cli
