// The simulation box and its periodic images (minimum-image convention).
#pragma once

#include <cmath>

#include "particula/core/types.hpp"

namespace particula {

struct Domain {
  Vec2 lo, hi;
  bool periodic_x = false, periodic_y = false;

  PARTICULA_HD Vec2 size() const { return hi - lo; }

  /// r_i - r_j with the minimum-image convention along periodic axes.
  PARTICULA_HD Vec2 separation(Vec2 xi, Vec2 xj) const {
    Vec2 d = xi - xj;
    if (periodic_x) {
      const real L = hi.x - lo.x;
      d.x -= L * std::nearbyint(d.x / L);
    }
    if (periodic_y) {
      const real L = hi.y - lo.y;
      d.y -= L * std::nearbyint(d.y / L);
    }
    return d;
  }

  /// Maps a position back into [lo, hi) along periodic axes.
  PARTICULA_HD Vec2 wrap(Vec2 x) const {
    if (periodic_x) {
      const real L = hi.x - lo.x;
      x.x -= L * std::floor((x.x - lo.x) / L);
      if (x.x >= hi.x) x.x -= L;  // guard the round-off case x == hi
    }
    if (periodic_y) {
      const real L = hi.y - lo.y;
      x.y -= L * std::floor((x.y - lo.y) / L);
      if (x.y >= hi.y) x.y -= L;
    }
    return x;
  }
};

}  // namespace particula
