// The case-file schema as a JSON Schema (draft-07), for editors (Even Better TOML / taplo,
// VS Code) and other tools: `particula schema --json`. Derived from the one table of
// src/case/schema.cpp, like docs/case-files.md, so it cannot drift from the loader.
//
// What JSON Schema can say is said here: types, SI units (in the description and as "x-unit"),
// defaults, ranges, choices, names, required keys, exactly-one-of groups, and the members of
// [[body]] used by some shapes or motions only (if/then/else). Cross checks (walls that meet,
// bodies inside the domain, unique names, ...) remain the loader's.
#include <fmt/format.h>

#include <cctype>
#include <algorithm>
#include <map>

#include "particula/case/schema.hpp"
#include "particula/io/json.hpp"

namespace particula {
namespace {

using io::JsonObject;
using io::JsonRaw;

// ---------------------------------------------------------------------------------------------
// Values and types.

/// A point [x, y] as JSON.
std::string json_point(Vec2 p) { return fmt::format("[{}, {}]", io::json_number(p.x), io::json_number(p.y)); }

/// A checked Value as JSON text (the "default" of a key).
std::string json_value(const Value& value) {
  struct Visitor {
    std::string operator()(real x) const { return io::json_number(x); }
    std::string operator()(std::int64_t i) const { return std::to_string(i); }
    std::string operator()(bool b) const { return b ? "true" : "false"; }
    std::string operator()(const std::string& s) const { return io::json_escape(s); }
    std::string operator()(Vec2 v) const { return json_point(v); }
    std::string operator()(const Bool2& b) const {
      return fmt::format("[{}, {}]", b[0] ? "true" : "false", b[1] ? "true" : "false");
    }
    std::string operator()(const std::vector<Vec2>& points) const {
      std::string out = "[";
      for (std::size_t i = 0; i < points.size(); ++i) out += fmt::format("{}{}", i ? ", " : "", json_point(points[i]));
      return out + "]";
    }
    std::string operator()(const std::vector<std::vector<Vec2>>& loops) const {
      std::string out = "[";
      for (std::size_t i = 0; i < loops.size(); ++i) out += (i ? ", " : "") + (*this)(loops[i]);
      return out + "]";
    }
    std::string operator()(const std::vector<Real4>& rows) const {
      std::string out = "[";
      for (std::size_t i = 0; i < rows.size(); ++i)
        out += fmt::format("{}[{}, {}, {}, {}]", i ? ", " : "", io::json_number(rows[i][0]), io::json_number(rows[i][1]),
                           io::json_number(rows[i][2]), io::json_number(rows[i][3]));
      return out + "]";
    }
  };
  return std::visit(Visitor{}, value);
}

/// {"type": "number"|"integer"} with the bounds of `r`.
JsonObject number_schema(const char* type, const Range& r) {
  JsonObject j;
  j.set("type", type);
  if (r.lo) j.set(r.lo_open ? "exclusiveMinimum" : "minimum", *r.lo);
  if (r.hi) j.set(r.hi_open ? "exclusiveMaximum" : "maximum", *r.hi);
  return j;
}

/// An array of exactly `n` items of `item`.
JsonObject fixed_array(JsonObject item, std::int64_t n) {
  JsonObject j;
  j.set("type", "array").set("items", std::move(item)).set("minItems", n).set("maxItems", n);
  return j;
}

/// The type part of a key's schema (no description or default).
JsonObject type_schema(const KeySpec& s) {
  JsonObject j;
  switch (s.type) {
    case ValueType::Real: return number_schema("number", s.range);
    case ValueType::Int: return number_schema("integer", s.range);
    case ValueType::Bool: j.set("type", "boolean"); return j;
    case ValueType::String:
      j.set("type", "string");
      if (s.identifier) j.set("pattern", "^[A-Za-z0-9_-]+$").set("maxLength", kMaxNameLength);
      return j;
    case ValueType::Choice: j.set("type", "string").set("enum", s.choices); return j;
    case ValueType::Vec2: return fixed_array(number_schema("number", s.range), 2);
    case ValueType::Bool2: return fixed_array(JsonObject().set("type", "boolean"), 2);
    case ValueType::Vec2List:
      j.set("type", "array").set("items", fixed_array(number_schema("number", s.range), 2));
      j.set("minItems", s.min_items);
      return j;
    case ValueType::Real4Table:
      j.set("type", "array").set("items", fixed_array(number_schema("number", s.range), 4));
      j.set("minItems", s.min_items);
      return j;
    case ValueType::Vec2Loops: {
      JsonObject loop;
      loop.set("type", "array").set("items", fixed_array(number_schema("number", s.range), 2)).set("minItems", 3);
      j.set("type", "array").set("items", loop);
      return j;
    }
  }
  return j;
}

/// The whole schema of one key: type, description (meaning, unit, default), unit, default.
JsonObject key_schema(const KeySpec& s) {
  JsonObject j = type_schema(s);
  std::string text = s.meaning;
  if (!s.columns.empty()) text += fmt::format(" Columns: {}.", fmt::join(s.columns, ", "));
  if (s.unit == "-")
    text += " Dimensionless.";
  else if (!s.unit.empty())
    text += fmt::format(" Unit: {}.", s.unit);
  std::string need = default_text(s);  // "required ...", "one of ..." or the default
  if (s.need == Need::Default)
    need = "Default: " + need;
  else
    need[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(need[0])));
  text += " " + need + ".";
  j.set("description", text);
  if (!s.unit.empty()) j.set("x-unit", s.unit);
  if (s.need == Need::Default && !s.default_for) j.set("default", JsonRaw{json_value(s.default_value)});
  return j;
}

// ---------------------------------------------------------------------------------------------
// Sections.

/// The keys of one section (rows whose section() is `name`), in schema order.
std::vector<const KeySpec*> section_keys(const std::string& name) {
  std::vector<const KeySpec*> keys;
  for (const KeySpec& s : case_schema())
    if (s.section() == name) keys.push_back(&s);
  return keys;
}

/// The "if shape is one of ... then (required) else (absent)" rule of a member used by some
/// choices only.
JsonObject used_when_rule(const KeySpec& s) {
  const std::string decider = s.used_when->key.substr(s.used_when->key.rfind('.') + 1);
  JsonObject cond;
  cond.set("properties", JsonObject().set(decider, JsonObject().set("enum", s.used_when->values)));
  // An absent decider takes its default (probe[].kind: "line"): the condition holds without it
  // when the default is one of the values, and fails without it otherwise.
  const KeySpec* d = find_key(s.used_when->key);
  const auto* fallback = d && d->need == Need::Default ? std::get_if<std::string>(&d->default_value) : nullptr;
  const auto& v = s.used_when->values;
  if (!fallback || std::find(v.begin(), v.end(), *fallback) == v.end())
    cond.set("required", std::vector<std::string>{decider});
  JsonObject rule;
  rule.set("if", cond);
  if (s.need == Need::Required) rule.set("then", JsonObject().set("required", std::vector<std::string>{s.leaf()}));
  rule.set("else", JsonObject().set("not", JsonObject().set("required", std::vector<std::string>{s.leaf()})));
  return rule;
}

/// An object with the keys of section `name` as properties, its required keys, its
/// exactly-one-of groups and its used-when rules. `description` is set when not empty.
JsonObject table_schema(const std::string& name, const std::string& description) {
  JsonObject properties;
  std::vector<std::string> required;
  std::map<std::string, std::vector<std::string>> groups;  // OneOf group -> its keys
  std::vector<JsonObject> rules;
  for (const KeySpec* s : section_keys(name)) {
    properties.set(s->leaf(), key_schema(*s));
    if (s->used_when)
      rules.push_back(used_when_rule(*s));
    else if (s->need == Need::Required)
      required.push_back(s->leaf());
    if (s->need == Need::OneOf) groups[s->group].push_back(s->leaf());
  }
  JsonObject j;
  j.set("type", "object");
  if (!description.empty()) j.set("description", description);
  j.set("properties", properties);
  j.set("additionalProperties", false);
  if (!required.empty()) j.set("required", required);
  for (const auto& [group, keys] : groups) {
    std::vector<JsonObject> one_of;
    for (const auto& k : keys) one_of.push_back(JsonObject().set("required", std::vector<std::string>{k}));
    rules.push_back(JsonObject().set("oneOf", one_of));
  }
  if (!rules.empty()) j.set("allOf", rules);
  return j;
}

/// Whether a table section must be given: it has a required key or an exactly-one-of group.
bool section_required(const std::string& name) {
  for (const KeySpec* s : section_keys(name))
    if (!s->used_when && (s->need == Need::Required || s->need == Need::OneOf)) return true;
  return false;
}

}  // namespace

std::string case_json_schema() {
  JsonObject properties;
  std::vector<std::string> required;
  for (const KeySpec* s : section_keys("")) properties.set(s->leaf(), key_schema(*s));
  for (const KeySpec* s : section_keys(""))
    if (s->need == Need::Required) required.push_back(s->leaf());
  for (const SectionSpec& sec : case_sections()) {
    if (sec.name.empty()) continue;
    if (sec.array) {
      JsonObject a;
      a.set("type", "array").set("description", sec.meaning).set("items", table_schema(sec.name, ""));
      properties.set(sec.name, a);
    } else {
      properties.set(sec.name, table_schema(sec.name, sec.meaning));
      if (section_required(sec.name)) required.push_back(sec.name);
    }
  }
  JsonObject schema;
  schema.set("$schema", "http://json-schema.org/draft-07/schema#");
  schema.set("title", "particula case file");
  schema.set("description",
             "A particula case file (TOML); every key with its SI unit, default and range. Generated by "
             "`particula schema --json` from the schema in src/case/schema.cpp; the reference is "
             "docs/case-files.md. The loader checks more (walls that meet, bodies inside the domain, unique "
             "names, cost limits).");
  schema.set("type", "object");
  schema.set("properties", properties);
  schema.set("additionalProperties", false);
  schema.set("required", required);
  return schema.dump() + "\n";
}

}  // namespace particula
