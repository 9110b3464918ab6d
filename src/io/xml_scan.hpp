// Internal: a tiny scanner for the XML that this module writes (VTK .vtp and .pvd files).
// It reads tags and attributes one by one; it is not a general XML parser. Every malformed
// input raises IoError (without a file name; callers add it), never undefined behaviour.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace particula::io::detail {

/// One element tag: <name a="v">, </name> or <name a="v"/>.
struct XmlTag {
  std::string_view name;
  bool closing = false;                                              ///< </name>
  bool self_closing = false;                                         ///< <name .../>
  std::vector<std::pair<std::string_view, std::string>> attributes;  ///< values unescaped
  std::size_t end = 0;                                               ///< offset just after the '>'

  /// The attribute's value, or nullptr when absent.
  const std::string* find(std::string_view key) const;
  /// The attribute's value; throws IoError naming the element and attribute when absent.
  const std::string& at(std::string_view key) const;
};

/// The next element tag at or after `pos`, skipping text, <?...?>, <!--...--> and <!...>.
/// std::nullopt when no '<' is left.
std::optional<XmlTag> next_tag(std::string_view text, std::size_t pos);

/// Escapes &, <, >, " and ' for use in attribute values.
std::string xml_escape(std::string_view s);

/// Parses a non-negative decimal integer attribute; throws IoError when it is not one.
std::uint64_t parse_count(std::string_view s, std::string_view what);

}  // namespace particula::io::detail
