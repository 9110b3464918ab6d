// Open boundaries (docs/method.md, "Open boundaries"): inlets and outlets on straight
// segments of the domain's edge, with a buffer of particles outside the domain behind each.
//
// The buffer particles live in the fluid block with the kinds Inlet and Outlet. They are
// neighbours of the fluid like any particle, but they are not integrated: their fields are set
// by the boundary (a prescribed velocity at an inlet, a prescribed pressure at an outlet, the
// other fields continued from the fluid by a linear moving-least-squares fit at the point
// mirrored into the fluid), and they move only along the boundary's normal. Fluid that crosses
// an outlet line becomes an outlet buffer particle and is removed once it leaves the buffer; an
// inlet buffer particle that crosses the inlet line becomes fluid and a new one takes its place
// at the back of its column.
#pragma once

#include <cmath>
#include <cstddef>

#include "particula/core/types.hpp"

namespace particula {

/// The geometry and rules of one open boundary (a plain struct for host and device).
struct OpenZone {
  bool inlet = true;  // false: outlet
  Vec2 from;          // start of the segment
  Vec2 t;             // unit tangent from `from` to its end
  Vec2 n;             // unit inward normal (into the fluid, the tangent's left)
  real width = 0;     // length of the segment
  real depth = 0;     // L_b: depth of the buffer behind the line (layers x spacing)
  real spacing = 0;   // lattice spacing along n (the buffer's row spacing)
  real mass = 0;      // mass of a buffer particle created at an inlet
  real pressure = 0;  // outlet: P on the line (the equation of state's P: p0 + the case's pressure)
};

/// xi: the signed distance of x into the fluid from the zone's line (negative in the buffer).
PARTICULA_HD real open_depth(const OpenZone& z, Vec2 x) { return dot(z.n, x - z.from); }

/// s: the distance of x along the segment from its start.
PARTICULA_HD real open_along(const OpenZone& z, Vec2 x) { return dot(z.t, x - z.from); }

/// Whether x lies in the zone's strip beyond the line: 0 <= s <= width and xi < 0. (The strips of
/// the zones of a case do not overlap: they lie on edges of the domain, outside it.)
PARTICULA_HD bool beyond_open_line(const OpenZone& z, Vec2 x) {
  const real s = open_along(z, x);
  return open_depth(z, x) < 0 && s >= 0 && s <= z.width;
}

/// The ghost point of buffer particle x: its mirror image in the line, inside the fluid.
PARTICULA_HD Vec2 open_ghost_point(const OpenZone& z, Vec2 x) { return x - (2 * open_depth(z, x)) * z.n; }

/// The smooth start of an inlet's flow: (1 - cos(pi t / T)) / 2 until T, then 1 (T = 0: none).
PARTICULA_HD real inlet_ramp(real t, real ramp_time) {
  if (!(ramp_time > 0) || t >= ramp_time) return 1;
  if (t <= 0) return 0;
  return 0.5 * (1 - std::cos(M_PI * t / ramp_time));
}

/// The outlet buffer's pressure: the odd mirror 2 P_out - P~(x_g) of the fluid's fitted pressure
/// at the ghost point, which makes P = P_out on the line and continues a linear pressure field
/// exactly (the ghost-cell Dirichlet rule of finite volumes). A constant P_out in the buffer would
/// put a kink into the pressure of a channel flow at the outlet.
PARTICULA_HD real outlet_buffer_pressure(real p_out, real p_ghost) { return 2 * p_out - p_ghost; }

/// Particle shifting next to open lines (P.33 limited): a fluid particle within h of a line (and
/// within h of the segment's span) keeps only the tangential part of its shift direction. A
/// normal shift next to the regular buffer would open a void behind an inlet, and one across a
/// line would move mass past it unaccounted; the tangential part still mixes the fluid. Shared
/// by the CPU loop and the CUDA kernel.
PARTICULA_HD void limit_shift_at_open_lines(const OpenZone* zones, std::size_t count, Vec2 x, real h,
                                            Vec2& shift_dir) {
  for (std::size_t k = 0; k < count; ++k) {
    const OpenZone& z = zones[k];
    const real xi = open_depth(z, x), s = open_along(z, x);
    if (xi < h && s > -h && s < z.width + h) shift_dir -= dot(shift_dir, z.n) * z.n;
  }
}

}  // namespace particula
