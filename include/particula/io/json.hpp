// A minimal JSON writer for summary.json and the case-file JSON Schema, and lookup helpers for tests.
#pragma once

#include <concepts>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace particula::io {

/// Verbatim JSON text stored as a value (e.g. a default of any type, formatted by the caller).
struct JsonRaw {
  std::string text;
};

/// A JSON object whose keys keep their insertion order. Setting an existing key replaces
/// its value in place. Doubles are written in their shortest round-trip form (io/number.hpp);
/// NaN and infinities (which JSON cannot represent) are written as null.
class JsonObject {
 public:
  JsonObject& set(std::string_view key, double value) { return put(key, value); }
  JsonObject& set(std::string_view key, bool value) { return put(key, value); }
  JsonObject& set(std::string_view key, std::string value) { return put(key, std::move(value)); }
  JsonObject& set(std::string_view key, std::string_view value) { return put(key, std::string(value)); }
  JsonObject& set(std::string_view key, const char* value) { return put(key, std::string(value)); }
  JsonObject& set(std::string_view key, std::vector<double> value) { return put(key, std::move(value)); }
  JsonObject& set(std::string_view key, std::vector<std::string> value) { return put(key, std::move(value)); }
  JsonObject& set(std::string_view key, JsonRaw value) { return put(key, std::move(value)); }
  JsonObject& set(std::string_view key, JsonObject value) {
    return put(key, std::make_shared<const JsonObject>(std::move(value)));
  }
  /// An array of objects (one per line when indented).
  JsonObject& set(std::string_view key, const std::vector<JsonObject>& value);
  /// Any integer type other than bool, stored as int64 (unsigned values above INT64_MAX wrap).
  template <std::integral T>
  requires(!std::same_as<T, bool>) JsonObject& set(std::string_view key, T value) {
    return put(key, static_cast<std::int64_t>(value));
  }

  bool contains(std::string_view key) const;
  std::size_t size() const { return entries_.size(); }

  /// The JSON text. indent > 0: one member per line, nested objects indented; indent <= 0:
  /// one line. No trailing newline.
  std::string dump(int indent = 2) const;

 private:
  using ObjectList = std::vector<std::shared_ptr<const JsonObject>>;
  using Value = std::variant<double, std::int64_t, bool, std::string, std::vector<double>, std::vector<std::string>,
                             JsonRaw, std::shared_ptr<const JsonObject>, ObjectList>;
  JsonObject& put(std::string_view key, Value value);
  void dump_to(std::string& out, int indent, int depth) const;

  std::vector<std::pair<std::string, Value>> entries_;
};

/// JSON string literal for `s` (quotes included), escaping '"', '\\' and control characters.
std::string json_escape(std::string_view s);

/// A double as JSON: its shortest round-trip text, null when not finite.
std::string json_number(double v);

/// The number after the first `"key":` in JSON text (NaN for null). Throws std::runtime_error
/// when the key is absent or its value is neither a number nor null. Meant for tests.
double json_number_field(const std::string& text, const std::string& key);

/// The members of the object after the first `"key":` whose values are numbers (null as NaN),
/// in their order, e.g. the guard counters of summary.json whatever their names. Members of
/// other types are skipped; nested objects are not entered. Throws std::runtime_error when the
/// key is absent or its value is not an object.
std::vector<std::pair<std::string, double>> json_object_numbers(const std::string& text, const std::string& key);

}  // namespace particula::io
