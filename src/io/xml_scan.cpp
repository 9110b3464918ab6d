// Tag scanner for the XML written by the io module.
#include "xml_scan.hpp"

#include <fmt/format.h>

#include <charconv>

#include "particula/io/error.hpp"

namespace particula::io::detail {
namespace {

bool is_space(char c) { return c == ' ' || c == '\n' || c == '\r' || c == '\t'; }
bool is_name_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' ||
         c == ':' || c == '.';
}

std::size_t skip_space(std::string_view t, std::size_t i) {
  while (i < t.size() && is_space(t[i])) ++i;
  return i;
}

/// Reads a name starting at i; throws when there is none.
std::string_view read_name(std::string_view t, std::size_t& i) {
  const std::size_t start = i;
  while (i < t.size() && is_name_char(t[i])) ++i;
  if (i == start) throw IoError(fmt::format("malformed XML at byte {}", start));
  return t.substr(start, i - start);
}

/// Replaces the five predefined entities; throws on any other entity.
std::string xml_unescape(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '&') {
      out += s[i];
      continue;
    }
    static constexpr std::pair<std::string_view, char> kEntities[] = {
        {"&amp;", '&'}, {"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}, {"&apos;", '\''}};
    bool found = false;
    for (const auto& [entity, ch] : kEntities) {
      if (s.substr(i, entity.size()) == entity) {
        out += ch;
        i += entity.size() - 1;
        found = true;
        break;
      }
    }
    if (!found) throw IoError("unsupported XML entity in attribute value");
  }
  return out;
}

/// Skips a <?...?>, <!--...--> or <!...> construct starting at i; returns the offset after it.
std::size_t skip_special(std::string_view t, std::size_t i) {
  std::string_view close = ">";
  if (t.substr(i, 2) == "<?") close = "?>";
  if (t.substr(i, 4) == "<!--") close = "-->";
  const std::size_t e = t.find(close, i + 2);
  if (e == std::string_view::npos) throw IoError("unterminated XML declaration or comment");
  return e + close.size();
}

/// Reads the attributes and the end of a tag whose name ends at i.
void read_attributes(std::string_view t, std::size_t i, XmlTag& tag) {
  for (;;) {
    i = skip_space(t, i);
    if (i >= t.size()) throw IoError("unterminated XML tag");
    if (t[i] == '>' || t.substr(i, 2) == "/>") {
      tag.self_closing = t[i] == '/';
      tag.end = i + (tag.self_closing ? 2 : 1);
      if (tag.closing && tag.self_closing) throw IoError("malformed closing XML tag");
      return;
    }
    if (tag.closing) throw IoError("attributes in a closing XML tag");
    const std::string_view key = read_name(t, i);
    i = skip_space(t, i);
    if (i >= t.size() || t[i] != '=') throw IoError(fmt::format("attribute '{}' without a value", key));
    i = skip_space(t, i + 1);
    if (i >= t.size() || (t[i] != '"' && t[i] != '\'')) throw IoError("unquoted XML attribute value");
    const std::size_t close = t.find(t[i], i + 1);
    if (close == std::string_view::npos) throw IoError("unterminated XML attribute value");
    tag.attributes.emplace_back(key, xml_unescape(t.substr(i + 1, close - i - 1)));
    i = close + 1;
  }
}

}  // namespace

const std::string* XmlTag::find(std::string_view key) const {
  for (const auto& [k, v] : attributes)
    if (k == key) return &v;
  return nullptr;
}

const std::string& XmlTag::at(std::string_view key) const {
  if (const std::string* v = find(key)) return *v;
  throw IoError(fmt::format("<{}> has no attribute '{}'", name, key));
}

std::optional<XmlTag> next_tag(std::string_view text, std::size_t pos) {
  for (;;) {
    const std::size_t lt = text.find('<', pos);
    if (lt == std::string_view::npos) return std::nullopt;
    if (lt + 1 < text.size() && (text[lt + 1] == '?' || text[lt + 1] == '!')) {
      pos = skip_special(text, lt);
      continue;
    }
    XmlTag tag;
    std::size_t i = lt + 1;
    if (i < text.size() && text[i] == '/') {
      tag.closing = true;
      ++i;
    }
    tag.name = read_name(text, i);
    read_attributes(text, i, tag);
    return tag;
  }
}

std::string xml_escape(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (const char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::uint64_t parse_count(std::string_view s, std::string_view what) {
  std::uint64_t v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || s.empty())
    throw IoError(fmt::format("{} is not a non-negative integer: '{}'", what, s));
  return v;
}

}  // namespace particula::io::detail
