// The simulation box and its periodic images (minimum-image convention), in D dimensions:
// DomainOf<2> (`Domain`, the 2D solver's) and DomainOf<3> (`Domain3`).
#pragma once

#include <cmath>

#include "particula/core/types3.hpp"

namespace particula {

template <int D>
struct DomainOf;

/// The minimum image of one component d of a separation along an axis of length L.
PARTICULA_HD real minimum_image(real d, real L) { return d - L * std::nearbyint(d / L); }
/// A coordinate x mapped into [lo, lo + L).
PARTICULA_HD real wrap_into(real x, real lo, real L) {
  x -= L * std::floor((x - lo) / L);
  return x >= lo + L ? x - L : x;  // guard the round-off case x == hi
}

template <>
struct DomainOf<2> {
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

  /// Whether x lies beyond a closed (not periodic) side of the box by more than `margin`.
  PARTICULA_HD bool outside_closed(Vec2 x, real margin) const {
    if (!periodic_x && (x.x < lo.x - margin || x.x > hi.x + margin)) return true;
    if (!periodic_y && (x.y < lo.y - margin || x.y > hi.y + margin)) return true;
    return false;
  }
};
using Domain = DomainOf<2>;

template <>
struct DomainOf<3> {
  Vec3 lo, hi;
  bool periodic_x = false, periodic_y = false, periodic_z = false;

  PARTICULA_HD Vec3 size() const { return hi - lo; }

  /// r_i - r_j with the minimum-image convention along periodic axes.
  PARTICULA_HD Vec3 separation(Vec3 xi, Vec3 xj) const {
    Vec3 d = xi - xj;
    if (periodic_x) d.x = minimum_image(d.x, hi.x - lo.x);
    if (periodic_y) d.y = minimum_image(d.y, hi.y - lo.y);
    if (periodic_z) d.z = minimum_image(d.z, hi.z - lo.z);
    return d;
  }

  /// Maps a position back into [lo, hi) along periodic axes.
  PARTICULA_HD Vec3 wrap(Vec3 x) const {
    if (periodic_x) x.x = wrap_into(x.x, lo.x, hi.x - lo.x);
    if (periodic_y) x.y = wrap_into(x.y, lo.y, hi.y - lo.y);
    if (periodic_z) x.z = wrap_into(x.z, lo.z, hi.z - lo.z);
    return x;
  }

  /// Whether x lies beyond a closed (not periodic) side of the box by more than `margin`.
  PARTICULA_HD bool outside_closed(Vec3 x, real margin) const {
    if (!periodic_x && (x.x < lo.x - margin || x.x > hi.x + margin)) return true;
    if (!periodic_y && (x.y < lo.y - margin || x.y > hi.y + margin)) return true;
    if (!periodic_z && (x.z < lo.z - margin || x.z > hi.z + margin)) return true;
    return false;
  }
};
using Domain3 = DomainOf<3>;

}  // namespace particula
