#include "graspcd/io/output_files.h"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "graspcd/io/text_input.h"

namespace graspcd::io {

namespace {

namespace fs = std::filesystem;

constexpr std::size_t kMaxPath = 4096;

// The table the signal handler reads: filled with the signals blocked, so that the handler never
// sees a half-written entry.
struct CleanupSlot {
  volatile sig_atomic_t used;
  char path[kMaxPath];
};
CleanupSlot g_slots[kMaxCleanupPaths];

const int kSignals[] = {SIGINT, SIGTERM, SIGHUP};

bool is_dot(const char* name) {
  return name[0] == '.' && (name[1] == '\0' || (name[1] == '.' && name[2] == '\0'));
}

// Removes `name` (relative to the folder dirfd) and, for a folder, everything under it, `depth`
// folders deep at most. Async-signal-safe: system calls and a buffer on the stack only.
void remove_at(int dirfd, const char* name, int depth) {
  if (unlinkat(dirfd, name, 0) == 0 || errno == ENOENT) return;
  if (depth > 16) return;
  const int fd = openat(dirfd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return;
  alignas(struct dirent64) char buffer[4096];
  // Entries removed while the folder is read may move: read it again until a pass removes none.
  for (int pass = 0; pass < 4; ++pass) {
    bool removed = false;
    lseek(fd, 0, SEEK_SET);
    for (;;) {
      const long n = syscall(SYS_getdents64, fd, buffer, sizeof(buffer));
      if (n <= 0) break;
      for (long at = 0; at < n;) {
        const auto* entry = reinterpret_cast<const struct dirent64*>(buffer + at);
        at += entry->d_reclen;
        if (is_dot(entry->d_name)) continue;
        remove_at(fd, entry->d_name, depth + 1);
        removed = true;
      }
    }
    if (!removed) break;
  }
  close(fd);
  unlinkat(dirfd, name, AT_REMOVEDIR);
}

extern "C" void on_cleanup_signal(int sig) {
  for (int i = kMaxCleanupPaths - 1; i >= 0; --i) {
    if (g_slots[i].used) remove_at(AT_FDCWD, g_slots[i].path, 0);
  }
  _exit(128 + sig);
}

// The three signals blocked while the table changes.
class SignalsBlocked {
 public:
  SignalsBlocked() {
    sigset_t set;
    sigemptyset(&set);
    for (int s : kSignals) sigaddset(&set, s);
    pthread_sigmask(SIG_BLOCK, &set, &previous_);
  }
  ~SignalsBlocked() { pthread_sigmask(SIG_SETMASK, &previous_, nullptr); }
  SignalsBlocked(const SignalsBlocked&) = delete;
  SignalsBlocked& operator=(const SignalsBlocked&) = delete;

 private:
  sigset_t previous_;
};

int register_path(const fs::path& path) {
  const std::string text = fs::absolute(path).lexically_normal().string();
  if (text.size() >= kMaxPath) throw std::length_error(text + ": path too long to clean up");
  SignalsBlocked blocked;
  for (int i = 0; i < kMaxCleanupPaths; ++i) {
    if (g_slots[i].used) continue;
    std::memcpy(g_slots[i].path, text.c_str(), text.size() + 1);
    g_slots[i].used = 1;
    return i;
  }
  throw std::length_error("more than " + std::to_string(kMaxCleanupPaths) +
                          " temporary paths at once");
}

void unregister_path(int slot) {
  if (slot < 0) return;
  SignalsBlocked blocked;
  g_slots[slot].used = 0;
}

std::string error_text(int error) { return std::strerror(error); }

}  // namespace

void install_cleanup_handlers() {
  static bool installed = false;
  if (installed) return;
  installed = true;
  struct sigaction action {};
  action.sa_handler = on_cleanup_signal;
  sigemptyset(&action.sa_mask);
  for (int s : kSignals) sigaddset(&action.sa_mask, s);
  for (int s : kSignals) {
    struct sigaction previous {};
    // A signal the parent set to be ignored (nohup) stays ignored.
    if (sigaction(s, nullptr, &previous) == 0 && previous.sa_handler == SIG_IGN) continue;
    sigaction(s, &action, nullptr);
  }
}

CleanupGuard::CleanupGuard(const fs::path& path) : path_(path), slot_(register_path(path)) {}

CleanupGuard::~CleanupGuard() {
  if (slot_ < 0) return;
  std::error_code ignored;
  fs::remove_all(path_, ignored);
  unregister_path(slot_);
}

CleanupGuard::CleanupGuard(CleanupGuard&& other) noexcept
    : path_(std::move(other.path_)), slot_(std::exchange(other.slot_, -1)) {}

CleanupGuard& CleanupGuard::operator=(CleanupGuard&& other) noexcept {
  if (this != &other) {
    if (slot_ >= 0) {
      std::error_code ignored;
      fs::remove_all(path_, ignored);
      unregister_path(slot_);
    }
    path_ = std::move(other.path_);
    slot_ = std::exchange(other.slot_, -1);
  }
  return *this;
}

void CleanupGuard::release() {
  unregister_path(slot_);
  slot_ = -1;
}

RemoveIfEmpty::~RemoveIfEmpty() {
  std::error_code ignored;
  if (!path_.empty() && fs::is_empty(path_, ignored)) fs::remove(path_, ignored);
}

bool prepare_output_folder(const std::string& dir) {
  std::error_code ec;
  const fs::path folder(dir);
  bool created = false;
  if (fs::exists(folder, ec)) {
    if (!fs::is_directory(folder, ec)) throw InputError(dir, 0, "not a folder");
  } else {
    // The nearest part of the path that exists must be a folder.
    for (fs::path up = fs::absolute(folder).parent_path(); !up.empty(); up = up.parent_path()) {
      if (fs::exists(up, ec)) {
        if (!fs::is_directory(up, ec)) {
          throw InputError(dir, 0, "cannot create the folder: " + up.string() + " is a file");
        }
        break;
      }
      if (up == up.root_path()) break;
    }
    fs::create_directories(folder, ec);
    if (ec) throw InputError(dir, 0, "cannot create the folder: " + ec.message());
    created = true;
  }
  std::string probe = (folder / ".graspcd-probe-XXXXXX").string();
  const int fd = mkstemp(probe.data());
  if (fd < 0) throw InputError(dir, 0, "cannot write into the folder: " + error_text(errno));
  close(fd);
  unlink(probe.c_str());
  return created;
}

CleanupGuard make_private_folder(const fs::path& parent, const std::string& prefix,
                                 const std::string& named) {
  std::string pattern = (parent / (prefix + "-XXXXXX")).string();
  // A signal between the folder's creation and its registration would leave it behind.
  const SignalsBlocked blocked;
  if (mkdtemp(pattern.data()) == nullptr) {
    throw InputError(named, 0,
                     "cannot write into " + (parent.empty() ? std::string(".") : parent.string()) +
                         ": " + error_text(errno));
  }
  return CleanupGuard(pattern);
}

fs::path temporary_folder() {
  const char* tmpdir = std::getenv("TMPDIR");
  const fs::path folder = tmpdir != nullptr && *tmpdir != '\0' ? fs::path(tmpdir) : "/tmp";
  std::error_code ec;
  if (!fs::exists(folder, ec)) {
    throw InputError(folder.string(), 0, "the temporary folder (TMPDIR) does not exist");
  }
  if (!fs::is_directory(folder, ec)) {
    throw InputError(folder.string(), 0, "the temporary folder (TMPDIR) is not a folder");
  }
  return folder;
}

AtomicFile::AtomicFile(std::string target) : target_(std::move(target)) {
  std::error_code ec;
  const fs::path path(target_);
  if (fs::exists(path, ec) && !fs::is_regular_file(path, ec)) {
    if (fs::is_directory(path, ec)) throw InputError(target_, 0, "cannot write: it is a folder");
    write_path_ = target_;  // a device or a pipe: written directly
    return;
  }
  const fs::path parent = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  if (!fs::is_directory(parent, ec)) {
    // A missing folder is created (with its parents), unless a file is in the way.
    try {
      prepare_output_folder(parent.string());
    } catch (const InputError& e) {
      throw InputError(target_, 0, "cannot write: " + e.message() + " (" + parent.string() + ")");
    }
  }
  std::string hidden = (parent / ("." + path.filename().string() + ".graspcd-XXXXXX")).string();
  const SignalsBlocked blocked;
  const int fd = mkstemp(hidden.data());
  if (fd < 0) throw InputError(target_, 0, "cannot write: " + error_text(errno));
  const mode_t mask = umask(0);
  umask(mask);
  fchmod(fd, 0666 & ~mask);
  close(fd);
  guard_ = CleanupGuard(hidden);
  write_path_ = hidden;
}

void AtomicFile::commit() {
  if (guard_.path().empty()) return;
  if (std::rename(write_path_.c_str(), target_.c_str()) != 0) {
    throw InputError(target_, 0, "cannot write: " + error_text(errno));
  }
  guard_.release();
}

}  // namespace graspcd::io
