// The surface guard: no fluid particle crosses a wall or a body surface, and particle shifting
// never moves a particle towards a surface it is close to (docs/method.md, "Surface
// guard"). A kinematic correction applied after the position update of every step:
//
//   The surface near fluid particle i is represented by its nearest surface particle s (a wall
//   or body particle ON the surface, single-layer) and that particle's tangent line
//   (position x_s, outward normal n_s, velocity V_s). The signed distance of i from the surface
//   is d = (x_i - x_s) . n_s. Where d < d_keep (a fraction of d0, `numerics.surface_guard`):
//     x_i += (d_keep - d) n_s                      (back to the keep-out distance), and
//     V_i -= min(0, (V_i - V_s) . n_s) n_s         (no relative velocity into the surface).
//   The second surface considered is the nearest surface particle of ANOTHER rigid group (the
//   other side of a gap between two bodies, or the other wall of a corner). Where the two face
//   each other and the gap between them is narrower than 2 d_keep (a closing gap: no position
//   keeps d_keep from both), the particle is put midway between them and its normal velocity is
//   the mean of the two surfaces' normal velocities: it is carried by the closing gap instead of
//   being pushed through one side, until the pressure squeezes it out along the gap.
//
// Why a kinematic correction and not a repulsive force: a force (Monaghan-type boundary forces)
// needs a strength tuned to the flow speed and limits the time step; the correction needs no
// parameter beyond the keep-out distance, cannot be overpowered by a fast particle, and does
// nothing where the flow keeps the particle away (the paper's cases never trigger it).
#pragma once

#include <cstdint>

#include "particula/core/types.hpp"
#include "particula/neighbors/domain.hpp"

namespace particula {

/// "No surface particle" in the nearest-surface slots.
inline constexpr std::uint32_t kNoSurface = 0xffffffffu;

/// The nearest surface particle of a fluid particle (slot a) and the nearest one of another
/// rigid group (slot b), by distance squared, updated pair by pair in the geometry sweep.
struct NearestSurfaces {
  std::uint32_t a = kNoSurface, b = kNoSurface;
  std::int32_t group_a = -1;
  real d2a = 1e300, d2b = 1e300;
};

/// Offers surface particle j (rigid group `group`, distance squared d2) to the two slots: slot a
/// keeps the nearest overall, slot b the nearest of a group other than slot a's.
PARTICULA_HD void offer_surface(NearestSurfaces& s, std::uint32_t j, std::int32_t group, real d2) {
  if (group == s.group_a) {
    if (d2 < s.d2a) {
      s.a = j;
      s.d2a = d2;
    }
  } else if (d2 < s.d2a) {
    s.b = s.a;  // the old nearest is of another group than the new one
    s.d2b = s.d2a;
    s.a = j;
    s.d2a = d2;
    s.group_a = group;
  } else if (d2 < s.d2b) {
    s.b = j;
    s.d2b = d2;
  }
}

/// A surface near a fluid particle: the tangent line at one surface particle.
struct SurfaceTangent {
  Vec2 x, n, v;  // position, outward unit normal (into the fluid), velocity
};

/// Up to two surfaces near a fluid particle (see NearestSurfaces).
struct NearSurfaces {
  int count = 0;
  SurfaceTangent s[2];
};

/// The surfaces of slots a and b gathered from the boundary arrays (positions, normals, and
/// velocities unless v is null).
PARTICULA_HD NearSurfaces gather_surfaces(std::uint32_t a, std::uint32_t b, const Vec2* x, const Vec2* n,
                                          const Vec2* v) {
  NearSurfaces out;
  if (a != kNoSurface) out.s[out.count++] = SurfaceTangent{x[a], n[a], v ? v[a] : Vec2{}};
  if (b != kNoSurface) out.s[out.count++] = SurfaceTangent{x[b], n[b], v ? v[b] : Vec2{}};
  return out;
}

/// Signed distance of x from the tangent line of surface point s (positive on the fluid side).
PARTICULA_HD real surface_distance(const Domain& domain, Vec2 x, const SurfaceTangent& s) {
  return dot(domain.separation(x, s.x), s.n);
}

/// What the guard did to one particle.
enum class GuardOutcome : std::uint8_t { None = 0, Pushed = 1, Gap = 2 };

/// Two surfaces face each other across a gap (normals within 60 degrees of opposite).
PARTICULA_HD bool facing(const SurfaceTangent& a, const SurfaceTangent& b) { return dot(a.n, b.n) < -0.5; }

/// The surface guard for one fluid particle (see the header comment). `keep` = d_keep in metres.
PARTICULA_HD GuardOutcome guard_surfaces(const NearSurfaces& ns, real keep, const Domain& domain, Vec2& x, Vec2& v) {
  if (ns.count == 0 || !(keep > 0)) return GuardOutcome::None;
  if (ns.count == 2 && facing(ns.s[0], ns.s[1])) {
    const SurfaceTangent &a = ns.s[0], &b = ns.s[1];
    const real da = surface_distance(domain, x, a), db = surface_distance(domain, x, b);
    if (da + db < 2 * keep) {
      // A closing gap: midway between the two (measured along a's normal), moving with them.
      x = domain.wrap(x + (0.5 * (db - da)) * a.n);
      const real vn = 0.5 * dot(a.v + b.v, a.n);
      v += (vn - dot(v, a.n)) * a.n;
      return GuardOutcome::Gap;
    }
  }
  GuardOutcome out = GuardOutcome::None;
  for (int k = 0; k < ns.count; ++k) {
    const SurfaceTangent& s = ns.s[k];
    const real d = surface_distance(domain, x, s);
    if (d >= keep) continue;
    x = domain.wrap(x + (keep - d) * s.n);
    const real vn = dot(v - s.v, s.n);
    if (vn < 0) v -= vn * s.n;
    out = GuardOutcome::Pushed;
  }
  return out;
}

/// The unresolved-film fraction of a fluid particle (docs/method.md, "Unresolved films"):
/// between two facing surfaces whose gap through the particle, d_a + d_b, is narrower than
/// `film_gap`, the squeeze flow that drains (or fills) the gap is not resolved by one or two
/// particle layers, and the particle's volume change is left out of the continuity equation in
/// proportion: 0 for a gap of film_gap or more, 1 for film_gap / 2 or less, linear between.
PARTICULA_HD real film_fraction(const NearSurfaces& ns, real film_gap, const Domain& domain, Vec2 x) {
  if (ns.count < 2 || !(film_gap > 0) || !facing(ns.s[0], ns.s[1])) return 0;
  const real gap = surface_distance(domain, x, ns.s[0]) + surface_distance(domain, x, ns.s[1]);
  const real f = (film_gap - gap) / (0.5 * film_gap);
  return f <= 0 ? real(0) : (f >= 1 ? real(1) : f);
}

/// An isolated fluid particle (docs/method.md, "Isolated particles"): the fluid within its
/// kernel support, its own volume left out, weighs less than one neighbour at one particle
/// spacing, sum_{j fluid, j != i} w_j W_ij < d0^2 W(d0), and a surface is near. P.20 of a surface
/// particle leaves such particles out (sweeps.hpp, wall_pressure_at), and they take their pressure
/// from the surface particles around them (isolated_pressure_at): a lone particle in a wedge
/// between two solids set the P.20 pressures of the surface particles around it, whose pressure
/// gradient in turn drove the particle, a loop that shot it out at several times the sound speed;
/// and its continuity equation, with no fluid around it, compressed it in a closing gap.
PARTICULA_HD bool isolated(real others_fluid_support, real one_neighbour_support, std::uint32_t nearest_surface) {
  return nearest_surface != kNoSurface && others_fluid_support < one_neighbour_support;
}

/// Particle shifting never moves a particle towards a surface it is within `range` of (one
/// particle spacing): the shift's component into that surface is removed.
PARTICULA_HD Vec2 limit_shift_at_surfaces(Vec2 dr, const NearSurfaces& ns, real range, const Domain& domain, Vec2 x) {
  for (int k = 0; k < ns.count; ++k) {
    const SurfaceTangent& s = ns.s[k];
    const real into = dot(dr, s.n);
    if (into < 0 && surface_distance(domain, x, s) < range) dr -= into * s.n;
  }
  return dr;
}

}  // namespace particula
