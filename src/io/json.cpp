// JSON writer and number lookup.
#include "particula/io/json.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "particula/io/number.hpp"

namespace particula::io {
namespace {

/// Appends a newline plus indentation for `depth` levels (nothing on one line).
void line_break(std::string& out, int indent, int depth) {
  if (indent <= 0) return;
  out += '\n';
  out.append(static_cast<std::size_t>(indent * depth), ' ');
}

}  // namespace

std::string json_number(double v) { return std::isfinite(v) ? shortest(v) : "null"; }

JsonObject& JsonObject::set(std::string_view key, const std::vector<JsonObject>& value) {
  ObjectList list;
  for (const JsonObject& o : value) list.push_back(std::make_shared<const JsonObject>(o));
  return put(key, std::move(list));
}

JsonObject& JsonObject::put(std::string_view key, Value value) {
  for (auto& [k, v] : entries_) {
    if (k == key) {
      v = std::move(value);
      return *this;
    }
  }
  entries_.emplace_back(std::string(key), std::move(value));
  return *this;
}

bool JsonObject::contains(std::string_view key) const {
  for (const auto& e : entries_)
    if (e.first == key) return true;
  return false;
}

void JsonObject::dump_to(std::string& out, int indent, int depth) const {
  if (entries_.empty()) {
    out += "{}";
    return;
  }
  out += '{';
  for (std::size_t i = 0; i < entries_.size(); ++i) {
    if (i > 0) out += ',';
    line_break(out, indent, depth + 1);
    out += json_escape(entries_[i].first);
    out += ": ";
    const Value& v = entries_[i].second;
    if (const auto* d = std::get_if<double>(&v))
      out += json_number(*d);
    else if (const auto* n = std::get_if<std::int64_t>(&v))
      out += fmt::format("{}", *n);
    else if (const auto* b = std::get_if<bool>(&v))
      out += *b ? "true" : "false";
    else if (const auto* s = std::get_if<std::string>(&v))
      out += json_escape(*s);
    else if (const auto* a = std::get_if<std::vector<double>>(&v)) {
      out += '[';
      for (std::size_t j = 0; j < a->size(); ++j) {
        if (j > 0) out += ", ";
        out += json_number((*a)[j]);
      }
      out += ']';
    } else if (const auto* l = std::get_if<std::vector<std::string>>(&v)) {
      out += '[';
      for (std::size_t j = 0; j < l->size(); ++j) out += (j > 0 ? ", " : "") + json_escape((*l)[j]);
      out += ']';
    } else if (const auto* r = std::get_if<JsonRaw>(&v)) {
      out += r->text;
    } else if (const auto* objects = std::get_if<ObjectList>(&v)) {
      out += '[';
      for (std::size_t j = 0; j < objects->size(); ++j) {
        if (j > 0) out += ',';
        line_break(out, indent, depth + 2);
        (*objects)[j]->dump_to(out, indent, depth + 2);
      }
      if (!objects->empty()) line_break(out, indent, depth + 1);
      out += ']';
    } else {
      std::get<std::shared_ptr<const JsonObject>>(v)->dump_to(out, indent, depth + 1);
    }
  }
  line_break(out, indent, depth);
  out += '}';
}

std::string JsonObject::dump(int indent) const {
  std::string out;
  dump_to(out, indent, 0);
  return out;
}

std::string json_escape(std::string_view s) {
  std::string out = "\"";
  for (const char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\b':
        out += "\\b";
        break;
      case '\f':
        out += "\\f";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20)
          out += fmt::format("\\u{:04x}", static_cast<unsigned>(c));
        else
          out += c;  // UTF-8 bytes pass through unchanged
    }
  }
  out += '"';
  return out;
}

double json_number_field(const std::string& text, const std::string& key) {
  const std::string quoted = json_escape(key);
  for (std::size_t at = text.find(quoted); at != std::string::npos; at = text.find(quoted, at + 1)) {
    std::size_t i = text.find_first_not_of(" \t\r\n", at + quoted.size());
    if (i == std::string::npos || text[i] != ':') continue;  // a string value, not a key
    i = text.find_first_not_of(" \t\r\n", i + 1);
    if (i == std::string::npos) break;
    if (text.compare(i, 4, "null") == 0) return std::numeric_limits<double>::quiet_NaN();
    double v = 0;
    const auto [end, ec] = std::from_chars(text.data() + i, text.data() + text.size(), v);
    if (ec != std::errc()) throw std::runtime_error("JSON field '" + key + "' is not a number");
    return v;
  }
  throw std::runtime_error("JSON has no field '" + key + "'");
}

std::vector<std::pair<std::string, double>> json_object_numbers(const std::string& text, const std::string& key) {
  const std::string quoted = json_escape(key);
  std::size_t i = std::string::npos;
  for (std::size_t at = text.find(quoted); at != std::string::npos; at = text.find(quoted, at + 1)) {
    const std::size_t colon = text.find_first_not_of(" \t\r\n", at + quoted.size());
    if (colon != std::string::npos && text[colon] == ':') {
      i = text.find_first_not_of(" \t\r\n", colon + 1);
      break;
    }
  }
  if (i == std::string::npos) throw std::runtime_error("JSON has no field '" + key + "'");
  if (text[i] != '{') throw std::runtime_error("JSON field '" + key + "' is not an object");
  std::vector<std::pair<std::string, double>> out;
  int depth = 0;
  for (++i; i < text.size(); ++i) {
    const char ch = text[i];
    if (ch == '{' || ch == '[') ++depth;
    if (ch == '}' || ch == ']') {
      if (depth-- == 0) return out;
      continue;
    }
    if (ch != '"' || depth != 0) continue;
    // a member name (names written by JsonObject need no unescaping here: counters are plain words)
    const std::size_t close = text.find('"', i + 1);
    if (close == std::string::npos) break;
    const std::string name = text.substr(i + 1, close - i - 1);
    std::size_t v = text.find_first_not_of(" \t\r\n", close + 1);
    if (v == std::string::npos || text[v] != ':') {
      i = close;
      continue;
    }
    v = text.find_first_not_of(" \t\r\n", v + 1);
    if (v == std::string::npos) break;
    double value = 0;
    if (text.compare(v, 4, "null") == 0) {
      out.emplace_back(name, std::numeric_limits<double>::quiet_NaN());
    } else if (std::from_chars(text.data() + v, text.data() + text.size(), value).ec == std::errc()) {
      out.emplace_back(name, value);
    }
    i = close;
    if (text[v] == '"') {  // a string value: skipped whole, or its text would be read as a name
      i = text.find('"', v + 1);
      if (i == std::string::npos) break;
    }
  }
  throw std::runtime_error("JSON field '" + key + "': unterminated object");
}

}  // namespace particula::io
