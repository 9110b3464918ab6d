// The case-file schema: ONE table in code that lists every key a case file may contain, with
// its type, SI unit, default, allowed range, meaning and how it is stored in `Case`.
//
// Everything else is derived from this table: the defaults of a Case (default_case(); Case itself
// writes none), the loader (type, range and required checks, unknown-key detection with
// suggestions, --set overrides), the resolved case written back to a run directory, the generated
// reference docs/case-files.md and the JSON Schema for editors (`particula schema --json`,
// src/case/json_schema.cpp).
//
// Adding a key = one row in src/case/schema.cpp (its binding is the assignment into Case).
// Adding an array of tables (e.g. [[body]]) = one row in the section table plus its member rows.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "particula/case/case.hpp"
#include "particula/core/types.hpp"

namespace particula {

/// The value types a key can have.
enum class ValueType {
  Real,        // floating point number; a TOML integer is accepted (1 -> 1.0)
  Int,         // TOML integer only; a float is a type error
  Bool,        // true / false
  String,      // any string (optionally restricted to names, see KeySpec::identifier)
  Vec2,        // array of two reals [x, y]
  Choice,      // a string among KeySpec::choices
  Bool2,       // array of two bools [x, y]
  Vec2List,    // array of points [[x0, y0], [x1, y1], ...] (at least KeySpec::min_items)
  Real4Table,  // array of rows of four reals [[a, b, c, d], ...] (columns: KeySpec::columns)
  Vec2Loops,   // array of closed point lists [[[x0, y0], [x1, y1], [x2, y2], ...], ...] (each >= 3 points)
};

using Bool2 = std::array<bool, 2>;
/// One row of a Real4Table value.
using Real4 = std::array<real, 4>;

/// A checked value of a key. Real -> real, Int -> int64, Bool -> bool, String and Choice ->
/// string, Vec2 -> Vec2, Bool2 -> Bool2, Vec2List -> vector<Vec2>, Real4Table -> vector<Real4>,
/// Vec2Loops -> vector<vector<Vec2>>.
using Value = std::variant<real, std::int64_t, bool, std::string, Vec2, Bool2, std::vector<Vec2>, std::vector<Real4>,
                           std::vector<std::vector<Vec2>>>;

/// An allowed interval for Real and Int keys, and for each component of a Vec2 key (both bounds
/// optional, each inclusive or not). Non-finite numbers are never contained.
struct Range {
  std::optional<real> lo, hi;
  bool lo_open = false, hi_open = false;

  bool contains(real x) const;
  /// "> 0", ">= 0", "[1.5, 4]", "(0, 1]", or "" when unrestricted.
  std::string text() const;
};

/// Whether a key must be given.
enum class Need {
  Default,   // optional, with a default value
  Required,  // must be given
  OneOf,     // exactly one key of its `group` must be given
};

/// A member of an array of tables that is used only for some values of a choice member of the
/// same element: body[].radius only for body[].shape circle and half_disc. Where it is used the
/// row's `need` applies (Required: must be given); elsewhere it must not be given (a CaseError
/// from the cross checks) and it is not written to the resolved case.
struct UsedWhen {
  std::string key;                  // the deciding Choice row, earlier in the table ("body[].shape")
  std::vector<std::string> values;  // its values for which this key is used
};

/// How a checked value is stored into a Case and read back (for the resolved case).
/// `index` is the element of an array of tables (0 for plain keys). `get` returns nullopt for
/// keys that are not written back (e.g. fluid.mu, which is stored and written as fluid.nu).
struct Binding {
  std::function<void(Case&, std::size_t index, const Value&)> set;
  std::function<std::optional<Value>(const Case&, std::size_t index)> get;
};

/// One row of the schema.
struct KeySpec {
  std::string key;  // dotted key; members of arrays of tables as "wall[].from"
  ValueType type = ValueType::Real;
  std::string unit;  // SI unit, "-" for dimensionless, "" for non-numeric keys
  Need need = Need::Default;
  Value default_value;                            // when need == Default
  std::function<Value(std::size_t)> default_for;  // optional: default depending on the index
  std::string default_doc;                        // optional doc text for the default
  std::string group;                              // when need == OneOf: shared group label
  Range range;                                    // Real and Int keys, each component of Vec2
  std::size_t min_items = 0;                      // Vec2List and Real4Table: fewest points / rows
  std::vector<std::string> columns;               // Real4Table: names of the four columns
  std::optional<UsedWhen> used_when;              // members used only for some choices
  std::vector<std::string> choices;               // Choice keys
  bool identifier = false;                        // String: must match [A-Za-z0-9_-]+, at most kMaxNameLength
  bool unique = false;                            // array member: distinct across elements
  std::string meaning;                            // one sentence
  Binding bind;

  /// The section the key lives in: "" for top-level keys, "fluid", or "wall" for "wall[].from".
  std::string section() const;
  /// The key's own name within its section ("from" for "wall[].from").
  std::string leaf() const;
  /// True for members of an array of tables.
  bool in_array() const;
  /// The default for element `index` (uses default_for when set).
  Value default_at(std::size_t index) const;
  /// False if `used_when` excludes element `index` of `c` (its deciding choice is elsewhere).
  bool used_for(const Case& c, std::size_t index) const;
};

/// A section of the case file: a table ([fluid]) or an array of tables ([[wall]]).
struct SectionSpec {
  std::string name;  // "" for the top-level keys
  bool array = false;
  std::string meaning;
  std::function<std::size_t(const Case&)> size;    // arrays only: elements in a Case
  std::function<void(Case&, std::size_t)> resize;  // arrays only
};

/// Longest name (case, wall, probe and body names): names become file and directory names
/// (`runs/<name>`, `probe_<name>.csv`) and appear in columns and messages.
inline constexpr std::size_t kMaxNameLength = 64;

/// All keys, in the order they are applied to a Case and written back.
const std::vector<KeySpec>& case_schema();
/// All sections, in documentation and output order (top level first).
const std::vector<SectionSpec>& case_sections();
/// The row for a schema key ("fluid.nu", "wall[].from"), or nullptr.
const KeySpec* find_key(std::string_view key);
/// The section named `name` ("fluid", "wall"), or nullptr.
const SectionSpec* find_section(std::string_view name);

/// Short type name for messages and docs: "real", "integer", "vec2", "vec2 list", ...
std::string type_name(ValueType type);
/// A value written as TOML (reals with round-trip precision, strings quoted and escaped).
std::string format_toml_value(const Value& value);
/// The default of a row as documented: "required", "one of fluid.nu / fluid.mu", or the value;
/// rows with `used_when` add where they are used ("required for shape circle, half_disc").
std::string default_text(const KeySpec& spec);

/// The case-file schema as a JSON Schema (draft-07; types, units, defaults, ranges, choices,
/// required keys, arrays of tables), for editors: `particula schema --json` prints it.
std::string case_json_schema();

/// The case-file reference (markdown, one table per section) generated from the schema.
/// docs/case-files.md is this text; a test fails when they differ.
std::string case_reference_markdown();

}  // namespace particula
