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

#include <cmath>
#include <cstdint>

#include "particula/core/types.hpp"
#include "particula/core/types3.hpp"
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

/// A surface near a fluid particle: the tangent line at one surface particle, as far as `reach`
/// on either side (one surface spacing: the line stands for the surface there and no farther; a
/// wall ends at a corner), or at a convex corner of the solid (a polygon body's vertex, the
/// inward corner of an L-shaped container, where the fluid wraps round more than 180 degrees)
/// the two sides that meet there.
template <int D>
struct SurfaceTangentOf {
  Vec<D> x, n, v;  // position, outward unit normal (into the fluid; the bisector at a corner), velocity
  real wedge = 0;  // at a convex corner of the solid: half the angle between the two sides' normals
  real reach = 0;  // half-length of the stretch of tangent line that stands for the surface (0: unbounded)
};
using SurfaceTangent = SurfaceTangentOf<2>;

/// The boundary arrays the surfaces are gathered from (Particles' boundary block); v may be null.
template <int D>
struct SurfaceArraysOf {
  const Vec<D>* x = nullptr;
  const Vec<D>* n = nullptr;
  const real* wedge = nullptr;
  const real* ds = nullptr;
  const Vec<D>* v = nullptr;
};
using SurfaceArrays = SurfaceArraysOf<2>;

/// Up to two surfaces near a fluid particle (see NearestSurfaces).
template <int D>
struct NearSurfacesOf {
  int count = 0;
  SurfaceTangentOf<D> s[2];
};
using NearSurfaces = NearSurfacesOf<2>;

/// The spacing of a surface sample that stands for `ds` of the surface: ds itself in 2D (a
/// length), the side of the square of that area in 3D.
template <int D>
PARTICULA_HD real sample_spacing(real ds);
template <>
PARTICULA_HD real sample_spacing<2>(real ds) {
  return ds;
}
template <>
PARTICULA_HD real sample_spacing<3>(real ds) {
  return std::sqrt(ds);
}

/// The surface of surface particle j: its tangent line (plane) reaching one surface spacing.
template <int D>
PARTICULA_HD SurfaceTangentOf<D> surface_at(const SurfaceArraysOf<D>& s, std::uint32_t j) {
  return SurfaceTangentOf<D>{s.x[j], s.n[j], s.v ? s.v[j] : Vec<D>{}, s.wedge[j], sample_spacing<D>(s.ds[j])};
}

/// The surfaces of slots a and b.
template <int D>
PARTICULA_HD NearSurfacesOf<D> gather_surfaces(std::uint32_t a, std::uint32_t b,
                                               const SurfaceArraysOf<D>& s) {
  NearSurfacesOf<D> out;
  if (a != kNoSurface) out.s[out.count++] = surface_at(s, a);
  if (b != kNoSurface) out.s[out.count++] = surface_at(s, b);
  return out;
}

/// Signed distance of x from the surface at s (positive on the fluid side) and the unit
/// direction `away` in which it grows (the direction that moves x straight away from the solid).
///   On a smooth surface, a flat wall and a concave corner of the solid (a box corner, where the
///   fluid angle is below 180 degrees): the tangent line, d = (x - x_s) . n, away = n. At a
///   concave corner the line through the corner across the bisector lies in the solid, so it
///   keeps the fluid at least as far from both sides as the sides themselves would. The line
///   stands for the surface within `reach` of x_s along it: beyond, the distance is the one
///   from the end of that stretch, e = x_s +- reach t (away = (x - e) / |x - e|). The nearest
///   surface particle of a smooth surface or a flat wall always has x's foot within reach (half
///   a spacing on a flat wall, a little more outside a curve), so this changes nothing there;
///   at the last particle of a wall that ends at a convex corner, the line ran on past the
///   corner through the fluid.
///   At a convex corner of the solid (wedge > 0): the solid is the wedge between the two sides,
///   whose normals are n rotated by +-wedge, n1,2 = n cos(wedge) +- n_perp sin(wedge), and the
///   distance is the one from that wedge: with r = x - x_s, |r| (away = r / |r|) where r lies in
///   the corner's normal cone (within `wedge` of n: the corner point is the nearest point of the
///   solid), else max(r . n1, r . n2) (away = that side's normal: the nearest point is on a
///   side, or x is inside the solid). The tangent line there cut through the fluid beside the
///   corner: a particle level with one side, past the corner, was 'below' the line and was thrown
///   across the extension of the other side onto its neighbours.
PARTICULA_HD real surface_distance(const Domain& domain, Vec2 x, const SurfaceTangent& s, Vec2& away) {
  const Vec2 r = domain.separation(x, s.x);
  const real dn = dot(r, s.n);
  away = s.n;
  if (!(s.wedge > 0)) {
    const Vec2 t{-s.n.y, s.n.x};
    const real along = dot(r, t);
    if (!(s.reach > 0) || std::fabs(along) <= s.reach) return dn;
    const Vec2 from_end = r - std::copysign(s.reach, along) * t;
    const real len = norm(from_end);
    away = from_end / len;
    return len;
  }
  const real cw = std::cos(s.wedge), sw = std::sin(s.wedge);
  const Vec2 t{-s.n.y, s.n.x};
  const Vec2 n1 = cw * s.n + sw * t, n2 = cw * s.n - sw * t;
  const real len = norm(r);
  if (len > 0 && dn >= cw * len) {  // within the normal cone
    away = r / len;
    return len;
  }
  const real d1 = dot(r, n1), d2 = dot(r, n2);
  away = d1 >= d2 ? n1 : n2;
  return d1 >= d2 ? d1 : d2;
}

/// The same in 3D: the tangent plane at x_s stands for the surface within the disc of radius
/// `reach` round x_s (beyond it, the distance from the disc's rim at the foot's side, away =
/// (x - e) / |x - e|). At a convex edge or vertex of the solid (wedge > 0) the solid is taken
/// as the cone round -n whose surface makes the angle 90 degrees + wedge with n, the one
/// rotationally symmetric set with the 2D wedge's normal cone: |r| within `wedge` of n, else
/// r . n1 with n1 = n cos(wedge) + t sin(wedge) and t the direction of r's tangential part (in
/// the plane of n and r this is the 2D side on r's side, max(r . n1, r . n2) above).
PARTICULA_HD real surface_distance(const DomainOf<3>& domain, Vec3 x, const SurfaceTangentOf<3>& s,
                                   Vec3& away) {
  const Vec3 r = domain.separation(x, s.x);
  const real dn = dot(r, s.n);
  const Vec3 tangential = r - dn * s.n;
  const real along = norm(tangential);
  away = s.n;
  if (!(s.wedge > 0)) {
    if (!(s.reach > 0) || along <= s.reach) return dn;
    const Vec3 from_end = r - (s.reach / along) * tangential;
    const real len = norm(from_end);
    away = from_end / len;
    return len;
  }
  const real cw = std::cos(s.wedge), sw = std::sin(s.wedge);
  const real len = norm(r);
  if (len > 0 && dn >= cw * len) {  // within the normal cone
    away = r / len;
    return len;
  }
  // r along -n (no tangential part): every side is as near; take one perpendicular to n
  const Vec3 t = along > 0 ? tangential / along : any_perpendicular(s.n);
  away = cw * s.n + sw * t;
  return dot(r, away);
}

/// surface_distance without the direction.
template <int D>
PARTICULA_HD real surface_distance(const DomainOf<D>& domain, Vec<D> x, const SurfaceTangentOf<D>& s) {
  Vec<D> away;
  return surface_distance(domain, x, s, away);
}

/// What the guard did to one particle.
enum class GuardOutcome : std::uint8_t { None = 0, Pushed = 1, Gap = 2 };

/// Two surfaces face each other across a gap (normals within 60 degrees of opposite).
template <int D>
PARTICULA_HD bool facing(const SurfaceTangentOf<D>& a, const SurfaceTangentOf<D>& b) {
  return dot(a.n, b.n) < -0.5;
}

/// The surface guard for one fluid particle (see the header comment). `keep` = d_keep in metres.
template <int D>
PARTICULA_HD GuardOutcome guard_surfaces(const NearSurfacesOf<D>& ns, real keep, const DomainOf<D>& domain,
                                         Vec<D>& x, Vec<D>& v) {
  if (ns.count == 0 || !(keep > 0)) return GuardOutcome::None;
  if (ns.count == 2 && facing(ns.s[0], ns.s[1])) {
    const SurfaceTangentOf<D>&a = ns.s[0], &b = ns.s[1];
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
    const SurfaceTangentOf<D>& s = ns.s[k];
    Vec<D> away;
    const real d = surface_distance(domain, x, s, away);
    if (d >= keep) continue;
    x = domain.wrap(x + (keep - d) * away);
    const real vn = dot(v - s.v, away);
    if (vn < 0) v -= vn * away;
    out = GuardOutcome::Pushed;
  }
  return out;
}

/// The unresolved-film fraction of a fluid particle (docs/method.md, "Unresolved films"):
/// between two facing surfaces whose gap through the particle, d_a + d_b, is narrower than
/// `film_gap`, the squeeze flow that drains (or fills) the gap is not resolved by one or two
/// particle layers, and the particle's volume change is left out of the continuity equation in
/// proportion: 0 for a gap of film_gap or more, 1 for film_gap / 2 or less, linear between.
template <int D>
PARTICULA_HD real film_fraction(const NearSurfacesOf<D>& ns, real film_gap, const DomainOf<D>& domain,
                                Vec<D> x) {
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
PARTICULA_HD bool isolated(real others_fluid_support, real one_neighbour_support,
                           std::uint32_t nearest_surface) {
  return nearest_surface != kNoSurface && others_fluid_support < one_neighbour_support;
}

/// Particle shifting never moves a particle towards a surface it is within `range` of (one
/// particle spacing): the shift's component into that surface (against surface_distance's
/// `away`) is removed.
template <int D>
PARTICULA_HD Vec<D> limit_shift_at_surfaces(Vec<D> dr, const NearSurfacesOf<D>& ns, real range,
                                            const DomainOf<D>& domain, Vec<D> x) {
  for (int k = 0; k < ns.count; ++k) {
    const SurfaceTangentOf<D>& s = ns.s[k];
    Vec<D> away;
    const real d = surface_distance(domain, x, s, away);
    const real into = dot(dr, away);
    if (into < 0 && d < range) dr -= into * away;
  }
  return dr;
}

}  // namespace particula
