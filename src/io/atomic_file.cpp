// Atomic file writes with POSIX open/write/fsync/rename.
#include "particula/io/atomic_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace particula::io {
namespace {

/// The OS reason for the last failure, from errno.
std::string os_reason(int err) { return std::strerror(err); }

/// Writes all of `content` to `fd`, retrying on EINTR and short writes. Returns 0 or errno.
int write_all(int fd, std::string_view content) {
  const char* p = content.data();
  std::size_t left = content.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
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
int write_temp(const std::filesystem::path& tmp, std::string_view content) {
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return errno;
  int err = write_all(fd, content);
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

void write_file_atomic(const std::filesystem::path& p, std::string_view content) {
  std::filesystem::path tmp = p;
  tmp += fmt::format(".tmp.{}", static_cast<long>(::getpid()));
  int err = write_temp(tmp, content);
  if (err == 0 && std::rename(tmp.c_str(), p.c_str()) != 0) err = errno;
  if (err != 0) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw IoError(fmt::format("cannot write '{}': {}", p.string(), os_reason(err)));
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
