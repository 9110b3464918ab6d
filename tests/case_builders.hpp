// Programmatic cases for tests (no case file involved): a closed box, a periodic channel, and a
// circular body to put in them.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "particula/case/case.hpp"

namespace particula::cases {

/// Closed box [0,W]x[0,H] with four fixed walls listed counter-clockwise.
inline Case closed_box(real W, real H, real d0) {
  Case c = default_case();
  c.name = "box";
  c.domain_min = {0, 0};
  c.domain_max = {W, H};
  c.d0 = d0;
  c.rho0 = 1000;
  c.nu = 1e-6;
  c.c = 1;
  c.t_end = 1;
  c.output_interval = 1;
  c.walls = {{"bottom", {0, 0}, {W, 0}, {}},
             {"right", {W, 0}, {W, H}, {}},
             {"top", {W, H}, {0, H}, {}},
             {"left", {0, H}, {0, 0}, {}}};
  return c;
}

/// Start-up channel between plates y = 0 and y = L, periodic in x, `n_across` particles
/// across. The upper plate moves at `v_top` (Couette); `force` drives Poiseuille flow.
/// Parameters of reference/README.md.
inline Case startup_channel(int n_across, real v_top, real force) {
  Case c = default_case();
  const real L = 1e-3;
  const real d0 = L / n_across;
  c.name = "channel";
  c.domain_min = {0, 0};
  c.domain_max = {8 * d0, L};
  c.periodic_x = true;
  c.d0 = d0;
  c.rho0 = 1000;
  c.nu = 1e-6;
  c.c = 2.5e-4;  // 20x the peak speed 1.25e-5 m/s
  c.body_force = {force, 0};
  c.t_end = 1.5;
  c.output_interval = 0.1;
  c.shifting_beta = 0.01;
  c.walls = {{"bottom", {0, 0}, {8 * d0, 0}, {}}, {"top", {8 * d0, L}, {0, L}, {v_top, 0}}};
  return c;
}

/// A circular body of density 2000 (the robustness cases' cylinders).
inline BodySpec circle_body(const char* name, Vec2 center, real radius, BodyMotion motion = BodyMotion::Free) {
  BodySpec b;
  b.name = name;
  b.shape = BodyShape::Circle;
  b.center = center;
  b.radius = radius;
  b.density = 2000;
  b.motion = motion;
  return b;
}

/// A closed container whose fixed walls run counter-clockwise through `corners` (the fluid
/// fills the polygon), in the bounding box of the corners; water-like fluid under gravity.
inline Case walled_polygon(const std::vector<Vec2>& corners, real d0) {
  Case c = closed_box(1, 1, d0);
  c.name = "container";
  c.walls.clear();
  c.domain_min = c.domain_max = corners.front();
  for (std::size_t k = 0; k < corners.size(); ++k) {
    const Vec2 a = corners[k], b = corners[(k + 1) % corners.size()];
    c.walls.push_back({"side" + std::to_string(k), a, b, {}});
    c.domain_min = {std::min(c.domain_min.x, a.x), std::min(c.domain_min.y, a.y)};
    c.domain_max = {std::max(c.domain_max.x, a.x), std::max(c.domain_max.y, a.y)};
  }
  c.gravity = {0, -9.81};
  return c;
}

}  // namespace particula::cases
