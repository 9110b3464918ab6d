// Atomic file writes with POSIX open/write/fsync/rename.
#include "particula/io/atomic_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>

namespace particula::io {
namespace {

/// The OS reason for the last failure, from errno.
std::string os_reason(int err) { return std::strerror(err); }

/// Bytes written between two polls of the stop check (a few milliseconds of disk bandwidth).
constexpr std::size_t kChunk = std::size_t{8} << 20;

/// Returned instead of an errno when the stop check asked to give up.
constexpr int kStopped = -1;

/// Writes all of `content` to `fd`, retrying on EINTR and short writes, polling `stop` between
/// chunks. Returns 0, an errno or kStopped.
int write_all(int fd, std::string_view content, const StopCheck& stop) {
  const char* p = content.data();
  std::size_t left = content.size();
  while (left > 0) {
    if (stop && stop()) return kStopped;
    const ssize_t n = ::write(fd, p, std::min(left, kChunk));
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  return 0;
}

/// Writes and fsyncs `content` to a new file `tmp`. Returns 0 or errno (tmp may remain).
int write_temp(const std::filesystem::path& tmp, std::string_view content, const StopCheck& stop) {
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return errno;
  int err = write_all(fd, content, stop);
  if (err == 0 && ::fsync(fd) != 0) err = errno;
  if (::close(fd) != 0 && err == 0) err = errno;
  return err;
}

/// Makes the rename durable by syncing the directory; failures are harmless and ignored.
void sync_directory(const std::filesystem::path& dir) {
  const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  (void)::fsync(fd);
  (void)::close(fd);
}

}  // namespace

std::filesystem::path atomic_temp_path(const std::filesystem::path& target, long pid) {
  std::filesystem::path tmp = target;
  tmp += fmt::format(".tmp.{}", pid);
  return tmp;
}

std::optional<AtomicTemp> atomic_temp_target(std::string_view name) {
  const std::size_t dot = name.rfind(".tmp.");
  if (dot == std::string_view::npos || dot == 0) return std::nullopt;
  const std::string_view digits = name.substr(dot + 5);
  if (digits.empty() || digits.size() > 10 || digits.front() == '0') return std::nullopt;
  long pid = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), pid);
  if (ec != std::errc() || end != digits.data() + digits.size() || pid <= 0 || pid > 2147483647L) return std::nullopt;
  return AtomicTemp{std::string(name.substr(0, dot)), pid};
}

void write_file_atomic(const std::filesystem::path& p, std::string_view content, const StopCheck& stop) {
  const std::filesystem::path tmp = atomic_temp_path(p, static_cast<long>(::getpid()));
  int err = write_temp(tmp, content, stop);
  if (err == 0 && std::rename(tmp.c_str(), p.c_str()) != 0) err = errno;
  if (err != 0) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    if (err == kStopped) throw Cancelled();
    throw WriteError(fmt::format("cannot write '{}': {}", p.string(), os_reason(err)));
  }
  sync_directory(p.parent_path());
}

std::string read_file(const std::filesystem::path& p) {
  const int fd = ::open(p.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw IoError(fmt::format("cannot read '{}': {}", p.string(), os_reason(errno)));
  std::string text;
  char chunk[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, chunk, sizeof chunk);
    if (n == 0) break;
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      ::close(fd);
      throw IoError(fmt::format("cannot read '{}': {}", p.string(), os_reason(err)));
    }
    text.append(chunk, static_cast<std::size_t>(n));
  }
  ::close(fd);
  return text;
}

void AtomicFile::commit() {
  if (committed_) throw std::logic_error("AtomicFile::commit called twice for " + target_.string());
  write_file_atomic(target_, buffer_.view());
  committed_ = true;
}

}  // namespace particula::io
