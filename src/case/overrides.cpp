// --set key=value overrides, applied to the parsed TOML document before it is checked.
//
// Keys are dotted schema keys; an array of tables is addressed by index ("probe.0.points").
// Values are TOML values; string and choice keys also take a bare word ("morris").
#include <fmt/format.h>

#include <algorithm>
#include <optional>

#include "internal.hpp"

namespace particula::case_detail {
namespace {

/// One step of an override key: a table key, or an array of tables with an element index.
struct Step {
  std::string name;
  std::optional<std::size_t> index;
};

/// A parsed override key.
struct Target {
  std::vector<Step> steps;
  std::string schema;    // "probe[].points"
  std::string concrete;  // "probe[0].points"
};

[[noreturn]] void fail(const std::string& key, const std::string& message) {
  throw CaseError(std::string(kOverrideSource), 0, key, message);
}

std::string trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string_view::npos) return "";
  return std::string(s.substr(b, s.find_last_not_of(" \t") - b + 1));
}

bool all_digits(const std::string& s) {
  return !s.empty() && s.size() <= 9 &&
         std::all_of(s.begin(), s.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
}

/// Parses "probe.0.points" into steps and checks that it names a schema key.
Target parse_key(const std::string& text) {
  const std::vector<std::string> parts = split_dots(text);
  Target t;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (!plain_component(parts[i])) fail(text, "malformed key (letters, digits, '_' and '-' between dots)");
    const std::string dot = t.schema.empty() ? "" : ".";
    const std::string schema = t.schema + dot + parts[i];
    if (is_array_section(schema)) {
      if (i + 1 >= parts.size() || !all_digits(parts[i + 1]))
        fail(text,
             fmt::format("[[{0}]] is an array of tables: write {0}.<index>.<key>, e.g. {0}.0.name", schema));
      const std::size_t index = std::stoul(parts[++i]);
      t.steps.push_back({parts[i - 1], index});
      t.schema = schema + "[]";
      t.concrete += dot + fmt::format("{}[{}]", parts[i - 1], index);
    } else {
      t.steps.push_back({parts[i], std::nullopt});
      t.schema = schema;
      t.concrete += dot + parts[i];
    }
  }
  if (!find_key(t.schema)) fail(t.concrete, unknown_key_message(t.concrete));
  return t;
}

/// Parses the value as TOML ("value = <text>"); a bare word for a string or choice is quoted.
toml::table parse_value(const std::string& text, const KeySpec& spec, const std::string& key) {
  std::string toml_text = text;
  const bool stringy = spec.type == ValueType::String || spec.type == ValueType::Choice;
  if (stringy && !text.starts_with('"') && !text.starts_with('\''))
    toml_text = format_toml_value(Value{text});
  toml::table doc;
  try {
    doc = toml::parse("value = " + toml_text, std::string(kOverrideSource));
  } catch (const toml::parse_error& e) {
    fail(key, fmt::format("cannot read value '{}' as TOML: {}", text, e.description()));
  }
  if (doc.size() != 1 || !doc.contains("value")) fail(key, fmt::format("malformed value '{}'", text));
  return doc;
}

/// The table that holds the target key, creating missing plain tables on the way.
toml::table& parent_table(toml::table& root, const Target& t) {
  toml::table* table = &root;
  std::string where;
  for (std::size_t i = 0; i + 1 < t.steps.size(); ++i) {
    const Step& s = t.steps[i];
    where += (where.empty() ? "" : ".") + s.name;
    toml::node* node = table->get(s.name);
    if (s.index) {
      const auto* a = node ? node->as_array() : nullptr;
      const std::size_t n = a ? a->size() : 0;
      if (*s.index >= n)
        fail(t.concrete, fmt::format("no element {} in [[{}]]: the case has {} of them", *s.index, where, n));
      node = node->as_array()->get(*s.index);
      where += fmt::format("[{}]", *s.index);
    } else if (!node) {
      node = &table->emplace<toml::table>(s.name).first->second;
    }
    if (!node->is_table()) fail(t.concrete, fmt::format("'{}' in the case file is not a table", where));
    table = node->as_table();
  }
  return *table;
}

/// Applies one "key=value" override.
void apply_one(toml::table& root, const std::string& text, LoadContext& ctx) {
  const auto eq = text.find('=');
  if (eq == std::string::npos) fail("", fmt::format("malformed override '{}': expected key=value", text));
  const std::string key = trim(std::string_view(text).substr(0, eq));
  const std::string value = trim(std::string_view(text).substr(eq + 1));
  if (key.empty()) fail("", fmt::format("malformed override '{}': the key is empty", text));
  const Target t = parse_key(key);
  toml::table doc = parse_value(value, *find_key(t.schema), t.concrete);
  parent_table(root, t).insert_or_assign(t.steps.back().name, std::move(*doc.get("value")));
  ctx.overridden.insert(t.concrete);
}

}  // namespace

void apply_overrides(toml::table& root, const std::vector<std::string>& overrides, LoadContext& ctx) {
  for (const std::string& o : overrides) apply_one(root, o, ctx);
}

}  // namespace particula::case_detail
