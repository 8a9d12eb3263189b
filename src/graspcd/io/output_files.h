// The files graspcd writes: checked before the work, written under names no other run uses and
// renamed into place at the end, and removed when the run fails or is interrupted
// (docs/bad-input.md, "Output files").
//
// Cleanup on INT, TERM and HUP: install_cleanup_handlers() sets a handler for the three signals
// that kills the run's child processes (ChildProcess), removes every path registered with a
// CleanupGuard (a file, or a folder with everything in it) and ends the process with exit code
// 128 + the signal's number (async-signal-safe: it allocates nothing). Errors and normal returns
// remove the same paths through CleanupGuard's destructor. A Deadline ends the run the same way,
// with exit code 2, when work that cannot be stopped from inside runs past its time.
//
// What an output may replace: never a file the run reads (same_file), and of what exists only
// what graspcd wrote, each writer recognising its own (decompose's manifest, a scene's marker
// line, a trajectory's keys); a read-only folder is refused, also for root (writable_folder).
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <string>
#include <utility>

namespace graspcd::io {

// Installs the handler for SIGINT, SIGTERM and SIGHUP (once; later calls do nothing).
void install_cleanup_handlers();

// A path removed (with everything under it) when the guard is destroyed, unless released, and by
// the signal handler while the guard lives. At most kMaxCleanupPaths guards live at once; the
// path must be shorter than 4096 bytes (std::length_error otherwise).
inline constexpr int kMaxCleanupPaths = 32;
class CleanupGuard {
 public:
  CleanupGuard() = default;
  explicit CleanupGuard(const std::filesystem::path& path);
  ~CleanupGuard();
  CleanupGuard(CleanupGuard&& other) noexcept;
  CleanupGuard& operator=(CleanupGuard&& other) noexcept;
  CleanupGuard(const CleanupGuard&) = delete;
  CleanupGuard& operator=(const CleanupGuard&) = delete;

  const std::filesystem::path& path() const { return path_; }
  // Keeps the path: no longer removed, neither by the destructor nor by a signal.
  void release();

 private:
  std::filesystem::path path_;
  int slot_ = -1;
};

// A child process tied to the run: forked at construction with INT, TERM and HUP blocked and
// registered before they are unblocked, so that the cleanup handler kills it (SIGKILL, and reaps
// it) before it removes the run's paths; the kernel kills it too when graspcd ends any other way
// (PR_SET_PDEATHSIG, e.g. SIGKILL). In the child, the three signals have their default action
// again and only async-signal-safe calls may follow (then _exit or exec). The destructor, in the
// parent, kills and reaps a child that was not reaped. At most kMaxChildren live at once.
inline constexpr int kMaxChildren = 8;
class ChildProcess {
 public:
  ChildProcess();
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  // fork()'s answer: 0 in the child, the child's id in the parent, -1 when fork failed (errno).
  pid_t pid() const { return pid_; }
  // waitpid without EINTR (blocking, or WNOHANG): true once the child was reaped, its status in
  // `status`; it then leaves the table (its id may be reused).
  bool wait(int* status, bool block);
  // SIGKILL to a child not yet reaped.
  void kill();

 private:
  pid_t pid_ = -1;
  int slot_ = -1;
  bool reaped_ = false;
};

// A time limit on work that cannot be stopped from inside (MuJoCo's mesh compiler in
// mj_loadXML). When `seconds` pass before the Deadline is cancelled or destroyed, `message` goes
// to stderr as one line, the run's children are killed, every guarded path is removed and the
// process ends with exit code 2, as on an error, without unwinding the stack (SIGALRM, handled as
// INT, TERM and HUP are; one Deadline at a time; the message is cut at 4095 bytes).
class Deadline {
 public:
  Deadline(double seconds, const std::string& message);
  ~Deadline();
  Deadline(const Deadline&) = delete;
  Deadline& operator=(const Deadline&) = delete;
  void cancel();

 private:
  bool armed_ = false;
};

// Whether `a` and `b` name one existing file (the same device and inode: a link or another
// path of it counts).
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

// Throws InputError(dir, "cannot write into the folder: ...") unless the existing folder `dir`
// can be written into: its mode grants a write permission (root, to whom any mode is writable,
// is refused a folder whose mode grants none: the user made it read-only) and a probe file can
// be created in it.
void writable_folder(const std::string& dir);

// The folder `dir` can be written into: created (with its parents) when it does not exist.
// Throws InputError(dir, ...) when it cannot be: a parent is a regular file, it is not a folder,
// or it is read-only (writable_folder). Returns whether it was created.
bool prepare_output_folder(const std::string& dir);

// A folder this run created, removed at the end when it is still empty (a run that failed leaves
// no empty folder behind).
class RemoveIfEmpty {
 public:
  explicit RemoveIfEmpty(std::filesystem::path path) : path_(std::move(path)) {}
  ~RemoveIfEmpty();
  RemoveIfEmpty(const RemoveIfEmpty&) = delete;
  RemoveIfEmpty& operator=(const RemoveIfEmpty&) = delete;

 private:
  std::filesystem::path path_;
};

// A new folder under `parent` named PREFIX-XXXXXX (mkdtemp), guarded: removed on errors and
// signals unless released. Throws InputError naming `named` (the user's output) when it cannot be
// created.
CleanupGuard make_private_folder(const std::filesystem::path& parent, const std::string& prefix,
                                 const std::string& named);

// Moves every entry of the folder `work` into the folder `target` (one file system), an entry of
// the same name in `target` moved into `work` first (removed with it), with INT, TERM and HUP held
// back meanwhile: a run interrupted before the call leaves `target` as it was, and none leaves it
// half replaced. Throws InputError naming `named` (the target as the user knows it).
void move_entries(const std::filesystem::path& work, const std::filesystem::path& target,
                  const std::string& named);

// The system's temporary folder ($TMPDIR, else /tmp). Throws InputError naming it when it does
// not exist or is not a folder.
std::filesystem::path temporary_folder();

// An output file written whole or not at all: the bytes go to a hidden file beside `target`
// (.NAME.graspcd-XXXXXX, created at construction: an unwritable folder is found before the
// work), renamed over `target` by commit(); its folder is created when missing and refused when
// read-only (prepare_output_folder). A `target` that exists and is not a regular file
// (/dev/stdout, /dev/full) is written directly. Throws InputError naming `target`.
class AtomicFile {
 public:
  explicit AtomicFile(std::string target);
  // Where to write now (the hidden file, or `target` itself for a special file).
  const std::string& write_path() const { return write_path_; }
  // Renames the written file into place; throws InputError naming the target when it cannot.
  void commit();

 private:
  std::string target_;
  std::string write_path_;
  CleanupGuard guard_;
};

}  // namespace graspcd::io
