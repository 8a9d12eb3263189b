// Processes as a test sees them through /proc: a command's children (node, the mesh reader's
// fork), whether one still runs, and a bounded wait for a state, so that the tests that send
// signals wait for what they need instead of sleeping a fixed time (a loaded machine is slow).
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <ios>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace graspcd::testing {

// The state letter, parent id and command name of a process from /proc/PID/stat ('\0' when it
// is gone, also when it went between the file's opening and its reading: then the read fails with
// ESRCH, which libstdc++'s file buffer throws as an exception).
struct ProcessStat {
  char state = '\0';
  pid_t parent = 0;
  std::string name;
};

inline ProcessStat process_stat(pid_t pid) {
  std::string text;
  try {
    std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  } catch (const std::ios_base::failure&) {
    return {};
  }
  ProcessStat s;
  const std::size_t open = text.find('(');
  const std::size_t close = text.rfind(')');
  if (open == std::string::npos || close == std::string::npos || close < open) return s;
  s.name = text.substr(open + 1, close - open - 1);
  std::istringstream rest(text.substr(close + 1));
  rest >> s.state >> s.parent;
  return s;
}

// Whether `pid` runs (a zombie, which runs no more, counts as gone).
inline bool process_runs(pid_t pid) {
  const char state = process_stat(pid).state;
  return state != '\0' && state != 'Z' && state != 'X';
}

// The running children of `parent`, with their command names.
inline std::vector<std::pair<pid_t, std::string>> children_of(pid_t parent) {
  std::vector<std::pair<pid_t, std::string>> out;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator("/proc", ec)) {
    const std::string name = e.path().filename().string();
    if (name.empty() || name.find_first_not_of("0123456789") != std::string::npos) continue;
    const pid_t pid = static_cast<pid_t>(std::stol(name));
    const ProcessStat s = process_stat(pid);
    if (s.parent == parent && s.state != 'Z' && s.state != '\0') out.emplace_back(pid, s.name);
  }
  return out;
}

// Polls `condition` every 5 ms for at most `seconds`; whether it came true.
inline bool wait_for(const std::function<bool()>& condition, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (!condition()) {
    if (std::chrono::steady_clock::now() > end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

// Starts `exe` with `args`, the variables `env` ("NAME=VALUE") added to the environment, stdout
// and stderr into the files `out` and `err`; its id.
inline pid_t spawn(const std::string& exe, const std::vector<std::string>& args,
                   const std::vector<std::string>& env, const std::string& out,
                   const std::string& err) {
  std::vector<std::string> words = {exe};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    for (const std::string& e : env) putenv(const_cast<char*>(e.c_str()));
    const int o = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int e = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(o, 1);
    dup2(e, 2);
    execv(exe.c_str(), argv.data());
    _exit(127);
  }
  return pid;
}

// Waits at most `seconds` for `pid` to end; its exit code, or 128 + the signal that ended it; -1
// when it was still running (then it is killed).
inline int finish(pid_t pid, double seconds) {
  int status = 0;
  const bool ended = wait_for([&] { return waitpid(pid, &status, WNOHANG) == pid; }, seconds);
  if (!ended) {
    kill(pid, SIGKILL);
    waitpid(pid, &status, 0);
    return -1;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace graspcd::testing
