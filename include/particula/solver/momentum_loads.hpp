// Hydrodynamic loads on solids from the momentum balance of the fluid in a band around each
// solid (`numerics.force = "momentum"`; docs/method.md, "Forces on solids").
//
// For any weight phi_B that is 1 on the surface of solid B and 0 on every other solid surface,
// the divergence theorem over the fluid region gives the force and torque on B exactly:
//
//   F_B = - int [ grad(phi_B) . sigma + phi_B div(sigma) ] dA,
//   T_B = - int r x [ grad(phi_B) . sigma + phi_B div(sigma) ] dA,   r = x - X_B,
//
// and div(sigma) = rho (a - f) is what the discrete momentum equation of each fluid particle
// computes, -<grad P> + mu <lap V>. As a particle sum (volumes w_i = m_i / rho_i):
//
//   F_B = - sum_i [ w_i grad(phi_B)_i . sigma_i + phi_B(x_i) m_i (-<grad P>_i/rho_i + nu <lap V>_i) ].
//
// The surface sum of P.26-P.27 reads the stress at the surface particles, where the
// renormalized operators see a one-sided support and are first order: the drag on a cylinder
// array came out 5.5 % / 3.0 % / 2.2 % low at 10 / 20 / 28 particles across. Here the momentum
// rate of the particles next to the surface enters exactly as the scheme computes it (it IS the
// momentum the fluid exchanges with the surface), and the stress is read only where phi_B
// varies, which the weight below keeps more than about h from every surface, where the
// operators have their full support. A large smooth pressure field (hydrostatic) is taken out
// of sigma and its force added exactly, so that the quadrature error of the band sum does not
// scale with it.
//
// Everything here is a plain function of one particle (PARTICULA_HD): the CPU loop and the CUDA
// kernel evaluate the same formulas.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "particula/core/types.hpp"
#include "particula/neighbors/domain.hpp"

namespace particula {

/// Width of the band around a solid, in kernel radii h: phi_B falls to zero at this distance.
/// 5 h: with 3 h the torque on the walls of a box round a turning cylinder came out 1.5 % above
/// the cylinder's at 20 particles across (0.17 % with 5 h); the drag on the cylinder array is
/// within 0.05 % of the force balance with either.
inline constexpr real kLoadBandReach = 5.0;

/// A kept band (numerics.load_band_motion) between two solids a gap g apart is built again once
/// they have moved relative to each other by kBandGapShare max(g, kBandGapFloor d0): the
/// partition below changes by about 4 delta / g when they close in by delta, so this keeps that
/// change near 20 %. At 0.05 the rebound of the drop_rebound case at d0 = 1e-4 came out
/// as with the band built every step (docs/method.md, "The kept band").
inline constexpr real kBandGapShare = 0.05;
inline constexpr real kBandGapFloor = 0.1;

/// Weight of a solid at distance s (in units of the band reach) from its surface,
/// w(s) = psi(s) / s^4 with psi(s) = (1 - s)^2 (1 + 2 s), and dw/ds. The partition
/// phi_B = w_B / (1 + sum_C w_C) over the solids near a point is then 1 on B's surface
/// (w_B -> infinity), 0 on every other surface and beyond the reach, and flat next to a
/// surface (1 - phi_B ~ s^4): phi_B varies only between about 0.4 and 1 reach. The s^-4 keeps
/// the stress of the particles within h of the surface, where the operators are one-sided,
/// out of the sum (a plain smoothstep over the band put the drag 2-4 % high).
PARTICULA_HD void band_weight(real s, real& w, real& dw) {
  if (s >= 1) {
    w = dw = 0;
    return;
  }
  const real sc = s > real(1e-4) ? s : real(1e-4);  // a particle on the surface: phi_B = 1 to round-off
  const real psi = (1 - sc) * (1 - sc) * (1 + 2 * sc), dpsi = -6 * sc * (1 - sc);
  const real s2 = sc * sc, s4 = s2 * s2;
  w = psi / s4;
  dw = dpsi / s4 - 4 * psi / (s4 * sc);
}

/// A solid near a fluid particle: its distance d (m, from the surface, positive in the fluid) and
/// the unit gradient of that distance at the particle; w and dw, its band_weight at d / reach
/// and the derivative (weigh_near_solids).
struct NearSolid {
  std::int32_t group = -1;
  real d = 0;
  Vec2 n;
  real w = 0, dw = 0;
};

/// One fluid particle in the band of one solid: phi_B(x_i) and grad phi_B(x_i), and the area
/// that weighs its grad(phi) terms (voronoi_cell_area; 0: its volume m_i / rho_i), fixed for a
/// step (positions are frozen during the stages).
struct BandEntry {
  std::uint32_t particle = 0;
  std::int32_t group = -1;
  real phi = 0;
  Vec2 grad_phi;
  real area = 0;
  // this entry's group among the groups of its block of kBandBlock entries (sum_band_entry_loads)
  std::uint16_t slot = 0;
  // the particle sits in a film between this solid and another thinner than kFilmGap h (the sum
  // of its distances to the two): the band's pressure torque is not resolved there
  bool in_film = false;
};

/// The band's entries are summed per group in blocks of this many (in particle order): each
/// block's sum per group, then the blocks' sums in block order, whatever the thread count.
inline constexpr std::size_t kBandBlock = 1024;

/// A film between two solid surfaces thinner than this many h holds at most about two fluid
/// particles across: there the partition phi_B falls from 1 to 0 across the film within a
/// spacing or two, and the moment of the band's pressure terms is not resolved.
inline constexpr real kFilmGap = 2.0;

/// Largest number of vertices of a cell in voronoi_cell_area (a square clipped by at most
/// kVoronoiMaxVertices - 4 bisectors; a cell with more is left to the volume m / rho).
constexpr int kVoronoiMaxVertices = 48;

/// Area of the Voronoi cell of a particle among neighbours at separations d[k] = x_k - x_i
/// (k < count): the square of half-width reach / 2 round it, clipped by the perpendicular
/// bisector of each neighbour (Sutherland-Hodgman). Returns 0 when the cell does not close
/// within reach / 2 of the particle (a void or an edge of the fluid beside it) or has too many
/// vertices: the caller then uses the particle's volume. A neighbour farther than twice the
/// cell's farthest vertex cannot cut it and is skipped.
///
/// Why (docs/method.md, "Forces on solids"): the band's grad(phi) terms are an area
/// integral, and its quadrature weight must be the area the particle stands for now. Its volume
/// m / rho follows the fluid's motion through the continuity equation but not particle
/// shifting, which moves a particle relative to the fluid without changing its density; the
/// Voronoi cells of the particles tile the plane whatever their arrangement.
PARTICULA_HD real voronoi_cell_area(const Vec2* d, int count, real reach) {
  Vec2 buf[2][kVoronoiMaxVertices];
  const real a0 = 0.5 * reach;
  int n = 4, cur = 0;
  buf[0][0] = {-a0, -a0};
  buf[0][1] = {a0, -a0};
  buf[0][2] = {a0, a0};
  buf[0][3] = {-a0, a0};
  real r2 = 2 * a0 * a0;  // the polygon's largest |x|^2
  for (int k = 0; k < count; ++k) {
    // keep the half-plane x . d_k <= |d_k|^2 / 2 (the side of the particle)
    const Vec2 dk = d[k];
    const real half = 0.5 * dot(dk, dk);
    if (0.5 * half >= r2) continue;  // |d_k| / 2 >= the farthest vertex: no cut
    const Vec2* in = buf[cur];
    // Each vertex's side of the bisector, once. With no vertex beyond it the clip would return
    // the polygon as it is (every vertex kept, no crossing), so it is skipped; a polygon of 48
    // vertices is left to the clip, which gives up on it.
    real f[kVoronoiMaxVertices];
    bool cuts = n >= kVoronoiMaxVertices;
    for (int a = 0; a < n; ++a) {
      f[a] = dot(in[a], dk) - half;
      cuts = cuts || f[a] > 0;
    }
    if (!cuts) continue;
    Vec2* out = buf[1 - cur];
    int m = 0;
    for (int a = 0; a < n; ++a) {
      const int b = a + 1 < n ? a + 1 : 0;
      const Vec2 P = in[a], Q = in[b];
      const real fp = f[a], fq = f[b];
      if (m + 2 > kVoronoiMaxVertices) return 0;
      if (fp <= 0) out[m++] = P;
      if ((fp < 0 && fq > 0) || (fp > 0 && fq < 0)) out[m++] = P + (fp / (fp - fq)) * (Q - P);
    }
    n = m;
    cur = 1 - cur;
    if (n < 3) return 0;
    r2 = 0;
    for (int a = 0; a < n; ++a) r2 = r2 > dot(out[a], out[a]) ? r2 : dot(out[a], out[a]);
  }
  const Vec2* poly = buf[cur];
  real area = 0;
  for (int a = 0; a < n; ++a) area += cross(poly[a], poly[a + 1 < n ? a + 1 : 0]);
  return r2 < a0 * a0 ? 0.5 * area : 0;
}

/// The band weight w and dw of each of the `count` solids near a particle (band reach `reach`,
/// m), once per particle: every solid's phi_B among them reads all of them (band_partition).
PARTICULA_HD void weigh_near_solids(NearSolid* near, int count, real reach) {
  for (int c = 0; c < count; ++c) band_weight(near[c].d / reach, near[c].w, near[c].dw);
}

/// The denominator of the partition at a particle, S = 1 + sum_C w_C over the `count` solids
/// near it (weighed by weigh_near_solids with the same reach), and its gradient: once per
/// particle, for all its solids.
PARTICULA_HD void band_partition_sum(const NearSolid* near, int count, real reach, real& S, Vec2& gradS) {
  S = 1;
  gradS = Vec2{};
  for (int c = 0; c < count; ++c) {
    S += near[c].w;
    gradS += (near[c].dw / reach) * near[c].n;
  }
}

/// phi_B = w_B / S and its gradient for the solid `near` of a particle whose partition sum is
/// S, gradS (band_partition_sum).
PARTICULA_HD void band_partition_of(const NearSolid& near, real S, Vec2 gradS, real reach, real& phi,
                                    Vec2& grad_phi) {
  phi = near.w / S;
  // grad(w_k / S) = (grad w_k - phi grad S) / S
  grad_phi = ((near.dw / reach) * near.n - phi * gradS) / S;
}

/// phi and grad phi of solid k among the `count` solids near a particle, weighed by
/// weigh_near_solids with the same reach: phi_B = w_B / (1 + sum_C w_C).
PARTICULA_HD void band_partition(const NearSolid* near, int count, int k, real reach, real& phi,
                                 Vec2& grad_phi) {
  real S;
  Vec2 gradS;
  band_partition_sum(near, count, reach, S, gradS);
  band_partition_of(near[k], S, gradS, reach, phi, grad_phi);
}

/// The per-particle fields a stage's load sum reads (plain pointers: host or device arrays).
struct LoadArrays {
  Domain domain;
  const Vec2* x = nullptr;
  const real* m = nullptr;
  const real* rho = nullptr;
  const real* p = nullptr;
  const Mat2* grad_v = nullptr;
  const Vec2* lap_v = nullptr;
  const Vec2* odd_even = nullptr;         // the odd-even damping's acceleration of the stage, or none
  const Vec2* grad_p_over_rho = nullptr;  // <grad P>_i / rho_i of the stage
  const Vec2* group_pos = nullptr;        // reference point X_B of each rigid group
  const real* group_level = nullptr;      // K_B of each group's smooth pressure field (smooth_pressure)
  real mu = 0, nu = 0;
  real rho0 = 0, c2 = 0, p0 = 0;  // the equation of state P = p0 + c^2 (rho - rho0)
  Vec2 g_h, x_ref;                // acceleration whose hydrostatic pressure is taken out
};

/// Shape of the smooth pressure field: P_h(x) = p0 - rho0 c^2 + K_B e(x), e(x) =
/// exp(g_h . (x - x_ref) / c^2), the hydrostatic pressure of the weakly compressible fluid
/// (grad P_h = rho_h g_h with rho_h the density of P_h): at rest, the fluid's own.
PARTICULA_HD real smooth_pressure_shape(const LoadArrays& a, Vec2 x) {
  return std::exp(dot(a.g_h, x - a.x_ref) / a.c2);
}

/// P_h of group g at x.
PARTICULA_HD real smooth_pressure(const LoadArrays& a, std::int32_t g, Vec2 x) {
  return a.p0 - a.rho0 * a.c2 + a.group_level[g] * smooth_pressure_shape(a, x);
}

/// What the band sums read of fluid particle i in a stage, once for all its entries (its
/// solids differ only in phi, grad phi, K_B and X_B).
struct BandSample {
  real m = 0;
  real w = 0;      // volume m / rho
  real area = 0;   // weight of the grad(phi) terms: BandEntry::area, or w when that is 0
  real p_rel = 0;  // P_i - p0 + rho0 c^2: the pressure above the state's zero density
  real shape = 0;  // e(x_i) of the smooth pressure (smooth_pressure_shape)
  Mat2 tau;        // mu (L + L^T - tr(L) I), L_ab = d_a V_b (renormalized, P.7)
  Vec2 m_rate_p;   // m_i (-<grad P>_i / rho_i): the pressure share of the particle's m (a - f)
  Vec2 m_rate_v;   // m_i nu <lap V>_i: the viscous share
  Vec2 m_rate_d;   // m_i kappa (<lap V>_i - <div <grad V>>_i): the odd-even damping's (not a load)
  Vec2 x;
};

PARTICULA_HD BandSample band_sample(const LoadArrays& a, std::uint32_t i, real area) {
  BandSample s;
  s.m = a.m[i];
  s.w = s.m / a.rho[i];
  s.area = area > 0 ? area : s.w;
  s.p_rel = a.p[i] - a.p0 + a.rho0 * a.c2;
  s.x = a.x[i];
  s.shape = smooth_pressure_shape(a, s.x);
  // tau = mu (L + L^T - tr(L) I): symmetric, and its divergence is mu lap V, the scheme's own
  // viscous term (mu (L + L^T) differs from it by mu grad(div V), which the weakly compressible
  // flow does not make zero: the Rhie-Chow term balances a steady div V)
  const Mat2 L = a.grad_v[i];
  const real div_v = trace(L);
  s.tau = a.mu * (L + transpose(L) - Mat2{div_v, 0, 0, div_v});
  s.m_rate_p = -s.m * a.grad_p_over_rho[i];
  s.m_rate_v = (s.m * a.nu) * a.lap_v[i];
  if (a.odd_even != nullptr) s.m_rate_d = s.m * a.odd_even[i];
  return s;
}

/// A particle's share of its solid's level K_B, the weighted mean of (P_i - p0 + rho0 c^2) /
/// e(x_i) with weights phi w_i: num and den of the mean.
PARTICULA_HD void band_share_level(const BandSample& s, real phi, real& num, real& den) {
  den = phi * s.w;
  num = den * (s.p_rel / s.shape);
}

/// Load of a particle (sample s) on solid B (its entry e; level = K_B e(x_i) = P_h - p0 +
/// rho0 c^2 at x_i), -[A_i grad(phi) . sigma_dyn + phi (m_i (a_i - f) + w_i grad P_h)] with
/// sigma_dyn = -P_dyn I + tau, P_dyn = P_i - P_h(x_i), A_i the particle's area (its Voronoi cell,
/// or w_i = m_i / rho_i), split into the pressure part (P_dyn, <grad P>, grad P_h) and the
/// viscous part (tau, <lap V>), and the torques about X_B (lever = x_i - X_B, minimum image) of
/// each part: torque.x of the pressure part, torque.y of the viscous part (a circle takes only the
/// latter in a film: LoadBand::group_loads). The phi terms keep the volume w_i: they are
/// the particle's own momentum rate, m_i (a_i - f) = w_i (-<grad P>_i + ...).
PARTICULA_HD void band_share_load(const BandSample& s, real phi, Vec2 grad_phi, real level, Vec2 lever,
                                  const LoadArrays& a, Vec2& fp, Vec2& fv, Vec2& torque) {
  const real p_dyn = s.p_rel - level;
  const Vec2 grad_p_h = (level / a.c2) * a.g_h;  // rho_h g_h
  fp = (s.area * p_dyn) * grad_phi - phi * (s.m_rate_p + s.w * grad_p_h);
  fv = -s.area * (grad_phi * s.tau) - phi * s.m_rate_v;
  torque = Vec2{cross(lever, fp), cross(lever, fv)};
}

/// The odd-even damping's share of particle s on a solid of weight phi: -phi m_i a_damp,i, with
/// the sign of a load. Not part of the load: the damping (sweeps.hpp, odd_even_velocity_at) is a
/// numerical term that is zero for quadratic fields in the interior, but next to a surface, where
/// the compact and the wide Laplacian see one-sided supports, or on a boundary layer the particles
/// do not resolve, it takes momentum from the fluid like a wall stress. Counted in the load, it
/// moved the DFG cylinder's drag away from the reference (docs/method.md, "Forces on
/// solids"); left out, the fluid's momentum budget misses it. So it is summed apart
/// (RigidGroup::force_damping, the fdx and fdy columns of bodies.csv and walls.csv): the momentum
/// the damping took from the fluid next to each solid, for budgets and for judging the resolution.
PARTICULA_HD Vec2 band_share_damping(const BandSample& s, real phi) { return -phi * s.m_rate_d; }

/// One group's sums over band entries (a block's partial sum, or the group's total): pressure
/// and viscous forces, the odd-even damping's share (band_share_damping, not a load) and the torque.
struct BandLoadSum {
  Vec2 fp, fv, fd;
  real torque = 0;
  PARTICULA_HD BandLoadSum& operator+=(const BandLoadSum& o) {
    fp += o.fp;
    fv += o.fv;
    fd += o.fd;
    torque += o.torque;
    return *this;
  }
};

/// Adds one entry's load (torque: of its pressure part in x, its viscous part in y) to its group's
/// sum. A circle takes no torque from pressure about its centre, and the band's pressure torque is
/// not resolved in a film thinner than about two spacings (docs/method.md, "Forces on solids"):
/// for a circle's entry in such a film only the viscous part counts.
PARTICULA_HD void add_band_entry_load(BandLoadSum& sum, Vec2 fp, Vec2 fv, Vec2 torque, Vec2 fd,
                                      bool viscous_torque_only) {
  sum.fp += fp;
  sum.fv += fv;
  sum.fd += fd;
  sum.torque += viscous_torque_only ? torque.y : torque.x + torque.y;
}

/// The entries' levels (num, den per entry, as band_entry_level gives them) summed per block
/// slot in the order sum_band_entry_loads adds the loads.
void sum_band_entry_levels(const std::vector<BandEntry>& band, const std::vector<std::size_t>& block_first,
                           const std::vector<Vec2>& num_den, std::vector<Vec2>& partial);

/// The entries' loads (fp, fv, torque, fd per entry, as band_entry_load gives them) summed per
/// block slot: block b's entries (kBandBlock of them, in band order) add in that order into
/// partial[block_first[b] + entry.slot] (add_band_entry_load; `circle[k]`: group k is a circular
/// body); blocks in parallel. The one order of additions whatever the thread count or backend.
void sum_band_entry_loads(const std::vector<BandEntry>& band, const std::vector<std::size_t>& block_first,
                          const std::vector<std::uint8_t>& circle, const std::vector<Vec2>& fp,
                          const std::vector<Vec2>& fv, const std::vector<Vec2>& torque,
                          const std::vector<Vec2>& fd, std::vector<BandLoadSum>& partial);

/// band_share_load of entry e with its particle's sample s and its group's K_B and X_B.
PARTICULA_HD void band_entry_share(const LoadArrays& a, const BandSample& s, const BandEntry& e, Vec2& fp,
                                   Vec2& fv, Vec2& torque) {
  band_share_load(s, e.phi, e.grad_phi, a.group_level[e.group] * s.shape,
                  a.domain.separation(s.x, a.group_pos[e.group]), a, fp, fv, torque);
}

/// Band entry e's share of its group's level K_B (band_share_level of its particle).
PARTICULA_HD void band_entry_level(const LoadArrays& a, const BandEntry& e, real& num, real& den) {
  band_share_level(band_sample(a, e.particle, e.area), e.phi, num, den);
}

/// The load of band entry e (band_share_load of its particle on its solid) and the damping's
/// share fd (band_share_damping).
PARTICULA_HD void band_entry_load(const LoadArrays& a, const BandEntry& e, Vec2& fp, Vec2& fv, Vec2& torque,
                                  Vec2& fd) {
  const BandSample s = band_sample(a, e.particle, e.area);
  band_entry_share(a, s, e, fp, fv, torque);
  fd = band_share_damping(s, e.phi);
}

}  // namespace particula
