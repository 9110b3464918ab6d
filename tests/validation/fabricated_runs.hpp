// Fabricated run directories for the tests of `particula validate`'s checks: bodies.csv written
// from closed-form trajectories, and a lookup of a check by the start of its quantity.
#pragma once

#include <cmath>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "particula/io/csv.hpp"
#include "particula/validation/validate.hpp"

namespace fabricated {

/// State of one body at one time (the columns of bodies.csv that the checks read).
struct Row {
  double x = 0, y = 0, angle = 0, vx = 0, vy = 0, omega = 0, fx = 0, fy = 0;
};

/// Writes DIR/bodies.csv with `bodies` bodies sampled every `dt` up to `t_end` from `state(t, body)`.
inline void write_bodies(const std::filesystem::path& dir, int bodies, double dt, double t_end,
                         const std::function<Row(double, int)>& state) {
  particula::io::CsvWriter csv(dir / "bodies.csv", {"time", "body", "x", "y", "angle", "vx", "vy", "omega", "fx", "fy",
                                                    "torque", "fpx", "fpy", "fvx", "fvy", "fcx", "fcy"});
  const int n = static_cast<int>(std::lround(t_end / dt));
  for (int k = 0; k <= n; ++k)
    for (int b = 0; b < bodies; ++b) {
      const double t = k * dt;
      const Row r = state(t, b);
      csv.row({t, static_cast<double>(b), r.x, r.y, r.angle, r.vx, r.vy, r.omega, r.fx, r.fy, 0, 0, 0, 0, 0, 0, 0});
    }
}

/// The check whose quantity starts with `start`.
inline const particula::ValidationCheck& find(const std::vector<particula::ValidationCheck>& checks,
                                              const std::string& start) {
  for (const auto& c : checks)
    if (c.quantity.rfind(start, 0) == 0) return c;
  throw std::runtime_error("no check starting with '" + start + "'");
}

}  // namespace fabricated
