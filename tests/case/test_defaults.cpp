// One source for every default: the schema's rows (src/case/schema.cpp). default_case() holds
// them, physics_params() carries them into PhysicsParams, and the structs of case.hpp and
// physics_params.hpp write none of their own (their members are value-initialised with `{}`).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "particula/case/schema.hpp"
#include "particula/scene/scene.hpp"
#include "particula/solver/physics_params.hpp"

using namespace particula;

namespace {

const std::filesystem::path kRoot = PARTICULA_SOURCE_DIR;

/// The rows of plain keys (not members of arrays of tables) that have a default.
std::vector<const KeySpec*> plain_default_rows() {
  std::vector<const KeySpec*> rows;
  for (const KeySpec& s : case_schema())
    if (!s.in_array() && s.need == Need::Default) rows.push_back(&s);
  return rows;
}

std::string text(const Value& v) { return format_toml_value(v); }

/// The value-initialised value of a key of type `t` (a Choice: its first choice, the first
/// enumerator).
Value zero_of(const KeySpec& s) {
  switch (s.type) {
    case ValueType::Real:
      return real{};
    case ValueType::Int:
      return std::int64_t{};
    case ValueType::Bool:
      return false;
    case ValueType::String:
      return std::string{};
    case ValueType::Vec2:
      return Vec2{};
    case ValueType::Choice:
      return s.choices.at(0);
    case ValueType::Bool2:
      return Bool2{};
    case ValueType::Vec2List:
      return std::vector<Vec2>{};
    case ValueType::Real4Table:
      return std::vector<Real4>{};
    case ValueType::Vec2Loops:
      return std::vector<std::vector<Vec2>>{};
  }
  return real{};
}

using Read = std::function<Value(const PhysicsParams&)>;

/// The schema keys PhysicsParams carries, each read back from it as the key's value (lengths in
/// d0 divided by p.d0; choices from the flags they set).
std::map<std::string, Read> physics_keys() {
  auto pick = [](bool flag, const char* yes, const char* no) { return Value{std::string(flag ? yes : no)}; };
  return {
      {"resolution.h_over_d0", [](const PhysicsParams& p) { return Value{p.h / p.d0}; }},
      {"fluid.rho0", [](const PhysicsParams& p) { return Value{p.rho0}; }},
      {"fluid.p0", [](const PhysicsParams& p) { return Value{p.p0}; }},
      {"fluid.gravity", [](const PhysicsParams& p) { return Value{p.gravity}; }},
      {"fluid.gravity_in_fluid", [](const PhysicsParams& p) { return Value{p.gravity_in_fluid}; }},
      {"fluid.body_force", [](const PhysicsParams& p) { return Value{p.body_force}; }},
      {"time.cfl", [](const PhysicsParams& p) { return Value{p.cfl}; }},
      {"time.dt_max", [](const PhysicsParams& p) { return Value{p.dt_max}; }},
      {"numerics.laplacian",
       [=](const PhysicsParams& p) { return pick(p.fatehi_manzari, "fatehi_manzari", "morris"); }},
      {"numerics.boundary",
       [=](const PhysicsParams& p) { return pick(p.single_layer, "single_layer", "dummy"); }},
      {"numerics.normals",
       [=](const PhysicsParams& p) { return pick(p.kernel_normals, "kernel", "analytic"); }},
      {"numerics.force", [=](const PhysicsParams& p) { return pick(p.momentum_force, "momentum", "paper"); }},
      {"numerics.gradient",
       [=](const PhysicsParams& p) { return pick(p.zeroth_order_gradient, "consistent", "paper"); }},
      {"numerics.rhie_chow_factor", [](const PhysicsParams& p) { return Value{p.rhie_chow_factor}; }},
      {"numerics.shifting_beta", [](const PhysicsParams& p) { return Value{p.shifting_beta}; }},
      {"numerics.odd_even_damping", [](const PhysicsParams& p) { return Value{p.odd_even_damping}; }},
      {"numerics.surface_guard", [](const PhysicsParams& p) { return Value{p.surface_guard}; }},
      {"numerics.film_gap", [](const PhysicsParams& p) { return Value{p.film_gap}; }},
      {"numerics.load_band_motion", [](const PhysicsParams& p) { return Value{p.load_band_motion / p.d0}; }},
      {"numerics.wall_pressure_sweeps",
       [](const PhysicsParams& p) { return Value{std::int64_t{p.wall_pressure_sweeps}}; }},
      {"guard.rho_min_ratio", [](const PhysicsParams& p) { return Value{p.rho_min_ratio}; }},
      {"guard.rho_max_ratio", [](const PhysicsParams& p) { return Value{p.rho_max_ratio}; }},
      {"collision.model",
       [=](const PhysicsParams& p) {
         return pick(p.collision_model == ContactModel::SpringDashpot, "spring_dashpot", "paper");
       }},
      {"collision.stiffness", [](const PhysicsParams& p) { return Value{p.collision_stiffness}; }},
      {"collision.range", [](const PhysicsParams& p) { return Value{p.collision_range}; }},
      {"collision.restitution", [](const PhysicsParams& p) { return Value{p.collision_restitution}; }},
      {"collision.friction", [](const PhysicsParams& p) { return Value{p.collision_friction}; }},
      {"collision.max_overlap", [](const PhysicsParams& p) { return Value{p.collision_max_overlap}; }},
      {"collision.lubrication", [](const PhysicsParams& p) { return Value{p.collision_lubrication}; }},
      {"collision.lubrication_range",
       [](const PhysicsParams& p) { return Value{p.collision_lubrication_range}; }},
  };
}

/// The keys with a default that PhysicsParams does not carry (the run, the scene and the outputs
/// read them from the Case).
const std::set<std::string> kNotPhysics = {"description",
                                           "domain.periodic",
                                           "time.max_steps",
                                           "initial.perturbation",
                                           "initial.seed",
                                           "initial.flow",
                                           "initial.amplitude",
                                           "initial.hydrostatic",
                                           "output.snapshots",
                                           "output.snapshot_interval",
                                           "output.checkpoint_interval",
                                           "validation.exact",
                                           "analysis.reference_velocity",
                                           "analysis.reference_length"};

// ---------------------------------------------------------------------------------------------
// The scan of the headers.

std::string read(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// `source` without its // and /* */ comments.
std::string without_comments(const std::string& source) {
  std::string out;
  for (std::size_t i = 0; i < source.size(); ++i) {
    if (source.compare(i, 2, "//") == 0) {
      i = source.find('\n', i);
      if (i == std::string::npos) break;
    } else if (source.compare(i, 2, "/*") == 0) {
      i = source.find("*/", i);
      if (i == std::string::npos) break;
      ++i;
      continue;
    }
    out += source[i];
  }
  return out;
}

std::string trimmed(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\n\r");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\n\r") - a + 1);
}

/// Whether the statement text before a `{` opens a function body or a nested type (whose members
/// are scanned on their own) rather than a brace initialiser.
bool opens_body(const std::string& before) {
  const std::string t = trimmed(before);
  if (t.empty() || t.back() == ')') return true;
  for (const char* w : {"const", "noexcept", "override", "struct ", "enum ", "class ", "union "})
    if (t.ends_with(w) || t.starts_with(w)) return true;
  return false;
}

/// The data members of the struct whose body starts after `open` (the index of its `{`) that
/// write a value: an initialiser with `=`, or braces that are not empty.
std::vector<std::string> written_defaults(const std::string& src, std::size_t open) {
  std::vector<std::string> found;
  std::string statement;
  for (std::size_t i = open + 1; i < src.size() && src[i] != '}'; ++i) {
    if (src[i] == ';') {
      if (statement.find('=') != std::string::npos && statement.find('(') == std::string::npos)
        found.push_back(trimmed(statement));
      statement.clear();
    } else if (src[i] == '{') {
      int depth = 1;
      std::size_t j = i + 1;
      for (; j < src.size() && depth > 0; ++j) depth += src[j] == '{' ? 1 : src[j] == '}' ? -1 : 0;
      const std::string inside = src.substr(i + 1, j - i - 2);
      if (opens_body(statement)) {
        statement.clear();  // a function body or nested type ends the statement
      } else {
        if (!trimmed(inside).empty()) found.push_back(trimmed(statement) + "{" + trimmed(inside) + "}");
        statement += "{}";
      }
      i = j - 1;
    } else {
      statement += src[i];
    }
  }
  return found;
}

/// "Struct: member" for every data member of every struct in `source` that writes a value, and
/// the names of the structs scanned.
std::vector<std::string> written_defaults_in(const std::string& source, std::vector<std::string>* structs) {
  const std::string src = without_comments(source);
  std::vector<std::string> found;
  for (std::size_t at = src.find("struct "); at != std::string::npos; at = src.find("struct ", at + 1)) {
    const std::size_t brace = src.find_first_of("{;", at);
    if (brace == std::string::npos || src[brace] != '{') continue;  // a declaration
    const std::string name = trimmed(src.substr(at + 7, brace - at - 7));
    if (structs) structs->push_back(name);
    for (const std::string& m : written_defaults(src, brace)) found.push_back(name + ": " + m);
  }
  return found;
}

}  // namespace

TEST(Defaults, DefaultCaseHoldsEverySchemaDefault) {
  const Case d = default_case();
  const std::vector<const KeySpec*> rows = plain_default_rows();
  EXPECT_GT(rows.size(), 40u);
  for (const KeySpec* s : rows) {
    SCOPED_TRACE(s->key);
    const std::optional<Value> v = s->bind.get(d, 0);
    ASSERT_TRUE(v);
    EXPECT_EQ(text(*v), text(s->default_value));
  }
}

TEST(Defaults, ValueInitialisedCaseHoldsNoDefaults) {
  // A default written into case.hpp (`real cfl = 0.5;`) shows in a value-initialised Case.
  const Case zero{};
  int checked = 0;
  for (const KeySpec& s : case_schema()) {
    if (s.in_array()) continue;
    const std::optional<Value> v = s.bind.get(zero, 0);
    if (!v) continue;  // fluid.mu: stored as fluid.nu
    SCOPED_TRACE(s.key);
    EXPECT_EQ(text(*v), text(zero_of(s)));
    ++checked;
  }
  EXPECT_GT(checked, 50);
}

TEST(Defaults, ArrayElementsValueInitialiseToTheSchemaDefaults) {
  // The loader applies every row's default to each element; code that builds an element by hand
  // (WallSpec w; BodySpec b;) gets the value-initialised members, so the schema's defaults of the
  // array members must be those (a non-zero one would need a schema-made element, as default_case).
  Case fresh = default_case();
  fresh.walls.resize(1);
  fresh.probes.resize(1);
  fresh.bodies.resize(1);
  fresh.inlets.resize(1);
  fresh.outlets.resize(1);
  fresh.bodies[0].motion = BodyMotion::Prescribed;  // so that body[].schedule is used
  for (const KeySpec& s : case_schema()) {
    if (!s.in_array() || s.need != Need::Default || s.default_for) continue;
    SCOPED_TRACE(s.key);
    if (s.key == "body[].motion") {
      EXPECT_EQ(text(s.default_value), "\"free\"");
      EXPECT_EQ(BodySpec{}.motion, BodyMotion::Free);
      continue;
    }
    if (s.key == "body[].holes") {  // a polygon without holes; no holes are not written back
      Case polygon = fresh;
      polygon.bodies[0].shape = BodyShape::Polygon;
      ASSERT_TRUE(s.used_for(polygon, 0));
      EXPECT_FALSE(s.bind.get(polygon, 0));
      EXPECT_TRUE(std::get<std::vector<std::vector<Vec2>>>(s.default_value).empty());
      continue;
    }
    ASSERT_TRUE(s.used_for(fresh, 0));
    const std::optional<Value> v = s.bind.get(fresh, 0);
    if (s.key == "body[].schedule") {  // an empty schedule is not written back
      EXPECT_FALSE(v);
      EXPECT_TRUE(std::get<std::vector<Real4>>(s.default_value).empty());
      continue;
    }
    ASSERT_TRUE(v);
    EXPECT_EQ(text(*v), text(s.default_value));
  }
}

TEST(Defaults, PhysicsParamsCarryTheCaseDefaults) {
  Case d = default_case();
  d.d0 = 1;  // required; 1 keeps the lengths in d0 exact
  const PhysicsParams p = physics_params(d);
  const std::map<std::string, Read> carried = physics_keys();
  for (const auto& [key, read_back] : carried) {
    SCOPED_TRACE(key);
    const KeySpec* s = find_key(key);
    ASSERT_TRUE(s);
    ASSERT_EQ(s->need, Need::Default);
    EXPECT_EQ(text(read_back(p)), text(s->default_value));
  }
  // Every key with a default is either carried or listed as not physics: a new key is placed.
  for (const KeySpec* s : plain_default_rows())
    EXPECT_TRUE(carried.contains(s->key) || kNotPhysics.contains(s->key)) << s->key;
  EXPECT_EQ(p.reorder_interval, kReorderInterval);
  EXPECT_FALSE(p.cuda);
}

TEST(Defaults, HeadersWriteNoDefaults) {
  // The scan finds a written default (checked on text that has them) ...
  const std::string planted = R"(struct P {
  real a{};  // a = 1 in a comment is not code
  real b = 0.5;
  bool c{true};
  Vec2 f() const { const Vec2 t = g(); return t; }
  int d = 2;
  struct Inner { int e = 3; };
};)";
  EXPECT_EQ(
      written_defaults_in(planted, nullptr),
      (std::vector<std::string>{"P: real b = 0.5", "P: bool c{true}", "P: int d = 2", "Inner: int e = 3"}));
  // ... and none in the structs of the case and of the physics parameters.
  for (const char* header :
       {"include/particula/case/case.hpp", "include/particula/solver/physics_params.hpp"}) {
    SCOPED_TRACE(header);
    const std::string source = read(kRoot / header);
    ASSERT_FALSE(source.empty());
    std::vector<std::string> structs;
    EXPECT_EQ(written_defaults_in(source, &structs), std::vector<std::string>{})
        << "defaults belong in the schema (src/case/schema.cpp); members here are value-initialised, `{}`";
    EXPECT_GE(structs.size(), 3u);
  }
}
