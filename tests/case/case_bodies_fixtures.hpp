// Shared fixtures of the [[body]] case-file tests (test_case_bodies*.cpp).
#pragma once

#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>
#include "particula/case/load.hpp"
#include "particula/case/schema.hpp"

namespace case_bodies_test {

using namespace particula;

inline const std::string kFile = "cases/bodies.toml";

/// A closed 0.02 x 0.06 m box at d0 = 1e-4 m (a body needs 1e-3 m across), no bodies.
inline const std::string kBase = R"(name = "bodies"

[domain]
min = [0.0, 0.0]
max = [0.02, 0.06]

[resolution]
d0 = 1e-4

[fluid]
mu = 0.01
c = 0.5
gravity = [0, -9.81]

[time]
end = 1.0

[output]
interval = 0.01
)";

/// One body of each shape and motion, and the collision table.
inline const std::string kBodies = R"(
[collision]
stiffness = 1.5e6
range = 3e-4

[[body]]
name = "disc"
shape = "circle"
center = [0.01, 0.01]
radius = 0.00125
density = 1250
velocity = [0.001, -0.002]
omega = 0.5

[[body]]
shape = "ellipse"
center = [0.01, 0.054]
semi_axes = [0.002, 0.001]
angle = 0.25
density = 1100

[[body]]
name = "paddle"
shape = "polygon"
vertices = [[0.014, 0.02], [0.018, 0.02], [0.018, 0.024], [0.014, 0.024]]
motion = "prescribed"
schedule = [
  [0, 0, 0, 0],
  [0.5, 0.001, 0, 2],
  [1.5, 0, -0.001, 0],
]

[[body]]
name = "obstacle"
shape = "half_disc"
center = [0, 0.04]
radius = 0.005
motion = "fixed"
)";

inline const std::string kCase = kBase + kBodies;

/// `text` with the first occurrence of `from` replaced by `to` (which must exist).
inline std::string with(std::string text, const std::string& from, const std::string& to) {
  const auto p = text.find(from);
  EXPECT_NE(p, std::string::npos) << "fixture lacks: " << from;
  if (p != std::string::npos) text.replace(p, from.size(), to);
  return text;
}

/// 1-based line of the first occurrence of `needle` in `text`.
inline int line_of(const std::string& text, const std::string& needle) {
  const auto p = text.find(needle);
  EXPECT_NE(p, std::string::npos) << needle;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(p), '\n'));
}

/// The CaseError thrown by loading `text` (a test failure if it loads or throws anything else).
CaseError error_of(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    load_case_text(text, kFile, overrides);
  } catch (const CaseError& e) {
    return e;
  }
  ADD_FAILURE() << "expected a CaseError for:\n" << text;
  return CaseError("", 0, "", "");
}

/// Asserts an error at `key`, on the line of `needle` in `text`, whose message contains `part`.
inline void expect_error(const std::string& text, const std::string& key, const std::string& needle,
                  const std::string& part) {
  const CaseError e = error_of(text);
  EXPECT_EQ(e.file(), kFile) << e.what();
  EXPECT_EQ(e.key(), key) << e.what();
  EXPECT_EQ(e.line(), line_of(text, needle)) << e.what();
  EXPECT_NE(e.message().find(part), std::string::npos) << e.what();
  EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
}

/// Asserts an error from an override: file "--set", line 0.
inline void expect_override_error(const std::string& text, const std::vector<std::string>& overrides,
                           const std::string& key, const std::string& part) {
  const CaseError e = error_of(text, overrides);
  EXPECT_EQ(e.file(), "--set") << e.what();
  EXPECT_EQ(e.line(), 0) << e.what();
  EXPECT_EQ(e.key(), key) << e.what();
  EXPECT_NE(e.message().find(part), std::string::npos) << e.what();
}

/// kBase with one [[body]] table holding `lines`.
inline std::string one_body(const std::string& lines) { return kBase + "\n[[body]]\n" + lines; }

inline Case load(const std::string& text, const std::vector<std::string>& overrides = {}) {
  return load_case_text(text, kFile, overrides);
}

inline bool same(real a, real b) { return std::memcmp(&a, &b, sizeof a) == 0; }
inline bool same(Vec2 a, Vec2 b) { return same(a.x, b.x) && same(a.y, b.y); }

/// Bodies and collision settings compared bit for bit.
inline void expect_same_bodies(const Case& a, const Case& b) {
  EXPECT_TRUE(same(a.collision_stiffness, b.collision_stiffness));
  EXPECT_TRUE(same(a.collision_range, b.collision_range));
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    SCOPED_TRACE(i);
    const BodySpec &x = a.bodies[i], &y = b.bodies[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.shape, y.shape);
    EXPECT_TRUE(same(x.center, y.center));
    EXPECT_TRUE(same(x.radius, y.radius));
    EXPECT_TRUE(same(x.semi_axes, y.semi_axes));
    ASSERT_EQ(x.vertices.size(), y.vertices.size());
    for (std::size_t k = 0; k < x.vertices.size(); ++k) EXPECT_TRUE(same(x.vertices[k], y.vertices[k])) << k;
    EXPECT_TRUE(same(x.angle, y.angle));
    EXPECT_TRUE(same(x.density, y.density));
    EXPECT_EQ(x.motion, y.motion);
    EXPECT_TRUE(same(x.velocity, y.velocity));
    EXPECT_TRUE(same(x.omega, y.omega));
    ASSERT_EQ(x.schedule.size(), y.schedule.size());
    for (std::size_t k = 0; k < x.schedule.size(); ++k) {
      EXPECT_TRUE(same(x.schedule[k].t, y.schedule[k].t)) << k;
      EXPECT_TRUE(same(x.schedule[k].velocity, y.schedule[k].velocity)) << k;
      EXPECT_TRUE(same(x.schedule[k].omega, y.schedule[k].omega)) << k;
    }
  }
}

/// The resolved text of `a` loads as `a` again and gives the same text.
inline void expect_round_trip(const Case& a) {
  const std::string text = resolved_case_toml(a);
  const Case b = load_case_text(text, "run/case.toml");
  expect_same_bodies(a, b);
  EXPECT_EQ(resolved_case_toml(b), text);
}

}  // namespace case_bodies_test
