// Open boundaries in the time step (solver/open_boundaries.hpp; boundary/open_boundary.hpp has
// the per-particle formulas; docs/method.md, "Open boundaries"): the buffer particles' fields from
// the fluid's mirrored fit, their motion, the conversion, deletion and creation of particles where
// the fluid enters and leaves, and bodies removed at outlets.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "particula/fluid/fluid.hpp"
#include "particula/solver/open_boundaries.hpp"
#include "particula/solver/solids.hpp"

namespace particula {

namespace {

/// Coefficients of a linear moving-least-squares fit f(x) ~ a0 + a1 . (x - x_g) over data
/// points at offsets d_j = (x_j - x_g)/h with weights w_j: the fitted value at offset e is
/// sum_j c_j f_j with c_j = w_j p(d_j) . M^-1 p(e), p(d) = (1, d.x, d.y), M = sum_j w_j p p^T.
/// Solves M y = p(e) for the two targets e (the ghost point, 0, and the buffer particle) by a
/// Cholesky factorisation; false when a pivot loses all but 1e-6 of its diagonal entry (the
/// points do not determine a plane: too few of them, or all on one line).
bool linear_fit_targets(const std::vector<Vec2>& d, const std::vector<real>& w, Vec2 e, real y0[3],
                        real y1[3]) {
  real M[3][3] = {};
  for (std::size_t j = 0; j < d.size(); ++j) {
    const real p[3] = {1, d[j].x, d[j].y};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c <= r; ++c) M[r][c] += w[j] * p[r] * p[c];
  }
  for (int c = 0; c < 3; ++c) {
    real s = M[c][c];
    for (int k = 0; k < c; ++k) s -= M[c][k] * M[c][k];
    if (!(M[c][c] > 0) || !(s > 1e-6 * M[c][c])) return false;
    M[c][c] = std::sqrt(s);
    for (int r = c + 1; r < 3; ++r) {
      real t = M[r][c];
      for (int k = 0; k < c; ++k) t -= M[r][k] * M[c][k];
      M[r][c] = t / M[c][c];
    }
  }
  const auto solve = [&](const real rhs[3], real y[3]) {
    for (int r = 0; r < 3; ++r) {
      real s = rhs[r];
      for (int c = 0; c < r; ++c) s -= M[r][c] * y[c];
      y[r] = s / M[r][r];
    }
    for (int r = 2; r >= 0; --r) {
      real s = y[r];
      for (int c = r + 1; c < 3; ++c) s -= M[c][r] * y[c];
      y[r] = s / M[r][r];
    }
  };
  const real at_ghost[3] = {1, 0, 0}, at_particle[3] = {1, e.x, e.y};
  solve(at_ghost, y0);
  solve(at_particle, y1);
  return true;
}

}  // namespace

int OpenBoundaries::zone_of(const PhysicsParams& prm, Vec2 x, Kind k) {
  int best = -1;
  real best_d = 0;
  const bool inlet = k == Kind::Inlet;
  for (std::size_t z = 0; z < prm.open.size(); ++z) {
    const OpenZone& oz = prm.open[z];
    if (oz.inlet != inlet) continue;
    const real s = open_along(oz, x), tol = 1e-9 * oz.width;
    if (s < -tol || s > oz.width + tol) continue;
    const real d = std::fabs(open_depth(oz, x));
    if (best < 0 || d < best_d) {
      best = static_cast<int>(z);
      best_d = d;
    }
  }
  return best;
}

real OpenBoundaries::inlet_speed(const PhysicsParams& prm, std::size_t zone, real s, real t) {
  const OpenSpec& o = prm.open_specs[zone];
  const real W = prm.open[zone].width;
  real u = o.velocity;
  switch (o.profile) {
    case InletProfile::Uniform:
      break;
    case InletProfile::Parabolic:
      u = 4 * o.velocity * s * (W - s) / (W * W);
      break;
    case InletProfile::Table: {
      const std::vector<Vec2>& tab = o.table;  // (s, u), s increasing (checked at load)
      if (s <= tab.front().x) {
        u = tab.front().y;
      } else if (s >= tab.back().x) {
        u = tab.back().y;
      } else {
        std::size_t k = 1;
        while (tab[k].x < s) ++k;
        const real f = (s - tab[k - 1].x) / (tab[k].x - tab[k - 1].x);
        u = (1 - f) * tab[k - 1].y + f * tab[k].y;
      }
      break;
    }
  }
  return u * inlet_ramp(t, o.ramp_time);
}

void OpenBoundaries::clear() {
  buffer_.clear();
  buffer_zone_.clear();
  ghost_start_.assign(1, 0);
  ghost_j_.clear();
  ghost_val_.clear();
  ghost_lin_.clear();
}

void OpenBoundaries::fit(const OpenScene& s, const Particles& P, const CellGrid& grid, SolverCounters& cnt) {
  const std::size_t n = P.size(), nb = P.n_boundary;
  for (std::size_t i = nb; i < n; ++i)
    if (is_buffer(P.kind[i])) {
      buffer_.push_back(static_cast<std::uint32_t>(i));
      buffer_zone_.push_back(zone_of(s.prm, P.x[i], P.kind[i]));
    }
  // The grid is binned at this step's positions; the ghost point's candidates are the particles of
  // the 3x3 cells round it, in the grid's fixed order.
  const GridGeometry& g = grid.geometry();
  const std::uint32_t* sorted = grid.sorted().data();
  const std::uint32_t* cell_start = grid.cell_start().data();
  const real h = s.prm.h, h2 = h * h;
  std::vector<std::uint32_t>& js = fit_j_;
  std::vector<Vec2>& d = fit_d_;
  std::vector<real>& w = fit_w_;
  for (std::size_t k = 0; k < buffer_.size(); ++k) {
    const std::size_t b = buffer_[k];
    js.clear();
    d.clear();
    w.clear();
    if (buffer_zone_[k] >= 0) {
      const OpenZone& z = s.prm.open[static_cast<std::size_t>(buffer_zone_[k])];
      const Vec2 xg = open_ghost_point(z, P.x[b]);
      int first[9], last[9];
      const int runs = g.neighbor_cell_runs(g.cell_index(xg), first, last);
      for (int r = 0; r < runs; ++r)
        for (std::uint32_t q = cell_start[first[r]]; q < cell_start[last[r] + 1]; ++q) {
          const std::uint32_t j = sorted[q];
          if (P.kind[j] != Kind::Fluid) continue;  // the fit reads the fluid only (Tafuni et al. 2018)
          const Vec2 rj = s.domain.separation(P.x[j], xg);
          const real r2 = norm2(rj);
          if (!(r2 < h2)) continue;
          js.push_back(j);
          d.push_back(rj / h);
          w.push_back(P.m[j] / P.rho[j] * s.kernel.W(std::sqrt(r2)));  // V_j = m_j / rho_j
        }
      real y0[3], y1[3];
      const Vec2 e = (P.x[b] - xg) / h;
      if (linear_fit_targets(d, w, e, y0, y1)) {
        for (std::size_t q = 0; q < js.size(); ++q) {
          ghost_j_.push_back(js[q]);
          ghost_val_.push_back(w[q] * (y0[0] + y0[1] * d[q].x + y0[2] * d[q].y));
          ghost_lin_.push_back(w[q] * (y1[0] + y1[1] * d[q].x + y1[2] * d[q].y));
        }
      } else {
        // Too few fluid particles round the ghost point for a plane: their Shepard mean.
        ++cnt.open_fit_fallback;
        real sw = 0;
        for (const real wq : w) sw += wq;
        for (std::size_t q = 0; q < js.size() && sw > 0; ++q) {
          ghost_j_.push_back(js[q]);
          ghost_val_.push_back(w[q] / sw);
          ghost_lin_.push_back(w[q] / sw);
        }
      }
    }
    ghost_start_.push_back(static_cast<std::uint32_t>(ghost_j_.size()));
  }
}

void OpenBoundaries::set_velocities(const OpenScene& s, Particles& P, real t_mid) const {
  for (std::size_t k = 0; k < buffer_.size(); ++k) {
    if (buffer_zone_[k] < 0) continue;
    const std::size_t b = buffer_[k], zi = static_cast<std::size_t>(buffer_zone_[k]);
    const OpenZone& z = s.prm.open[zi];
    if (z.inlet) {
      P.v[b] = inlet_speed(s.prm, zi, open_along(z, P.x[b]), t_mid) * z.n;
      continue;
    }
    // Outlet: the fluid's velocity at the ghost point (an even mirror, dV/dn = 0 at the line).
    if (ghost_start_[k] == ghost_start_[k + 1]) continue;
    Vec2 v;
    for (std::uint32_t q = ghost_start_[k]; q < ghost_start_[k + 1]; ++q)
      v += ghost_val_[q] * P.v[ghost_j_[q]];
    P.v[b] = v;
  }
}

void OpenBoundaries::set_pressures(const OpenScene& s, Particles& P) const {
  for (std::size_t k = 0; k < buffer_.size(); ++k) {
    if (buffer_zone_[k] < 0 || ghost_start_[k] == ghost_start_[k + 1]) continue;
    const std::size_t b = buffer_[k];
    const OpenZone& z = s.prm.open[static_cast<std::size_t>(buffer_zone_[k])];
    real p_ghost = 0, p_lin = 0;
    for (std::uint32_t q = ghost_start_[k]; q < ghost_start_[k + 1]; ++q) {
      const real pj = P.p[ghost_j_[q]];
      p_ghost += ghost_val_[q] * pj;
      p_lin += ghost_lin_[q] * pj;
    }
    // Inlet: the fluid's pressure continued linearly to the particle; outlet: the line's pressure.
    P.p[b] = z.inlet ? p_lin : outlet_buffer_pressure(z.pressure, p_ghost);
    P.rho[b] = density_from_pressure(P.p[b], s.prm.rho0, s.prm.c, s.prm.p0);
  }
}

void OpenBoundaries::move(const OpenScene& s, Particles& P, real dt) const {
  for (std::size_t k = 0; k < buffer_.size(); ++k) {
    if (buffer_zone_[k] < 0) continue;
    const std::size_t b = buffer_[k];
    const OpenZone& z = s.prm.open[static_cast<std::size_t>(buffer_zone_[k])];
    // Both ways at an outlet: where the fluid flows back in (a pressure wave's reflection, a vortex
    // crossing the line) its buffer follows it, and open_transfer refills the back.
    P.x[b] += (dt * dot(P.v[b], z.n)) * z.n;
  }
}

void OpenBoundaries::transfer(const OpenScene& s, Particles& P) {
  if (s.prm.open.empty()) return;
  const std::size_t n = P.size(), nb = P.n_boundary;
  std::vector<CreatedParticle>& created = created_;
  created.clear();
  std::vector<unsigned char>& keep = keep_;
  keep.assign(n, 1);
  for (std::size_t i = nb; i < n; ++i) {
    const Kind k = P.kind[i];
    const Vec2 x = P.x[i];
    if (k == Kind::Fluid) {
      for (std::size_t z = 0; z < s.prm.open.size(); ++z) {
        if (!beyond_open_line(s.prm.open[z], x)) continue;
        OpenFlux& f = flux_[z];
        if (s.prm.open[z].inlet) {  // fluid leaving through an inlet: removed and counted
          keep[i] = 0;
          f.backflow_mass += P.m[i];
          ++f.deleted;
        } else {  // fluid leaving through an outlet joins its buffer
          P.kind[i] = Kind::Outlet;
          f.mass += P.m[i];
        }
        break;
      }
      continue;
    }
    if (!is_buffer(k)) continue;
    const int zi = zone_of(s.prm, x, k);
    if (zi < 0) {  // cannot happen for a particle that moves along its zone's normal; removed if it does
      keep[i] = 0;
      continue;
    }
    const OpenZone& z = s.prm.open[static_cast<std::size_t>(zi)];
    OpenFlux& f = flux_[static_cast<std::size_t>(zi)];
    const real xi = open_depth(z, x);
    if (xi >= 0) {
      // A buffer particle entered the fluid: it becomes fluid, and a new particle with its fields
      // and mass takes its place one buffer depth behind, so that a buffer moving in keeps its
      // particles (an inlet's column keeps its spacing; an outlet's buffer, which the fluid filled
      // in no order, is refilled at its back with the pattern that left its front). At an outlet
      // this is fluid flowing back in: counted as its backflow, which the outflow nets against.
      P.kind[i] = Kind::Fluid;
      (k == Kind::Inlet ? f.mass : f.backflow_mass) += P.m[i];
      ++f.created;
      created.push_back({x - z.depth * z.n, P.v[i], P.p[i], P.rho[i], P.m[i], k});
    } else if (k == Kind::Outlet && xi < -z.depth) {
      keep[i] = 0;
      ++f.deleted;
    }
  }
  // Stable compaction of the fluid block, then the created particles at its end: the order is a
  // function of the state alone, so a resumed run repeats it exactly.
  std::size_t to = nb;
  for (std::size_t i = nb; i < n; ++i) {
    if (!keep[i]) continue;
    if (to != i) {
      P.x[to] = P.x[i];
      P.v[to] = P.v[i];
      P.rho[to] = P.rho[i];
      P.p[to] = P.p[i];
      P.m[to] = P.m[i];
      P.kind[to] = P.kind[i];
      P.group[to] = P.group[i];
      P.id[to] = P.id[i];
    }
    ++to;
  }
  if (to == n && created.empty()) return;
  P.resize(to);
  append_created(P, created);
}

void OpenBoundaries::append_created(Particles& P, const std::vector<CreatedParticle>& created) {
  std::size_t to = P.size();
  P.resize(to + created.size());
  for (const CreatedParticle& c : created) {
    P.x[to] = c.x;
    P.v[to] = c.v;
    P.p[to] = c.p;
    P.rho[to] = c.rho;
    P.m[to] = c.m;
    P.kind[to] = c.kind;
    P.group[to] = -1;
    P.id[to] = P.next_id++;
    ++to;
  }
}

// ---------------------------------------------------------------------------------------------
// Bodies removed at outlets (outlet[].bodies = "removed"; docs/method.md, "Bodies removed at an
// outlet")

void OpenBoundaries::remove_bodies_at_outlets(const OpenScene& s, Particles& P, std::vector<RigidGroup>& groups,
                                              real t) {
  removed_now_.clear();
  if (s.prm.open.empty()) return;
  for (std::size_t k = 0; k < groups.size(); ++k) {
    const RigidGroup& g = groups[k];
    if (g.is_wall || g.removed || g.motion == Motion::Fixed) continue;
    for (std::size_t z = 0; z < s.prm.open.size(); ++z) {
      if (!removes_bodies(s.prm, z)) continue;
      // the body's surface has reached the line where a screen would hold it back
      const Contact c =
          wall_contact_exact(placed_body(s.prm, g), s.prm.open_screens[z]);
      if (!(c.gap <= 0)) continue;
      remove_body(s, P, groups, k, z, t);
      break;
    }
  }
}

namespace {

/// The pressure at x in the place of the body whose surface particles are [first, first + count):
/// their P.20 pressures carried inwards by the momentum balance of fluid that moves with the body,
/// grad P = rho0 (f - a(x)), weighted by inverse squared distance and surface length (every
/// surface particle counts, so that no point deep inside is left without a value).
real pressure_in_place_of(const OpenScene& s, const Particles& P, std::size_t first, std::size_t count, Vec2 x) {
  Vec2 f = s.prm.body_force;
  if (s.prm.gravity_in_fluid) f += s.prm.gravity;
  real num = 0, den = 0;
  for (std::size_t i = first; i < first + count; ++i) {
    if (P.kind[i] != Kind::Boundary) continue;
    const Vec2 d = s.domain.separation(x, P.x[i]);
    const real w = P.ds[i] / (dot(d, d) + real(1e-4) * s.prm.d0 * s.prm.d0);
    num += w * (P.p[i] + s.prm.rho0 * dot(f - P.acc[i], d));
    den += w;
  }
  return den > 0 ? num / den : s.prm.p0;
}

/// The fill of a body's place: the points of the fluid lattice (spacing d0 from the domain's
/// corner) at least d0/2 inside the body, as the scene keeps fluid at least d0/2 outside it; a body
/// too thin for any gets the points inside it, or one particle at its centroid.
std::vector<Vec2> fill_points(const OpenScene& s, const Shape& shape, const RigidGroup& g) {
  const GroupMotion mo = group_motion(g);
  const Domain& dom = s.domain;
  std::vector<Vec2> fill;
  const real R = shape.bounding_radius(), d0 = s.prm.d0;
  for (const real depth : {0.5 * d0, 0.0}) {
    const auto i0 = static_cast<long>(std::floor((g.pos.x - R - dom.lo.x) / d0));
    const auto j0 = static_cast<long>(std::floor((g.pos.y - R - dom.lo.y) / d0));
    const auto i1 = static_cast<long>(std::ceil((g.pos.x + R - dom.lo.x) / d0));
    const auto j1 = static_cast<long>(std::ceil((g.pos.y + R - dom.lo.y) / d0));
    for (long j = j0; j <= j1; ++j)
      for (long i = i0; i <= i1; ++i) {
        const Vec2 x{dom.lo.x + (static_cast<real>(i) + 0.5) * d0, dom.lo.y + (static_cast<real>(j) + 0.5) * d0};
        const Vec2 rel = dom.separation(x, g.pos);
        if (shape.signed_distance(rotate(rel, mo.cos_angle, -mo.sin_angle)) <= -depth) fill.push_back(dom.wrap(x));
      }
    if (!fill.empty()) break;
  }
  if (fill.empty()) fill.push_back(g.pos);
  return fill;
}

/// Takes particles [first, first + count) out of the boundary block; the later groups and the
/// dummies' sources move down by `count`.
void erase_boundary_range(Particles& P, std::vector<RigidGroup>& groups, std::size_t k, std::size_t first,
                          std::size_t count) {
  const auto erase = [&](auto& v) {
    v.erase(v.begin() + static_cast<std::ptrdiff_t>(first), v.begin() + static_cast<std::ptrdiff_t>(first + count));
  };
  erase(P.x);
  erase(P.v);
  erase(P.rho);
  erase(P.p);
  erase(P.m);
  erase(P.kind);
  erase(P.group);
  erase(P.id);
  erase(P.local);
  erase(P.normal_local);
  erase(P.ds);
  erase(P.acc);
  erase(P.normal);
  erase(P.wedge);
  erase(P.source);
  P.n_boundary -= count;
  for (std::int32_t& src : P.source)
    if (src >= static_cast<std::int32_t>(first + count)) src -= static_cast<std::int32_t>(count);
  for (std::size_t q = k + 1; q < groups.size(); ++q) groups[q].first -= count;
}

/// A removed body's group: no particles, at rest, no loads; where and when it left.
void mark_removed(RigidGroup& g, std::size_t zone, real t) {
  g.count = 0;
  g.removed = true;
  g.removed_at = static_cast<std::int32_t>(zone);
  g.removed_time = t;
  g.vel = g.acc = g.vel_n = Vec2{};
  g.omega = g.alpha = g.omega_n = 0;
  g.force_pressure = g.force_viscous = g.force_collision = g.force_damping = Vec2{};
  g.torque = g.torque_collision = 0;
  g.contact_speed = 0;
}

}  // namespace

void OpenBoundaries::remove_body(const OpenScene& s, Particles& P, std::vector<RigidGroup>& groups, std::size_t k,
                                 std::size_t z, real t) {
  RigidGroup& g = groups[k];
  const BodyParams& b = s.prm.bodies[static_cast<std::size_t>(g.body)];
  const std::size_t first = g.first, count = g.count;
  // The fill carries the fluid of the body's whole area, so that the fluid fills the region
  // again exactly, with the pressure of the body's place and the body's rigid velocity.
  const std::vector<Vec2> fill = fill_points(s, b.shape, g);
  std::vector<CreatedParticle> made;
  made.reserve(fill.size());
  real fill_mass = 0;
  for (const Vec2 x : fill) {
    const real p = pressure_in_place_of(s, P, first, count, x);
    const real rho = density_from_pressure(p, s.prm.rho0, s.prm.c, s.prm.p0);
    const Vec2 r = s.domain.separation(x, g.pos);
    const real m = rho * b.shape.area() / static_cast<real>(fill.size());
    made.push_back({x, g.vel + g.omega * Vec2{-r.y, r.x}, p, rho, m, Kind::Fluid});
    fill_mass += m;
  }
  erase_boundary_range(P, groups, k, first, count);
  mark_removed(g, z, t);
  // The fill joins the fluid block at its end, with new ids.
  append_created(P, made);
  OpenFlux& fl = flux_[z];
  ++fl.bodies_removed;
  fl.body_fill_mass += fill_mass;
  removed_now_.push_back({k, z, made.size(), fill_mass});
}

}  // namespace particula
