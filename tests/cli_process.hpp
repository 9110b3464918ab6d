// Runs the particula binary (PARTICULA_BINARY) as a child process for CLI tests: no shell, so
// paths need no quoting and a test can signal the child.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "scratch_dir.hpp"

extern char** environ;

namespace cli_test {

/// How a child ended: `code` is the exit status, or -1 when it ended on signal `signal`.
struct Ended {
  int code = -1;
  int signal = 0;
  std::string output;  // stdout and stderr together
};

/// A started child process, its output going to a temporary file.
class Child {
 public:
  /// Starts `program` (searched on the PATH) with `args`.
  Child(const std::string& program, const std::vector<std::string>& args) {
    static int counter = 0;
    log_ = std::filesystem::temp_directory_path() /
           ("particula_child_" + std::to_string(::getpid()) + "_" + std::to_string(counter++) + ".log");
    std::vector<std::string> all{program};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log_.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    if (posix_spawnp(&pid_, argv[0], &actions, nullptr, argv.data(), environ) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&actions);
  }
  ~Child() {
    if (pid_ > 0 && !waited_) {
      ::kill(pid_, SIGKILL);
      wait();
    }
    std::error_code ec;
    std::filesystem::remove(log_, ec);
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;

  pid_t pid() const { return pid_; }
  void signal(int sig) const { ::kill(pid_, sig); }

  /// Waits for the child to end.
  Ended wait() {
    Ended e;
    if (pid_ <= 0) {
      e.output = "could not start the child process";
      return e;
    }
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    waited_ = true;
    if (WIFEXITED(status)) e.code = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) e.signal = WTERMSIG(status);
    std::ifstream in(log_);
    std::stringstream ss;
    ss << in.rdbuf();
    e.output = ss.str();
    return e;
  }

 private:
  pid_t pid_ = -1;
  bool waited_ = false;
  std::filesystem::path log_;
};

/// Runs particula with `args` to its end.
inline Ended cli(const std::vector<std::string>& args) { return Child(PARTICULA_BINARY, args).wait(); }

inline std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline void write_text(const std::filesystem::path& p, const std::string& text) {
  std::ofstream(p, std::ios::binary) << text;
}

/// An empty scratch directory for one test (scratch_dir.hpp: removed when the binary passes).
inline std::filesystem::path fresh_dir(const std::string& name) { return test_scratch::scratch_dir(name); }

/// A process id that is not running (a child that has ended and been reaped).
inline long dead_pid() {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(0);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return static_cast<long>(pid);
}

/// The first CSV file in `dir` holding NaN or Inf (any case), or "".
inline std::string csv_with_non_finite(const std::filesystem::path& dir) {
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    if (e.path().extension() != ".csv") continue;
    std::string text = read_text(e.path());
    std::transform(text.begin(), text.end(), text.begin(), [](unsigned char ch) { return std::tolower(ch); });
    if (text.find("nan") != std::string::npos || text.find("inf") != std::string::npos)
      return e.path().filename().string();
  }
  return "";
}

}  // namespace cli_test
