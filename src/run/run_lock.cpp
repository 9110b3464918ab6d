// The advisory lock of a run directory (RunDirLock): flock(2) on DIR/.particula-lock.
#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>

#include "particula/io/error.hpp"
#include "particula/run/run_dir.hpp"

namespace particula {

namespace fs = std::filesystem;

namespace {

/// How many times a lock file that was renamed away or deleted while it was being locked (its
/// directory replaced by a `run --overwrite`) is looked up again.
constexpr int kLockAttempts = 5;

/// The pid at the start of the lock file open as `fd`; nullopt when it holds none.
std::optional<long> pid_in(int fd) {
  char buf[32];
  const ssize_t n = ::pread(fd, buf, sizeof buf, 0);
  if (n <= 0) return std::nullopt;
  long pid = 0;
  const auto [end, err] = std::from_chars(buf, buf + n, pid);
  if (err != std::errc() || end == buf || pid <= 0) return std::nullopt;
  return pid;
}

/// Whether `fd` is the file at `path` now (not one renamed away or deleted since it was opened).
bool same_file(int fd, const fs::path& path) {
  struct stat open_st {
  }, path_st{};
  if (::fstat(fd, &open_st) != 0 || ::lstat(path.c_str(), &path_st) != 0) return false;
  return open_st.st_dev == path_st.st_dev && open_st.st_ino == path_st.st_ino;
}

/// The lock file of `dir`, opened for reading and writing (created when missing).
int open_lock_file(const fs::path& dir) {
  const fs::path file = dir / kRunLock;
  struct stat st {};
  if (::lstat(file.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
    throw RunDirRefused(fmt::format("'{}': the lock file '{}' is {}; particula does not open it",
                                    dir.string(), file.string(),
                                    S_ISLNK(st.st_mode) ? "a symbolic link" : "not a regular file"));
  const int fd = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK, 0644);
  if (fd < 0) {
    const int err = errno;
    if (err == ELOOP)
      throw RunDirRefused(
          fmt::format("'{}': the lock file '{}' is a symbolic link", dir.string(), file.string()));
    throw io::WriteError(
        fmt::format("cannot create the lock file '{}': {}", file.string(), std::strerror(err)));
  }
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    throw RunDirRefused(
        fmt::format("'{}': the lock file '{}' is not a regular file", dir.string(), file.string()));
  }
  return fd;
}

}  // namespace

bool process_running(long pid) {
  if (pid <= 0) return false;
  if (pid == static_cast<long>(::getpid())) return true;
  return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
}

RunDirBusy::RunDirBusy(const fs::path& dir, std::optional<long> pid)
    : RunDirRefused(fmt::format("run directory '{}' is in use by another particula process{}, which holds "
                                "its lock {}: wait until it has ended, or stop it, before running, resuming "
                                "or overwriting this directory; nothing was changed",
                                dir.string(), pid ? fmt::format(", pid {}", *pid) : std::string(),
                                (dir / kRunLock).string())) {}

RunDirLock::RunDirLock(const fs::path& dir) {
  const fs::path file = dir / kRunLock;
  for (int attempt = 0; attempt < kLockAttempts; ++attempt) {
    const int fd = open_lock_file(dir);
    int r = 0;
    while ((r = ::flock(fd, LOCK_EX | LOCK_NB)) != 0 && errno == EINTR) {
    }
    if (r != 0) {
      const int err = errno;
      const std::optional<long> pid = pid_in(fd);
      ::close(fd);
      if (err == EWOULDBLOCK) throw RunDirBusy(dir, pid);
      throw io::WriteError(fmt::format("cannot lock '{}': {}", file.string(), std::strerror(err)));
    }
    // The directory may have been renamed aside or deleted between open and flock: then the
    // lock is on a file that is no longer this directory's, and the one there now is locked.
    if (!same_file(fd, file)) {
      ::close(fd);
      continue;
    }
    // The pid is for the messages of the processes refused; failing to write it changes nothing.
    const std::string text = fmt::format(
        "{}\n# particula process {} uses this run directory while it holds a lock "
        "(flock) on this file\n",
        static_cast<long>(::getpid()), static_cast<long>(::getpid()));
    if (::ftruncate(fd, 0) == 0) (void)!::pwrite(fd, text.data(), text.size(), 0);
    fd_ = fd;
    return;
  }
  throw RunDirBusy(dir, std::nullopt);  // replaced again and again: another particula is replacing it
}

RunDirLock& RunDirLock::operator=(RunDirLock&& other) noexcept {
  if (this != &other) {
    release();
    fd_ = other.fd_;
    other.fd_ = -1;
  }
  return *this;
}

void RunDirLock::release() {
  if (fd_ < 0) return;
  (void)!::ftruncate(fd_, 0);  // no pid: nobody uses the directory
  ::close(fd_);                // unlocks
  fd_ = -1;
}

std::optional<long> run_dir_user(const fs::path& dir) {
  const fs::path file = dir / kRunLock;
  struct stat st {};
  if (::lstat(file.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return std::nullopt;
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK);
  if (fd < 0) return std::nullopt;
  const std::optional<long> pid = pid_in(fd);
  ::close(fd);
  if (pid && process_running(*pid)) return pid;
  return std::nullopt;
}

}  // namespace particula
