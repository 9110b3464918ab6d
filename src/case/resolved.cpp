// resolved_case_toml: a Case written back as TOML, every key present, defaults filled in.
#include <fmt/format.h>

#include "internal.hpp"
#include "particula/case/load.hpp"

namespace particula {
namespace {

/// "key = value" lines of the rows of `section` for element `index` (values that are written back).
std::string key_lines(const Case& c, const std::string& section, std::size_t index) {
  std::string out;
  for (const KeySpec& spec : case_schema()) {
    if (spec.section() != section || !spec.used_for(c, index)) continue;
    if (const std::optional<Value> v = spec.bind.get(c, index))
      out += fmt::format("{} = {}\n", spec.leaf(), format_toml_value(*v));
  }
  return out;
}

}  // namespace

std::string resolved_case_toml(const Case& c) {
  std::string out =
      "# Fully resolved case written by particula: every key, defaults filled in, overrides applied.\n";
  for (const SectionSpec& s : case_sections()) {
    if (s.name.empty()) {
      out += key_lines(c, "", 0);
    } else if (!s.array) {
      out += fmt::format("\n[{}]\n{}", s.name, key_lines(c, s.name, 0));
    } else {
      for (std::size_t i = 0; i < s.size(c); ++i)
        out += fmt::format("\n[[{}]]\n{}", s.name, key_lines(c, s.name, i));
    }
  }
  return out;
}

}  // namespace particula
