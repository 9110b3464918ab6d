// The one exception type for every mistake a user can make in a case file or a --set override.
#pragma once

#include <stdexcept>
#include <string>

namespace particula {

/// A user error in a case file or an override. `what()` is one line:
///   `cases/foo.toml:12: key 'fluid.nuu': unknown key (did you mean 'fluid.nu'?)`
/// `file` is the case file, or "--set" when the offending value came from an override;
/// `line` is 1-based, 0 when there is no line (overrides, missing file, missing key with no table).
/// `key` is the dotted key in the form used in messages (`probe[0].points`), empty if none.
class CaseError : public std::runtime_error {
 public:
  CaseError(std::string file, int line, std::string key, std::string message);

  const std::string& file() const { return file_; }
  int line() const { return line_; }
  const std::string& key() const { return key_; }
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  int line_;
  std::string key_;
  std::string message_;
};

}  // namespace particula
