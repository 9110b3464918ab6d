// The one exception type of the io module.
#pragma once

#include <stdexcept>
#include <string>

namespace particula::io {

/// A file could not be read or written, or its content is malformed. The message always
/// names the file and, for OS failures, the OS reason. The CLI maps it to exit code 2.
class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace particula::io
