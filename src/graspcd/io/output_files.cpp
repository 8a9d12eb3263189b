#include "graspcd/io/output_files.h"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <system_error>
#include <utility>
#include <vector>

#include "graspcd/io/input_error.h"
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

// The run's children (ChildProcess), by id; 0 is a free entry.
volatile sig_atomic_t g_children[kMaxChildren];

// A Deadline's line (with its '\n'), written by the SIGALRM handler to the stderr the Deadline
// saw (a copy of the descriptor: a library may point descriptor 2 elsewhere for a while, as the
// MuJoCo layer does while mj_loadXML prints qhull's diagnostics).
char g_deadline_message[4096];
volatile sig_atomic_t g_deadline_length = 0;
volatile sig_atomic_t g_deadline_fd = -1;

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

// Kills the run's children and reaps them (a child writing into a folder about to be removed is
// gone before it is removed), then removes the guarded paths. Async-signal-safe.
void end_run() {
  for (int i = 0; i < kMaxChildren; ++i) {
    const pid_t pid = g_children[i];
    if (pid <= 0) continue;
    kill(pid, SIGKILL);
    while (waitpid(pid, nullptr, 0) < 0 && errno == EINTR) {
    }
    g_children[i] = 0;
  }
  for (int i = kMaxCleanupPaths - 1; i >= 0; --i) {
    if (g_slots[i].used) remove_at(AT_FDCWD, g_slots[i].path, 0);
  }
}

extern "C" void on_cleanup_signal(int sig) {
  end_run();
  _exit(128 + sig);
}

extern "C" void on_deadline(int) {
  const sig_atomic_t length = g_deadline_length;
  for (sig_atomic_t done = 0; done < length;) {
    const ssize_t n =
        write(g_deadline_fd, g_deadline_message + done, static_cast<std::size_t>(length - done));
    if (n <= 0 && errno != EINTR) break;
    if (n > 0) done += static_cast<sig_atomic_t>(n);
  }
  end_run();
  _exit(2);
}

// The three signals (and a Deadline's SIGALRM) blocked while the tables change.
class SignalsBlocked {
 public:
  SignalsBlocked() {
    sigset_t set;
    sigemptyset(&set);
    for (int s : kSignals) sigaddset(&set, s);
    sigaddset(&set, SIGALRM);
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
  sigaddset(&action.sa_mask, SIGALRM);
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

ChildProcess::ChildProcess() {
  const SignalsBlocked blocked;
  int slot = -1;
  for (int i = 0; i < kMaxChildren && slot < 0; ++i) {
    if (g_children[i] == 0) slot = i;
  }
  if (slot < 0) {
    errno = EAGAIN;
    return;
  }
  const pid_t parent = getpid();
  pid_ = fork();
  if (pid_ == 0) {
    // The child: the parent's handlers are not its own, and it dies with the parent.
    struct sigaction fallback {};
    fallback.sa_handler = SIG_DFL;
    sigemptyset(&fallback.sa_mask);
    for (int s : kSignals) {
      struct sigaction current {};
      if (sigaction(s, nullptr, &current) == 0 && current.sa_handler == on_cleanup_signal) {
        sigaction(s, &fallback, nullptr);
      }
    }
    sigaction(SIGALRM, &fallback, nullptr);
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(1);  // the parent ended before the line above
    return;
  }
  if (pid_ > 0) {
    g_children[slot] = pid_;
    slot_ = slot;
  }
}

ChildProcess::~ChildProcess() {
  if (pid_ <= 0) return;
  if (!reaped_) {
    ::kill(pid_, SIGKILL);
    int status = 0;
    try {
      wait(&status, true);
    } catch (const std::system_error&) {
    }
  }
}

bool ChildProcess::wait(int* status, bool block) {
  if (pid_ <= 0 || reaped_) return reaped_;
  pid_t done = 0;
  do {
    done = waitpid(pid_, status, block ? 0 : WNOHANG);
  } while (done < 0 && errno == EINTR);
  if (done == 0) return false;
  const int error = errno;
  reaped_ = true;
  if (slot_ >= 0) {
    const SignalsBlocked blocked;
    g_children[slot_] = 0;
    slot_ = -1;
  }
  if (done < 0) throw std::system_error(error, std::generic_category(), "waitpid");
  return true;
}

void ChildProcess::kill() {
  if (pid_ > 0 && !reaped_) ::kill(pid_, SIGKILL);
}

Deadline::Deadline(double seconds, const std::string& message) {
  const std::string line = one_line(message) + '\n';
  const SignalsBlocked blocked;
  const std::size_t length = std::min(line.size(), sizeof(g_deadline_message));
  std::memcpy(g_deadline_message, line.data(), length);
  g_deadline_message[length - 1] = '\n';
  g_deadline_length = static_cast<sig_atomic_t>(length);
  g_deadline_fd = fcntl(STDERR_FILENO, F_DUPFD_CLOEXEC, 3);
  struct sigaction action {};
  action.sa_handler = on_deadline;
  sigemptyset(&action.sa_mask);
  for (int s : kSignals) sigaddset(&action.sa_mask, s);
  sigaction(SIGALRM, &action, nullptr);
  itimerval timer{};
  const double whole = std::floor(std::max(seconds, 0.0));
  timer.it_value.tv_sec = static_cast<time_t>(whole);
  timer.it_value.tv_usec = static_cast<suseconds_t>((std::max(seconds, 0.0) - whole) * 1e6);
  if (timer.it_value.tv_sec == 0 && timer.it_value.tv_usec == 0) timer.it_value.tv_usec = 1;
  setitimer(ITIMER_REAL, &timer, nullptr);
  armed_ = true;
}

Deadline::~Deadline() { cancel(); }

void Deadline::cancel() {
  if (!armed_) return;
  armed_ = false;
  const SignalsBlocked blocked;
  const itimerval off{};
  setitimer(ITIMER_REAL, &off, nullptr);
  struct sigaction fallback {};
  fallback.sa_handler = SIG_DFL;
  sigemptyset(&fallback.sa_mask);
  sigaction(SIGALRM, &fallback, nullptr);
  g_deadline_length = 0;
  if (g_deadline_fd >= 0) close(g_deadline_fd);
  g_deadline_fd = -1;
}

bool same_file(const fs::path& a, const fs::path& b) {
  struct stat sa {
  }, sb{};
  return ::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0 && sa.st_dev == sb.st_dev &&
         sa.st_ino == sb.st_ino;
}

void writable_folder(const std::string& dir) {
  struct stat info {};
  if (::stat(dir.c_str(), &info) == 0 && (info.st_mode & (S_IWUSR | S_IWGRP | S_IWOTH)) == 0) {
    char mode[8];
    std::snprintf(mode, sizeof(mode), "%04o", static_cast<unsigned>(info.st_mode & 07777));
    throw InputError(
        dir, 0, std::string("cannot write into the folder: it is read-only (mode ") + mode + ")");
  }
  std::string probe = (fs::path(dir) / ".graspcd-probe-XXXXXX").string();
  const int fd = mkstemp(probe.data());
  if (fd < 0) throw InputError(dir, 0, "cannot write into the folder: " + error_text(errno));
  close(fd);
  unlink(probe.c_str());
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
  writable_folder(dir);
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

void move_entries(const fs::path& work, const fs::path& target, const std::string& named) {
  std::vector<fs::path> entries;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(work, ec)) entries.push_back(e.path());
  if (ec) throw InputError(named, 0, "cannot write into the folder: " + ec.message());
  const SignalsBlocked blocked;
  for (const fs::path& entry : entries) {
    const fs::path place = target / entry.filename();
    if (fs::exists(fs::symlink_status(place, ec))) {
      fs::rename(place, work / (".replaced-" + entry.filename().string()), ec);
      if (ec) throw InputError(place.string(), 0, "cannot replace: " + ec.message());
    }
    fs::rename(entry, place, ec);
    if (ec) throw InputError(place.string(), 0, "cannot write: " + ec.message());
  }
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
  // A missing folder is created (with its parents), unless a file is in the way; a read-only one
  // is refused.
  try {
    prepare_output_folder(parent.string());
  } catch (const InputError& e) {
    throw InputError(target_, 0, "cannot write: " + e.message() + " (" + parent.string() + ")");
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
