// The files graspcd writes: checked before the work, written under names no other run uses and
// renamed into place at the end, and removed when the run fails or is interrupted
// (docs/bad-input.md, "Output files").
//
// Cleanup on INT, TERM and HUP: install_cleanup_handlers() sets a handler for the three signals
// that removes every path registered with a CleanupGuard (a file, or a folder with everything in
// it) and ends the process with exit code 128 + the signal's number (async-signal-safe: it
// allocates nothing). Errors and normal returns remove the same paths through CleanupGuard's
// destructor.
#pragma once

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

// The folder `dir` can be written into: created (with its parents) when it does not exist.
// Throws InputError(dir, ...) when it cannot be: a parent is a regular file, it is not a folder,
// or it is read-only (a probe file cannot be created in it). Returns whether it was created.
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

// The system's temporary folder ($TMPDIR, else /tmp). Throws InputError naming it when it does
// not exist or is not a folder.
std::filesystem::path temporary_folder();

// An output file written whole or not at all: the bytes go to a hidden file beside `target`
// (.NAME.graspcd-XXXXXX, created at construction: an unwritable folder is found before the
// work), renamed over `target` by commit(); its folder is created when missing. A `target` that
// exists and is not a regular file (/dev/stdout, /dev/full) is written directly. Throws
// InputError naming `target`.
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
