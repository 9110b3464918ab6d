// Atomic whole-file writes: nothing a user asked for is ever left half-written.
//
// The content goes to a temporary file `<p>.tmp.<pid>` in the same directory, is flushed
// and fsync'ed, then renamed over `p` (rename is atomic within one file system). Readers see
// either the old file or the complete new one. A process killed while writing leaves its
// temporary file behind; atomic_temp_target() recognises such names so that the next run in
// that directory can remove them.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>

#include "particula/io/error.hpp"

namespace particula::io {

/// Polled between chunks of long writes; returning true gives the write up (io::Cancelled).
using StopCheck = std::function<bool()>;

/// Writes `content` to `p` atomically. The parent directory must exist. On failure the
/// temporary file is removed and WriteError is thrown, naming `p` and the OS reason. With
/// `stop`, a large content is written in chunks and `stop()` is polled between them: when it
/// returns true the temporary file is removed and io::Cancelled is thrown (`p` is untouched).
void write_file_atomic(const std::filesystem::path& p, std::string_view content, const StopCheck& stop = {});

/// Reads a whole file into a string; throws IoError naming the file when it cannot.
std::string read_file(const std::filesystem::path& p);

/// The temporary file a write_file_atomic of `target` by process `pid` uses.
std::filesystem::path atomic_temp_path(const std::filesystem::path& target, long pid);

/// For a file name of the form `<target>.tmp.<pid>` (what write_file_atomic leaves behind when
/// killed), the target's name and the pid; nullopt for any other name.
struct AtomicTemp {
  std::string target;
  long pid = 0;
};
std::optional<AtomicTemp> atomic_temp_target(std::string_view file_name);

/// Accumulates a file's content in memory and writes it atomically on commit().
/// Destroying it without commit() writes nothing.
class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path target) : target_(std::move(target)) {}

  /// The stream to write the content to.
  std::ostream& stream() { return buffer_; }
  /// Appends text to the content.
  void write(std::string_view text) { buffer_ << text; }
  /// Writes the content to the target atomically. Throws WriteError on failure and
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
