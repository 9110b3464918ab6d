// Values of case-file keys: TOML node -> checked Value, Value -> TOML text, ranges and names.
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>
#include <vector>

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
    case ValueType::Vec2List:
      return "vec2 list";
    case ValueType::Real4Table:
      return "real4 table";
    case ValueType::Vec2Loops:
      return "vec2 loops";
  }
  return "?";
}

namespace {

/// Lists (vec2 list, real4 table) longer than this are written one item per line.
constexpr std::size_t kItemsOnOneLine = 4;

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
    std::string operator()(const std::vector<Vec2>& points) const {
      std::vector<std::string> items;
      for (const Vec2& p : points) items.push_back((*this)(p));
      return list(items);
    }
    std::string operator()(const std::vector<std::vector<Vec2>>& loops) const {
      std::vector<std::string> items;
      for (const auto& loop : loops) {
        std::vector<std::string> points;
        for (const Vec2& p : loop) points.push_back((*this)(p));
        items.push_back(fmt::format("[{}]", fmt::join(points, ", ")));
      }
      if (items.empty()) return "[]";
      return fmt::format("[\n  {},\n]", fmt::join(items, ",\n  "));  // one loop per line
    }
    std::string operator()(const std::vector<Real4>& rows) const {
      std::vector<std::string> items;
      for (const Real4& r : rows)
        items.push_back(fmt::format("[{}, {}, {}, {}]", format_real(r[0]), format_real(r[1]),
                                    format_real(r[2]), format_real(r[3])));
      return list(items);
    }
    /// A TOML array of `items`: on one line when short, else one item per line.
    static std::string list(const std::vector<std::string>& items) {
      if (items.size() <= kItemsOnOneLine) return fmt::format("[{}]", fmt::join(items, ", "));
      return fmt::format("[\n  {},\n]", fmt::join(items, ",\n  "));
    }
  };
  return std::visit(Visitor{}, value);
}

std::string default_text(const KeySpec& spec) {
  std::string where;  // "shape circle, half_disc" for members used by some choices only
  if (spec.used_when)
    where = fmt::format("{} {}", spec.used_when->key.substr(spec.used_when->key.rfind('.') + 1),
                        fmt::join(spec.used_when->values, ", "));
  switch (spec.need) {
    case Need::Required:
      return where.empty() ? "required" : "required for " + where;
    case Need::OneOf: {
      std::string keys;
      for (const KeySpec& s : case_schema())
        if (s.need == Need::OneOf && s.group == spec.group) keys += (keys.empty() ? "" : " / ") + s.key;
      return "one of " + keys;
    }
    case Need::Default:
      break;
  }
  const std::string text =
      spec.default_doc.empty() ? format_toml_value(spec.default_value) : spec.default_doc;
  return where.empty() ? text : fmt::format("{}; only for {}", text, where);
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
    case ValueType::Vec2List:
      return fmt::format("an array of at least {} points [x, y]", spec.min_items);
    case ValueType::Real4Table:
      return fmt::format("an array of at least {} rows [{}] of real numbers", spec.min_items,
                         fmt::join(spec.columns, ", "));
    case ValueType::Vec2Loops:
      return "an array of loops, each an array of at least 3 points [x, y]";
  }
  return "?";
}

std::string wrong_type(const toml::node& n, const KeySpec& spec) {
  return fmt::format("wrong type: expected {}, got {}", expected(spec), describe(n));
}

/// 1-based line of a node in its document (0 if unknown).
int line_of(const toml::node& n) { return static_cast<int>(n.source().begin.line); }

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

/// An array of exactly `n` reals (TOML integers or floats) into `x`.
bool as_reals(const toml::node& node, real* x, std::size_t n) {
  const auto* a = node.as_array();
  if (!a || a->size() != n) return false;
  for (std::size_t i = 0; i < n; ++i)
    if (!as_real(*a->get(i), x[i])) return false;
  return true;
}

std::string convert_vec2(const toml::node& n, const KeySpec& spec, Value& out) {
  real x[2];
  if (!as_reals(n, x, 2)) return wrong_type(n, spec);
  const Vec2 v{x[0], x[1]};
  const bool finite = std::isfinite(v.x) && std::isfinite(v.y);
  if (!finite || !spec.range.contains(v.x) || !spec.range.contains(v.y)) {
    const std::string value = fmt::format("[{}, {}]", v.x, v.y);
    if (spec.range.text().empty()) return out_of_range(value, spec, finite);
    return fmt::format("value {} is out of range: each component must be {}{}{}", value,
                       finite ? "" : "a finite number ", spec.range.text(), unit_suffix(spec));
  }
  out = v;
  return "";
}

/// The elements of a Vec2List or Real4Table value: an array of at least spec.min_items items.
const toml::array* list_of(const toml::node& n, const KeySpec& spec, std::string& problem) {
  const auto* a = n.as_array();
  if (!a || (!a->empty() && !a->get(0)->is_array()))  // e.g. one point [x, y] instead of a list
    problem = wrong_type(n, spec);
  else if (a->size() < spec.min_items)
    problem = fmt::format("too few {}: expected {}, got {}",
                          spec.type == ValueType::Vec2List ? "points" : "rows", expected(spec), a->size());
  return problem.empty() ? a : nullptr;
}

std::string convert_vec2_list(const toml::node& n, const KeySpec& spec, Value& out, int& line) {
  std::string problem;
  const toml::array* a = list_of(n, spec, problem);
  if (!a) return problem;
  std::vector<Vec2> points;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node& e = *a->get(i);
    real x[2];
    if (!as_reals(e, x, 2)) {
      line = line_of(e);
      return fmt::format("wrong type: point [{}] must be [x, y] of two real numbers, got {}", i, describe(e));
    }
    if (!std::isfinite(x[0]) || !std::isfinite(x[1])) {
      line = line_of(e);
      return fmt::format("point [{}] = [{}, {}] is out of range: must be finite", i, x[0], x[1]);
    }
    points.push_back({x[0], x[1]});
  }
  out = std::move(points);
  return "";
}

std::string convert_real4_table(const toml::node& n, const KeySpec& spec, Value& out, int& line) {
  std::string problem;
  const toml::array* a = list_of(n, spec, problem);
  if (!a) return problem;
  std::vector<Real4> rows;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node& e = *a->get(i);
    Real4 r{};
    if (!as_reals(e, r.data(), 4)) {
      line = line_of(e);
      return fmt::format("wrong type: row [{}] must be [{}] of four real numbers, got {}", i,
                         fmt::join(spec.columns, ", "), describe(e));
    }
    if (!std::all_of(r.begin(), r.end(), [](real x) { return std::isfinite(x); })) {
      line = line_of(e);
      return fmt::format("row [{}] = [{}] is out of range: must be finite", i, fmt::join(r, ", "));
    }
    rows.push_back(r);
  }
  out = std::move(rows);
  return "";
}

/// An array of loops, each a Vec2List of at least 3 points (a problem names the loop and point).
std::string convert_vec2_loops(const toml::node& n, const KeySpec& spec, Value& out, int& line) {
  const auto* a = n.as_array();
  if (!a || (!a->empty() && !a->get(0)->is_array())) return wrong_type(n, spec);
  KeySpec loop_spec = spec;
  loop_spec.type = ValueType::Vec2List;
  loop_spec.min_items = 3;
  std::vector<std::vector<Vec2>> loops;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node& e = *a->get(i);
    Value points;
    const std::string problem = convert_vec2_list(e, loop_spec, points, line);
    if (!problem.empty()) {
      if (line == 0) line = line_of(e);
      return fmt::format("loop [{}]: {}", i, problem);
    }
    loops.push_back(std::get<std::vector<Vec2>>(points));
  }
  out = std::move(loops);
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
  if (spec.identifier && text.size() > kMaxNameLength)
    return fmt::format("'{}...' ({} characters) is too long: a name becomes part of file names and columns, "
                       "at most {} characters",
                       text.substr(0, 16), text.size(), kMaxNameLength);
  if (spec.identifier && !plain_component(text))
    return fmt::format("'{}' is not a valid name: use only letters, digits, '_' and '-'", text);
  out = text;
  return "";
}

std::string convert_scalar(const toml::node& node, const KeySpec& spec, Value& out) {
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
    case ValueType::Vec2List:
    case ValueType::Real4Table:
    case ValueType::Vec2Loops:
      break;
  }
  return "unsupported type";
}

}  // namespace

std::string convert_node(const toml::node& node, const KeySpec& spec, Value& out, int* element_line) {
  int line = 0;
  std::string problem;
  if (spec.type == ValueType::Vec2List)
    problem = convert_vec2_list(node, spec, out, line);
  else if (spec.type == ValueType::Real4Table)
    problem = convert_real4_table(node, spec, out, line);
  else if (spec.type == ValueType::Vec2Loops)
    problem = convert_vec2_loops(node, spec, out, line);
  else
    return convert_scalar(node, spec, out);
  if (element_line) *element_line = line;
  return problem;
}

}  // namespace case_detail
}  // namespace particula
