// The exception types of the io module.
#pragma once

#include <stdexcept>
#include <string>

namespace particula::io {

/// A file could not be read, or its content is malformed. The message always names the file
/// and, for OS failures, the OS reason. The CLI maps it to exit code 2 (bad input).
class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Writing to the file system failed: a file or directory could not be created, written,
/// renamed, truncated or removed (disk full, permission denied, file too large, ...). The
/// message names the path and the OS reason. The CLI maps it to exit code 4 (I/O failure),
/// not to "bad input"; it is an IoError so that code reading and writing alike can catch both.
class WriteError : public IoError {
 public:
  using IoError::IoError;
};

/// A long write was given up because the run was asked to stop (SIGINT/SIGTERM) while it was
/// being prepared; nothing of it was written. Not an IoError: nothing failed.
class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("cancelled: the run was asked to stop") {}
};

}  // namespace particula::io
