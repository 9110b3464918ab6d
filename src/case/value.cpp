// Values of case-file keys: TOML node -> checked Value, Value -> TOML text, ranges and names.
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>

#include "internal.hpp"

namespace particula {

// ---------------------------------------------------------------------------------------------
// Range.

bool Range::contains(real x) const {
  if (!std::isfinite(x)) return false;
  if (lo && (lo_open ? !(x > *lo) : !(x >= *lo))) return false;
  if (hi && (hi_open ? !(x < *hi) : !(x <= *hi))) return false;
  return true;
}

std::string Range::text() const {
  if (lo && hi) return fmt::format("{}{}, {}{}", lo_open ? '(' : '[', *lo, *hi, hi_open ? ')' : ']');
  if (lo) return fmt::format("{} {}", lo_open ? ">" : ">=", *lo);
  if (hi) return fmt::format("{} {}", hi_open ? "<" : "<=", *hi);
  return "";
}

// ---------------------------------------------------------------------------------------------
// Names and formatting.

std::string type_name(ValueType type) {
  switch (type) {
    case ValueType::Real:
      return "real";
    case ValueType::Int:
      return "integer";
    case ValueType::Bool:
      return "bool";
    case ValueType::String:
      return "string";
    case ValueType::Vec2:
      return "vec2";
    case ValueType::Choice:
      return "choice";
    case ValueType::Bool2:
      return "bool2";
  }
  return "?";
}

namespace {

/// A real as TOML with round-trip precision; always recognisable as a float ("1000.0").
std::string format_real(real x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  std::string s = fmt::format("{}", x);  // shortest representation that reads back exactly
  if (s.find_first_of(".eE") == std::string::npos) s += ".0";
  return s;
}

/// A TOML basic string with all necessary escapes.
std::string quote(const std::string& s) {
  std::string out = "\"";
  for (const char ch : s) {
    const auto u = static_cast<unsigned char>(ch);
    switch (ch) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        if (u < 0x20 || u == 0x7f)
          out += fmt::format("\\u{:04X}", u);
        else
          out += ch;
    }
  }
  return out + "\"";
}

}  // namespace

std::string format_toml_value(const Value& value) {
  struct Visitor {
    std::string operator()(real x) const { return format_real(x); }
    std::string operator()(std::int64_t i) const { return std::to_string(i); }
    std::string operator()(bool b) const { return b ? "true" : "false"; }
    std::string operator()(const std::string& s) const { return quote(s); }
    std::string operator()(const Vec2& v) const {
      return fmt::format("[{}, {}]", format_real(v.x), format_real(v.y));
    }
    std::string operator()(const Bool2& b) const {
      return fmt::format("[{}, {}]", b[0] ? "true" : "false", b[1] ? "true" : "false");
    }
  };
  return std::visit(Visitor{}, value);
}

std::string default_text(const KeySpec& spec) {
  switch (spec.need) {
    case Need::Required:
      return "required";
    case Need::OneOf: {
      std::string keys;
      for (const KeySpec& s : case_schema())
        if (s.need == Need::OneOf && s.group == spec.group) keys += (keys.empty() ? "" : " / ") + s.key;
      return "one of " + keys;
    }
    case Need::Default:
      break;
  }
  return spec.default_doc.empty() ? format_toml_value(spec.default_value) : spec.default_doc;
}

namespace case_detail {

// ---------------------------------------------------------------------------------------------
// Key helpers.

std::string concrete_key(const std::string& schema_key, std::size_t index) {
  const auto p = schema_key.find("[]");
  if (p == std::string::npos) return schema_key;
  return schema_key.substr(0, p) + "[" + std::to_string(index) + "]" + schema_key.substr(p + 2);
}

std::string schema_form(const std::string& concrete) {
  std::string out;
  for (std::size_t i = 0; i < concrete.size(); ++i) {
    out += concrete[i];
    if (concrete[i] != '[') continue;
    std::size_t j = i + 1;
    while (j < concrete.size() && std::isdigit(static_cast<unsigned char>(concrete[j]))) ++j;
    if (j > i + 1 && j < concrete.size() && concrete[j] == ']') i = j - 1;  // drop the digits
  }
  return out;
}

std::vector<std::string> split_dots(std::string_view s) {
  std::vector<std::string> parts(1);
  for (const char ch : s) {
    if (ch == '.')
      parts.emplace_back();
    else
      parts.back() += ch;
  }
  return parts;
}

bool plain_component(std::string_view name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char ch) {
    return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-';
  });
}

bool is_table_section(std::string_view prefix) {
  const std::string p = std::string(prefix) + ".";
  return std::any_of(case_schema().begin(), case_schema().end(),
                     [&](const KeySpec& s) { return s.key.starts_with(p); });
}

bool is_array_section(std::string_view prefix) {
  const std::string p = std::string(prefix) + "[].";
  return std::any_of(case_schema().begin(), case_schema().end(),
                     [&](const KeySpec& s) { return s.key.starts_with(p); });
}

// ---------------------------------------------------------------------------------------------
// TOML node -> checked Value.

namespace {

/// "a string", "an integer", ... for messages.
std::string describe(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a float";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::array:
      return fmt::format("an array of {} elements", n.as_array()->size());
    case toml::node_type::table:
      return "a table";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    default:
      return "nothing";
  }
}

/// What a key of this type must look like, for messages.
std::string expected(const KeySpec& spec) {
  switch (spec.type) {
    case ValueType::Real:
      return "a real number";
    case ValueType::Int:
      return "an integer";
    case ValueType::Bool:
      return "true or false";
    case ValueType::String:
      return "a string";
    case ValueType::Choice:
      return "a string (choice)";
    case ValueType::Vec2:
      return "an array of two real numbers [x, y]";
    case ValueType::Bool2:
      return "an array of two booleans [x, y]";
  }
  return "?";
}

std::string wrong_type(const toml::node& n, const KeySpec& spec) {
  return fmt::format("wrong type: expected {}, got {}", expected(spec), describe(n));
}

/// " m" after a range, nothing for dimensionless or unit-less keys.
std::string unit_suffix(const KeySpec& spec) {
  return spec.unit.empty() || spec.unit == "-" ? "" : " " + spec.unit;
}

std::string out_of_range(const std::string& value, const KeySpec& spec, bool finite) {
  const Range& r = spec.range;
  std::string must = r.text();
  if (r.lo && r.hi) must = "in " + must;
  if (!finite) must = must.empty() ? "a finite number" : "a finite number " + must;
  return fmt::format("value {} is out of range: must be {}{}", value, must, unit_suffix(spec));
}

/// A TOML integer or float as a real.
bool as_real(const toml::node& n, real& x) {
  if (const auto* f = n.as_floating_point())
    x = f->get();
  else if (const auto* i = n.as_integer())
    x = static_cast<real>(i->get());
  else
    return false;
  return true;
}

std::string convert_real(const toml::node& n, const KeySpec& spec, Value& out) {
  real x = 0;
  if (!as_real(n, x)) return wrong_type(n, spec);
  if (!spec.range.contains(x)) return out_of_range(fmt::format("{}", x), spec, std::isfinite(x));
  out = x;
  return "";
}

std::string convert_int(const toml::node& n, const KeySpec& spec, Value& out) {
  const auto* i = n.as_integer();
  if (!i) return wrong_type(n, spec);
  if (!spec.range.contains(static_cast<real>(i->get())))
    return out_of_range(std::to_string(i->get()), spec, true);
  out = i->get();
  return "";
}

std::string convert_vec2(const toml::node& n, const KeySpec& spec, Value& out) {
  const auto* a = n.as_array();
  Vec2 v;
  if (!a || a->size() != 2 || !as_real(*a->get(0), v.x) || !as_real(*a->get(1), v.y))
    return wrong_type(n, spec);
  if (!std::isfinite(v.x) || !std::isfinite(v.y))
    return out_of_range(fmt::format("[{}, {}]", v.x, v.y), spec, false);
  out = v;
  return "";
}

std::string convert_bool2(const toml::node& n, const KeySpec& spec, Value& out) {
  const auto* a = n.as_array();
  if (!a || a->size() != 2 || !a->get(0)->is_boolean() || !a->get(1)->is_boolean())
    return wrong_type(n, spec);
  out = Bool2{a->get(0)->as_boolean()->get(), a->get(1)->as_boolean()->get()};
  return "";
}

std::string convert_string(const toml::node& n, const KeySpec& spec, Value& out) {
  const auto* s = n.as_string();
  if (!s) return wrong_type(n, spec);
  const std::string& text = s->get();
  if (spec.type == ValueType::Choice &&
      std::find(spec.choices.begin(), spec.choices.end(), text) == spec.choices.end())
    return fmt::format("'{}' is not a valid choice: expected one of {}", text, fmt::join(spec.choices, ", "));
  if (spec.identifier && !plain_component(text))
    return fmt::format("'{}' is not a valid name: use only letters, digits, '_' and '-'", text);
  out = text;
  return "";
}

}  // namespace

std::string convert_node(const toml::node& node, const KeySpec& spec, Value& out) {
  switch (spec.type) {
    case ValueType::Real:
      return convert_real(node, spec, out);
    case ValueType::Int:
      return convert_int(node, spec, out);
    case ValueType::Bool:
      if (!node.is_boolean()) return wrong_type(node, spec);
      out = node.as_boolean()->get();
      return "";
    case ValueType::String:
    case ValueType::Choice:
      return convert_string(node, spec, out);
    case ValueType::Vec2:
      return convert_vec2(node, spec, out);
    case ValueType::Bool2:
      return convert_bool2(node, spec, out);
  }
  return "unsupported type";
}

}  // namespace case_detail
}  // namespace particula
