// Atomic whole-file writes: nothing a user asked for is ever left half-written.
//
// The content goes to a temporary file `<p>.tmp.<pid>` in the same directory, is flushed
// and fsync'ed, then renamed over `p` (rename is atomic within one file system). Readers see
// either the old file or the complete new one.
#pragma once

#include <filesystem>
#include <sstream>
#include <string>
#include <string_view>

#include "particula/io/error.hpp"

namespace particula::io {

/// Writes `content` to `p` atomically. The parent directory must exist. On failure the
/// temporary file is removed and IoError is thrown, naming `p` and the OS reason.
void write_file_atomic(const std::filesystem::path& p, std::string_view content);

/// Reads a whole file into a string; throws IoError naming the file when it cannot.
std::string read_file(const std::filesystem::path& p);

/// Accumulates a file's content in memory and writes it atomically on commit().
/// Destroying it without commit() writes nothing.
class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path target) : target_(std::move(target)) {}

  /// The stream to write the content to.
  std::ostream& stream() { return buffer_; }
  /// Appends text to the content.
  void write(std::string_view text) { buffer_ << text; }
  /// Writes the content to the target atomically. Throws IoError on failure and
  /// std::logic_error when called twice.
  void commit();

  const std::filesystem::path& target() const { return target_; }
  bool committed() const { return committed_; }

 private:
  std::filesystem::path target_;
  std::ostringstream buffer_;
  bool committed_ = false;
};

}  // namespace particula::io
