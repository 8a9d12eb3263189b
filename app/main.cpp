// graspcd: the command line of the project (docs/design.md, "The command line"). Each subcommand
// lives in its own file; this file parses, dispatches, and turns every error into one line on
// stderr and exit code 2.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <new>
#include <streambuf>
#include <string>
#include <vector>

#include "command.h"
#include "graspcd/io/output_files.h"
#include "graspcd/io/text_input.h"
#include "graspcd/io/warnings.h"
#include "graspcd/mujoco/mujoco_messages.h"
#include "graspcd/version.h"
#include "graspcd/version/provenance.h"

namespace {

constexpr int kExitError = 2;

std::string trimmed(std::string s) {
  const auto first = s.find_first_not_of(' ');
  if (first == std::string::npos) return "";
  const auto last = s.find_last_not_of(' ');
  return s.substr(first, last - first + 1);
}

std::string version_text() {
  return std::string("graspcd ") + GRASPCD_VERSION + "\nMuJoCo " + GRASPCD_MUJOCO_VERSION +
         "\nEigen " + GRASPCD_EIGEN_VERSION + "\nCGAL " + GRASPCD_CGAL_VERSION +
         "\nbuild type: " + GRASPCD_BUILD_TYPE + "\ncompiler: " + GRASPCD_CXX_COMPILER +
         "\nflags: " + trimmed(GRASPCD_BUILD_FLAGS) + "\ncommit: " + graspcd::provenance().commit;
}

// The run's warnings (graspcd/io/warnings.h), one line each on stderr after the answers. The
// JSON outputs carry the same list in their envelope.
void print_warnings() {
  std::cout.flush();
  for (const graspcd::Warning& w : graspcd::warnings().list()) {
    std::cerr << "warning: " << graspcd::warning_line(w) << '\n';
  }
}

// Prints one line on stderr, after whatever answers are already on stdout.
int report_error(const std::string& message) {
  std::cout.flush();
  std::cerr << graspcd::io::one_line(message) << '\n';
  std::cerr.flush();
  return kExitError;
}

// Standard output for std::cout: a buffer written to file descriptor 1 that keeps the error of the
// first write that failed (std::filebuf forgets it), so the error line can say why.
class StdoutBuffer : public std::streambuf {
 public:
  StdoutBuffer() { setp(buffer_, buffer_ + sizeof(buffer_)); }
  int error() const { return error_; }

 protected:
  int_type overflow(int_type c) override {
    if (drain() != 0) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return drain(); }

 private:
  // Writes the buffered bytes; on failure drops them and keeps errno (0 = no failure yet).
  int drain() {
    for (const char* p = pbase(); p < pptr();) {
      const ssize_t n = ::write(STDOUT_FILENO, p, static_cast<std::size_t>(pptr() - p));
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        if (error_ == 0) error_ = n < 0 ? errno : EIO;
        break;
      }
      p += n;
    }
    setp(buffer_, buffer_ + sizeof(buffer_));
    return error_ == 0 ? 0 : -1;
  }

  char buffer_[1 << 16];
  int error_ = 0;
};

// The answers were written only if standard output took them: a full disk (/dev/full), a closed
// stdout or an I/O error is an error of the run, never a success with the answers lost. Called
// once, at the end of every command. A closed pipe never gets here: SIGPIPE keeps its default
// action and ends the process quietly (`graspcd ... | head`).
int check_stdout(const StdoutBuffer& out, int exit_code) {
  std::cout.flush();
  int error = out.error();
  // C stdio (MuJoCo prints through it) has its own buffer on the same descriptor.
  if (error == 0 && (std::fflush(stdout) != 0 || std::ferror(stdout))) {
    error = errno != 0 ? errno : EIO;
  }
  if (error == 0) return exit_code;
  std::cerr << "<stdout>: cannot write: " << std::strerror(error) << '\n';
  std::cerr.flush();
  return kExitError;
}

// A parse error: --help and --version print (exit 0); every usage error is one line (exit 2).
int parse_error(CLI::App& app, const CLI::ParseError& e, int argc, char** argv,
                const StdoutBuffer& out) {
  if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) {
    return check_stdout(out, app.exit(e));
  }
  // A first word that is no option and no subcommand: a misspelled subcommand.
  if (app.get_subcommands().empty() && argc > 1 && argv[1][0] != '-') {
    std::string names;
    for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
      names += (names.empty() ? "" : ", ") + sub->get_name();
    }
    return report_error(std::string("graspcd: unknown subcommand '") + argv[1] +
                        "' (expected one of: " + names + ")");
  }
  return report_error(std::string("graspcd: ") + e.what() + " (run with --help for usage)");
}

// Runs the subcommand given, then prints the warnings; every error is one line, exit code 2.
int run(const std::vector<graspcd::cli::Command>& commands, const StdoutBuffer& out) {
  try {
    int exit_code = 0;
    for (const graspcd::cli::Command& command : commands) {
      if (!command.app->parsed()) continue;
      command.run();
      if (command.exit_code) exit_code = *command.exit_code;
    }
    print_warnings();
    return check_stdout(out, exit_code);
  } catch (const graspcd::io::InputError& e) {
    return report_error(e.what());
  } catch (const graspcd::cli::UsageError& e) {
    return report_error(std::string("graspcd: ") + e.what());
  } catch (const std::bad_alloc&) {
    // The text inputs name their file (text_input.h); elsewhere no file is to blame.
    return report_error("graspcd: error: out of memory");
  } catch (const std::exception& e) {
    return report_error(std::string("graspcd: error: ") + e.what());
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::ios::sync_with_stdio(false);
  StdoutBuffer stdout_buffer;
  // std::cout writes through stdout_buffer until main returns (then through its own buffer again).
  struct RestoreCout {
    std::streambuf* previous;
    ~RestoreCout() { std::cout.rdbuf(previous); }
  } restore_cout{std::cout.rdbuf(&stdout_buffer)};
  // MuJoCo's warnings go to the warning sink, never to stdout or MUJOCO_LOG.TXT.
  graspcd::mujoco::route_mujoco_warnings();
  // MuJoCo's errors become exceptions: one line naming the scene, exit 2, destructors run.
  graspcd::mujoco::route_mujoco_errors();
  // INT, TERM and HUP remove the run's temporary files and partial outputs, exit 128 + signal.
  graspcd::io::install_cleanup_handlers();
  CLI::App app{"graspcd: exact OBB-tree collision detection for robotic grasping.", "graspcd"};
  app.require_subcommand(1);
  app.set_version_flag("--version", version_text(),
                       "Print the version and the versions built with");
  app.footer("Run 'graspcd SUBCOMMAND --help' for the input format of each subcommand.");
  const std::vector<graspcd::cli::Command> commands = {
      graspcd::cli::add_tritri_command(app),    graspcd::cli::add_boxbox_command(app),
      graspcd::cli::add_meshpair_command(app),  graspcd::cli::add_grasp_command(app),
      graspcd::cli::add_study_command(app),     graspcd::cli::add_stress_command(app),
      graspcd::cli::add_validate_command(app),  graspcd::cli::add_trajectory_command(app),
      graspcd::cli::add_decompose_command(app), graspcd::cli::add_judge_command(app),
  };
  // --version prints and exits inside CLI11's parse, before the words after it are seen: a word
  // after it is refused here rather than ignored.
  if (argc > 2 && std::string(argv[1]) == "--version") {
    return report_error(std::string("graspcd: --version: unexpected argument '") + argv[2] +
                        "' (run with --help for usage)");
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return parse_error(app, e, argc, argv, stdout_buffer);
  }
  return run(commands, stdout_buffer);
}
