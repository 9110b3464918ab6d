// The vocabulary the case-file schema's table (schema.cpp) is written in: defaults, ranges,
// bindings of a key to a Case member, and one builder per kind of row. Included by schema.cpp
// only.
#pragma once

#include <algorithm>
#include <functional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "particula/case/schema.hpp"

namespace particula::schema_rows {

// ---------------------------------------------------------------------------------------------
// Defaults.

/// What a row says about being optional: a default value, required, or one of a group.
struct Def {
  Need need = Need::Default;
  Value value;
  std::string doc;
  std::string group;
  std::function<Value(std::size_t)> per_index;
};

inline Def required() { return {Need::Required, {}, {}, {}, {}}; }
inline Def def(Value v, std::string doc = {}) { return {Need::Default, std::move(v), std::move(doc), {}, {}}; }
inline Def one_of(std::string group) { return {Need::OneOf, {}, {}, std::move(group), {}}; }
/// A default that depends on the element index of an array of tables.
inline Def per_index(std::function<Value(std::size_t)> f, std::string doc) {
  return {Need::Default, f(0), std::move(doc), {}, std::move(f)};
}

// ---------------------------------------------------------------------------------------------
// Ranges.

inline Range any() { return {}; }
inline Range gt(real lo) { return {lo, std::nullopt, true, false}; }
inline Range ge(real lo) { return {lo, std::nullopt, false, false}; }
inline Range closed(real lo, real hi) { return {lo, hi, false, false}; }
inline Range open(real lo, real hi) { return {lo, hi, true, true}; }
inline Range open_closed(real lo, real hi) { return {lo, hi, true, false}; }

// ---------------------------------------------------------------------------------------------
// Bindings: how a checked Value is stored into a Case member and read back.

/// Converts a checked Value to the C++ type of a Case member.
template <class M>
M from_value(const Value& v) {
  if constexpr (std::is_same_v<M, bool>) {
    return std::get<bool>(v);
  } else if constexpr (std::is_integral_v<M>) {
    return static_cast<M>(std::get<std::int64_t>(v));  // range-checked by the loader
  } else {
    return std::get<M>(v);  // real, std::string, Vec2
  }
}

/// Converts a Case member back to a Value.
template <class M>
Value to_value(const M& m) {
  if constexpr (std::is_same_v<M, bool>) {
    return m;
  } else if constexpr (std::is_integral_v<M>) {
    return static_cast<std::int64_t>(m);
  } else {
    return m;
  }
}

/// A plain member of Case.
template <class M>
Binding field(M Case::*m) {
  return {[m](Case& c, std::size_t, const Value& v) { c.*m = from_value<M>(v); },
          [m](const Case& c, std::size_t) -> std::optional<Value> { return to_value(c.*m); }};
}

/// A member of element `index` of an array of tables stored as std::vector<E> in Case.
template <class E, class M>
Binding member(std::vector<E> Case::*array, M E::*m) {
  return {[array, m](Case& c, std::size_t i, const Value& v) { (c.*array).at(i).*m = from_value<M>(v); },
          [array, m](const Case& c, std::size_t i) -> std::optional<Value> {
            return to_value((c.*array).at(i).*m);
          }};
}

/// An enum member of Case whose enumerators are listed in the same order as `choices`.
template <class E>
Binding enum_field(E Case::*m, std::vector<std::string> choices) {
  return {[m, choices](Case& c, std::size_t, const Value& v) {
            const auto it = std::find(choices.begin(), choices.end(), std::get<std::string>(v));
            c.*m = static_cast<E>(it - choices.begin());  // the loader checked membership
          },
          [m, choices](const Case& c, std::size_t) -> std::optional<Value> {
            return choices.at(static_cast<std::size_t>(c.*m));
          }};
}

/// An enum member of element `index` of an array of tables (enumerators in the order of `choices`).
template <class E, class M>
Binding enum_member(std::vector<E> Case::*array, M E::*m, std::vector<std::string> choices) {
  return {[array, m, choices](Case& c, std::size_t i, const Value& v) {
            const auto it = std::find(choices.begin(), choices.end(), std::get<std::string>(v));
            (c.*array).at(i).*m = static_cast<M>(it - choices.begin());  // the loader checked membership
          },
          [array, m, choices](const Case& c, std::size_t i) -> std::optional<Value> {
            return choices.at(static_cast<std::size_t>((c.*array).at(i).*m));
          }};
}

/// body[].schedule: rows [t, vx, vy, omega] <-> MotionKnot; an empty schedule is not written back.
inline Binding motion_schedule() {
  return {[](Case& c, std::size_t i, const Value& v) {
            std::vector<MotionKnot>& knots = c.bodies.at(i).schedule;
            knots.clear();
            for (const Real4& r : std::get<std::vector<Real4>>(v))
              knots.push_back({r[0], {r[1], r[2]}, r[3]});
          },
          [](const Case& c, std::size_t i) -> std::optional<Value> {
            const std::vector<MotionKnot>& knots = c.bodies.at(i).schedule;
            if (knots.empty()) return std::nullopt;
            std::vector<Real4> rows;
            for (const MotionKnot& k : knots) rows.push_back({k.t, k.velocity.x, k.velocity.y, k.omega});
            return rows;
          }};
}

/// body[].holes; a polygon without holes does not write the key back.
inline Binding polygon_holes() {
  return {[](Case& c, std::size_t i, const Value& v) {
            c.bodies.at(i).holes = std::get<std::vector<std::vector<Vec2>>>(v);
          },
          [](const Case& c, std::size_t i) -> std::optional<Value> {
            const auto& holes = c.bodies.at(i).holes;
            if (holes.empty()) return std::nullopt;
            return holes;
          }};
}

/// A pair of bool members written as one [x, y] key.
inline Binding pair_field(bool Case::*x, bool Case::*y) {
  return {[x, y](Case& c, std::size_t, const Value& v) {
            c.*x = std::get<Bool2>(v)[0];
            c.*y = std::get<Bool2>(v)[1];
          },
          [x, y](const Case& c, std::size_t) -> std::optional<Value> {
            return Bool2{c.*x, c.*y};
          }};
}

/// fluid.mu: stored as nu = mu / rho0 (fluid.rho0 is applied first) and written back as fluid.nu.
inline Binding dynamic_viscosity() {
  return {[](Case& c, std::size_t, const Value& v) { c.nu = std::get<real>(v) / c.rho0; },
          [](const Case&, std::size_t) -> std::optional<Value> { return std::nullopt; }};
}

// ---------------------------------------------------------------------------------------------
// Row builders, one per value type.

inline KeySpec row(std::string key, ValueType type, std::string unit, Def d, Range r, std::string meaning,
            Binding b) {
  KeySpec s;
  s.key = std::move(key);
  s.type = type;
  s.unit = std::move(unit);
  s.need = d.need;
  s.default_value = std::move(d.value);
  s.default_for = std::move(d.per_index);
  s.default_doc = std::move(d.doc);
  s.group = std::move(d.group);
  s.range = r;
  s.meaning = std::move(meaning);
  s.bind = std::move(b);
  return s;
}

inline KeySpec real_key(std::string key, std::string unit, Def d, Range r, std::string meaning, Binding b) {
  if (const auto* i = std::get_if<std::int64_t>(&d.value)) d.value = static_cast<real>(*i);
  return row(std::move(key), ValueType::Real, std::move(unit), std::move(d), r, std::move(meaning),
             std::move(b));
}

inline KeySpec int_key(std::string key, Def d, Range r, std::string meaning, Binding b) {
  return row(std::move(key), ValueType::Int, "-", std::move(d), r, std::move(meaning), std::move(b));
}

inline KeySpec bool_key(std::string key, Def d, std::string meaning, Binding b) {
  return row(std::move(key), ValueType::Bool, "", std::move(d), any(), std::move(meaning), std::move(b));
}

/// A vec2 key; `r` restricts each component.
inline KeySpec vec2_key(std::string key, std::string unit, Def d, std::string meaning, Binding b, Range r = any()) {
  return row(std::move(key), ValueType::Vec2, std::move(unit), std::move(d), r, std::move(meaning),
             std::move(b));
}

/// A list of at least `min_points` points [x, y].
inline KeySpec vec2_list_key(std::string key, std::string unit, Def d, std::size_t min_points, std::string meaning,
                      Binding b) {
  KeySpec s = row(std::move(key), ValueType::Vec2List, std::move(unit), std::move(d), any(),
                  std::move(meaning), std::move(b));
  s.min_items = min_points;
  return s;
}

/// A table of at least `min_rows` rows of four reals named `columns`; `unit` lists the four units.
inline KeySpec real4_table_key(std::string key, std::string unit, Def d, std::vector<std::string> columns,
                        std::size_t min_rows, std::string meaning, Binding b) {
  KeySpec s = row(std::move(key), ValueType::Real4Table, std::move(unit), std::move(d), any(),
                  std::move(meaning), std::move(b));
  s.columns = std::move(columns);
  s.min_items = min_rows;
  return s;
}

inline KeySpec bool2_key(std::string key, Def d, std::string meaning, Binding b) {
  return row(std::move(key), ValueType::Bool2, "", std::move(d), any(), std::move(meaning), std::move(b));
}

/// A string key; a `name` (identifier) must match [A-Za-z0-9_-]+; `unique` within its array.
inline KeySpec string_key(std::string key, Def d, std::string meaning, Binding b, bool name = false,
                   bool unique = false) {
  KeySpec s =
      row(std::move(key), ValueType::String, "", std::move(d), any(), std::move(meaning), std::move(b));
  s.identifier = name;
  s.unique = unique;
  return s;
}

/// A choice stored in an enum member whose enumerators follow the order of `choices`.
template <class E>
KeySpec choice_key(std::string key, std::vector<std::string> choices, Def d, std::string meaning,
                   E Case::*m) {
  KeySpec s = row(std::move(key), ValueType::Choice, "", std::move(d), any(), std::move(meaning),
                  enum_field(m, choices));
  s.choices = std::move(choices);
  return s;
}

/// A choice stored in an enum member of an array element (enumerators in the order of `choices`).
template <class E, class M>
KeySpec choice_member(std::string key, std::vector<std::string> choices, Def d, std::string meaning,
                      std::vector<E> Case::*array, M E::*m) {
  KeySpec s = row(std::move(key), ValueType::Choice, "", std::move(d), any(), std::move(meaning),
                  enum_member(array, m, choices));
  s.choices = std::move(choices);
  return s;
}

/// The row `s`, used only where the choice member `key` of the same element is one of `values`.
inline KeySpec used_when(KeySpec s, std::string key, std::vector<std::string> values) {
  s.used_when = UsedWhen{std::move(key), std::move(values)};
  return s;
}

inline Value wall_name(std::size_t k) { return "wall" + std::to_string(k); }
inline Value body_name(std::size_t k) { return "body" + std::to_string(k); }
inline Value inlet_name(std::size_t k) { return "inlet" + std::to_string(k); }
inline Value outlet_name(std::size_t k) { return "outlet" + std::to_string(k); }

}  // namespace particula::schema_rows
