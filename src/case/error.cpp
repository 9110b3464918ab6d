// CaseError and the location of keys in a loaded document.
#include "particula/case/error.hpp"

#include <fmt/format.h>

#include "internal.hpp"

namespace particula {
namespace {

/// "file:line: key 'k': message", leaving out the line when 0 and the key when empty.
std::string one_line(const std::string& file, int line, const std::string& key, const std::string& message) {
  std::string s = file;
  if (line > 0) s += fmt::format(":{}", line);
  s += ": ";
  if (!key.empty()) s += fmt::format("key '{}': ", key);
  return s + message;
}

}  // namespace

CaseError::CaseError(std::string file, int line, std::string key, std::string message)
    : std::runtime_error(one_line(file, line, key, message)),
      file_(std::move(file)),
      line_(line),
      key_(std::move(key)),
      message_(std::move(message)) {}

namespace case_detail {

CaseError LoadContext::error(const std::string& key, const std::string& message) const {
  // The key itself, else its enclosing tables ("probe[1].points" -> "probe[1]" -> "probe").
  std::string k = key;
  while (!k.empty()) {
    if (overridden.contains(k)) return CaseError(std::string(kOverrideSource), 0, key, message);
    if (const auto it = lines.find(k); it != lines.end()) return CaseError(file, it->second, key, message);
    const auto cut = k.find_last_of(".[");
    k = cut == std::string::npos ? "" : k.substr(0, cut);
  }
  return CaseError(file, 0, key, message);
}

CaseError LoadContext::error_at(const std::string& key, int line, const std::string& message) const {
  const CaseError located = error(key, message);
  if (line <= 0 || located.file() != file) return located;  // overridden, or no better line
  return CaseError(file, line, key, message);
}

int LoadContext::item_line(const std::string& key, std::size_t i) const {
  const auto it = lines.find(fmt::format("{}[{}]", key, i));
  return it == lines.end() ? 0 : it->second;
}

}  // namespace case_detail
}  // namespace particula
