// The smooth pressure's load on each solid (solver/load_band.hpp): the part of the stress the band
// takes out of the fluid's pressure (hydrostatic, or a body force along a closed side) is added
// back exactly, as an integral over each solid's wetted surface.
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "particula/solver/load_band.hpp"

namespace particula {

namespace {

/// -int P_h n ds over the stretch [s0, s1] of wall w (4-point Gauss-Legendre on a segment, and on
/// each piece of at most pi/8 of an arc: P_h is exponential along it, with an exponent below
/// 1e-2 in a weakly compressible fluid), and its moment about `about`.
template <class SmoothPressure>
void wall_stretch_load(const WallPiece& w, real s0, real s1, const SmoothPressure& p_h, const Domain& dom,
                       Vec2 about, Vec2& force, real& torque) {
  constexpr real xg[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
  constexpr real wg[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
  const real span = s1 - s0;
  if (!(span > 0)) return;
  const int pieces =
      w.is_arc() ? std::max(1, static_cast<int>(std::ceil(std::fabs(w.sweep()) * span / (M_PI / 8)))) : 1;
  const real piece_len = w.length() * span / pieces;
  for (int m = 0; m < pieces; ++m)
    for (int q = 0; q < 4; ++q) {
      const real s = s0 + span * (m + 0.5 * (1 + xg[q])) / pieces;
      const Vec2 x = w.point_at(s);
      const Vec2 t = (-0.5 * piece_len * wg[q] * p_h(x)) * w.normal_at(s);
      force += t;
      torque += cross(dom.separation(x, about), t);
    }
}

}  // namespace

void LoadBand::smooth_pressure_load(const BandScene& s, const LoadArrays& a, std::size_t k, Vec2& force,
                                    real& torque) const {
  const RigidGroup& g = s.groups[k];
  const Particles& P = s.particles;
  const std::int32_t gk = static_cast<std::int32_t>(k);
  const auto p_h = [&](Vec2 x) { return smooth_pressure(a, gk, x); };
  force = Vec2{};
  torque = 0;
  if (g.removed) return;
  if (g.is_wall) {
    // -n int P_h ds over the wall's wetted stretches: not where a fixed body stands on it or
    // crosses it (the body carries those, below).
    std::vector<std::pair<real, real>> dry;
    for (const BodyParams& b : s.prm.bodies)
      for (const BodyParams::Cover& c : b.covers)
        if (c.wall == k) dry.emplace_back(c.s0, c.s1);
    std::sort(dry.begin(), dry.end());
    const WallPiece w = wall_now(s.prm, s.groups, k);
    real wet = 0;  // where the wetted stretch starts
    for (const auto& [d0, d1] : dry) {
      wall_stretch_load(w, wet, d0, p_h, s.domain, g.pos, force, torque);
      wet = std::max(wet, d1);
    }
    wall_stretch_load(w, wet, 1, p_h, s.domain, g.pos, force, torque);
    return;
  }
  const BodyParams& b = s.prm.bodies[static_cast<std::size_t>(g.body)];
  if (b.motion == BodyMotion::Fixed && (!b.covers.empty() || b.area_in != b.shape.area())) {
    // A fixed body standing on walls or crossing them: its wetted surface and the wall stretches
    // it covers close its part in the fluid region (area A_in), so by Gauss's theorem
    // -int_wetted P_h n ds = -rho_h g_h A_in - int_covered P_h n_wall ds.
    const Vec2 f_area =
        (-a.group_level[k] * smooth_pressure_shape(a, b.centroid_in) / a.c2 * b.area_in) * a.g_h;
    force = f_area;
    torque = cross(s.domain.separation(b.centroid_in, g.pos), f_area);
    for (const BodyParams::Cover& c : b.covers)
      wall_stretch_load(wall_now(s.prm, s.groups, c.wall), c.s0, c.s1, p_h, s.domain, g.pos, force, torque);
    return;
  }
  std::size_t surface = 0;
  for (std::size_t i = g.first; i < g.first + g.count; ++i) surface += P.kind[i] == Kind::Boundary;
  if (surface == b.samples.size()) {
    // A body with fluid all round: -int_body grad P_h dA = -rho_h g_h A, rho_h taken at the
    // centroid (exact for a linear density; the torque about the centroid is then zero).
    force = (-a.group_level[k] * smooth_pressure_shape(a, g.pos) / a.c2 * g.area) * a.g_h;
    return;
  }
  // Any other body with part of its surface left out: -P_h n dS over its surface particles,
  // placed from the group's pose (current on the host also when the particles live on the GPU).
  const GroupMotion mo = group_motion(g);
  for (std::size_t i = g.first; i < g.first + g.count; ++i) {
    if (P.kind[i] != Kind::Boundary) continue;
    const Vec2 xs = surface_position(s.domain, mo, P.local[i]);
    const Vec2 t =
        (-smooth_pressure(a, gk, xs) * P.ds[i]) * rotate(P.normal_local[i], mo.cos_angle, mo.sin_angle);
    force += t;
    torque += cross(s.domain.separation(xs, g.pos), t);
  }
}

}  // namespace particula
