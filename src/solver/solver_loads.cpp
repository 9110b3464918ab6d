// Hydrodynamic loads on the rigid groups (walls and bodies): the paper's surface sum
// (P.26-P.27) or the band momentum balance of solver/momentum_loads.hpp.
#include <algorithm>
#include <cmath>
#include <limits>

#include <omp.h>

#include "particula/solver/solver.hpp"

namespace particula {

void Solver::group_loads() {
  if (prm_.momentum_force) return momentum_group_loads();
  const real mu = prm_.nu * prm_.rho0;
  if (dev_) {
    dev_->group_loads(groups_, mu, loads_);
    for (std::size_t k = 0; k < groups_.size(); ++k) {
      groups_[k].force_pressure = loads_[k].force_pressure;
      groups_[k].force_viscous = loads_[k].force_viscous;
      groups_[k].torque = loads_[k].torque;
    }
    return;
  }
  for (auto& g : groups_) {
    Vec2 fp, fv;
    real torque = 0;
    for (std::size_t i = g.first; i < g.first + g.count; ++i) {
      if (P_.kind[i] != Kind::Boundary) continue;
      Vec2 tp, tv;
      surface_traction(P_.p[i], P_.ds[i], P_.normal[i], gradV_[i], mu, tp, tv);
      fp += tp;
      fv += tv;
      torque += cross(domain_.separation(P_.x[i], g.pos), tp + tv);
    }
    g.force_pressure = fp;
    g.force_viscous = fv;
    g.torque = torque;
  }
}

WallPiece Solver::wall_at(std::size_t k, real angle) const {
  const RigidGroup& g = groups_[k];
  if (angle == g.angle0) return prm_.walls[k];
  return prm_.walls[k].moved(g.pos0, angle - g.angle0, Vec2{});
}

bool Solver::offer_near_solid(Vec2 x, real reach, std::size_t k, NearSolid& out) const {
  const RigidGroup& g = groups_[k];
  real d = 0;
  Vec2 n;
  if (g.is_wall) {
    // Distance to the wall, from x's periodic image nearest the wall's middle (an arc's
    // centre), so that a wall spanning a periodic side is found from either end.
    const WallPiece& w = band_walls_[k];
    const Vec2 rel = domain_.separation(x, w.middle());
    if (w.surely_farther(rel, reach)) return false;
    const Vec2 xi = w.middle() + rel;
    const WallNearest near = w.nearest(xi);
    d = near.distance;
    if (!(d < reach)) return false;
    n = d > 1e-12 * w.length() ? (xi - near.point) / d : near.normal;
  } else {
    const BodyParams& b = prm_.bodies[static_cast<std::size_t>(g.body)];
    const Vec2 rel = domain_.separation(x, band_pos_[k]);
    // Most of the bodies offered lie beyond the reach: those are rejected from the squared
    // distance, without a square root. The margin keeps the decision that of norm(rel) > outer.
    const real outer = b.shape.bounding_radius() + reach;
    if (norm2(rel) > outer * outer * (1 + 1e-10) || norm(rel) > outer) return false;
    const real c = band_turn_[k].x, s = band_turn_[k].y;
    Vec2 nl;
    b.shape.distance_and_gradient(rotate(rel, c, -s), d, nl);
    if (!(d < reach)) return false;
    n = rotate(nl, c, s);
  }
  out = NearSolid{static_cast<std::int32_t>(k), std::max(d, real(0)), n};
  return true;
}

void Solver::place_solids_for_band() {
  // Each wall at the band's pose and each body's cos / sin of its angle, once a build rather
  // than once per fluid particle (the same values: the band is bitwise what it was when each
  // particle computed them).
  band_walls_.clear();
  band_turn_.assign(groups_.size(), Vec2{});
  for (std::size_t k = 0; k < groups_.size(); ++k) {
    if (groups_[k].is_wall)
      band_walls_.push_back(wall_at(k, band_angle_[k]));
    else
      band_turn_[k] = Vec2{std::cos(band_angle_[k]), std::sin(band_angle_[k])};
  }
}

void Solver::bin_bodies_for_band(real reach) {
  // Cells at least (largest bounding radius + reach) wide: a particle's solids are among the
  // bodies of its own and the 8 surrounding cells.
  real bound = 0;
  band_body_items_.clear();
  for (std::size_t k = 0; k < groups_.size(); ++k) {
    const RigidGroup& g = groups_[k];
    if (g.is_wall || g.removed) continue;
    bound = std::max(bound, prm_.bodies[static_cast<std::size_t>(g.body)].shape.bounding_radius());
    band_body_items_.push_back({static_cast<std::uint32_t>(k), band_pos_[k]});
  }
  band_bodies_.build(domain_, bound + reach, band_body_items_);
}

int Solver::near_solids(Vec2 x, real reach, NearSolid* out, int max) const {
  int count = 0;
  for (std::size_t k = 0; k < groups_.size() && groups_[k].is_wall && count < max; ++k)
    if (offer_near_solid(x, reach, k, out[count])) ++count;
  if (count < max)
    band_bodies_.visit(x, [&](std::uint32_t k) {
      if (offer_near_solid(x, reach, k, out[count])) ++count;
      return count < max;
    });
  return count;
}

real Solver::band_cell_area(std::size_t i, const std::vector<Vec2>& x, const NeighborList& nl) const {
  const std::size_t nb = P_.n_boundary;
  Vec2 d[kVoronoiMaxVertices - 4];
  int count = 0;
  bool closed_by_fluid = true;
  auto take = [&](std::uint32_t j) {
    if (j < nb || count == kVoronoiMaxVertices - 4) {
      closed_by_fluid = false;
      return;
    }
    d[count++] = domain_.separation(x[j], x[i]);
  };
  if (dev_) {
    visit_neighbors(band_grid_.geometry(), prm_.h * prm_.h, x.data(), band_grid_.sorted().data(),
                    band_grid_.cell_start().data(), band_grid_.cell_of()[i], static_cast<std::uint32_t>(i),
                    [&](std::uint32_t j, real) { take(j); });
  } else {
    // The neighbour list built at these positions from the same cells: the same neighbours
    // within h in the same order (visit_neighbors), without a second search.
    for (std::uint32_t s = nl.start[i]; s < nl.start[i + 1]; ++s) take(nl.j[s]);
  }
  return closed_by_fluid ? voronoi_cell_area(d, count, prm_.h) : 0;
}

namespace {

/// The kept band's motion limit of a particle between two solids the local gap g = d_B + d_C
/// apart (g at least `floor`), squared: its partition phi_B ~ 1 / (1 + (d_B / d_C)^4) changes
/// by about 4 delta / g when it moves by delta.
real band_moved_limit2(real gap, real limit, real floor) {
  const real l = std::min(limit, kBandGapShare * std::max(gap, floor));
  return l * l;
}

/// The local gap at a fluid particle: its distance to its closest solid plus that to the closest
/// solid facing it across the particle (distance gradients more than 120 degrees apart, as the
/// surface guard's `facing`), or infinity. The next piece of the same wall, or the other wall of
/// a corner, is not a gap.
real facing_gap(const NearSolid* near, int count, int closest) {
  real other = std::numeric_limits<real>::infinity();
  for (int k = 0; k < count; ++k)
    if (k != closest && dot(near[k].n, near[closest].n) < -0.5) other = std::min(other, near[k].d);
  return near[closest].d + other;
}

}  // namespace

void Solver::build_load_band(const std::vector<Vec2>& x, const NeighborList& nl) {
  ++band_builds_;
  const real reach = kLoadBandReach * prm_.h;
  const std::size_t nb = P_.n_boundary, nf = x.size() - nb;
  constexpr int kMaxNear = 16;
  bin_bodies_for_band(reach);
  place_solids_for_band();
  if (dev_) {
    // the device's neighbour list stays on the device: bin the downloaded positions here
    band_grid_.setup(domain_, prm_.h);  // a few numbers: cheaper than checking
    band_grid_.bin(x);
  }
  // One pass: each thread takes a contiguous range of fluid particles and lists their entries in
  // particle order; the threads' lists are then joined in thread order, so the band is in
  // particle order whatever the thread count.
  const std::size_t threads = static_cast<std::size_t>(omp_get_max_threads());
  band_parts_.resize(threads);
  band_part_first_.assign(threads + 1, 0);
  const real film = kFilmGap * prm_.h;
  // numerics.load_band_motion: each particle's limit, squared (band_moved_limit2)
  const real kept_limit = prm_.open.empty() ? prm_.load_band_motion : 0;
  if (kept_limit > 0) {
    band_limit2_.assign(x.size(), kept_limit * kept_limit);
    band_anchor_.assign(x.size(), -1);
  }
#pragma omp parallel num_threads(static_cast<int>(threads))
  {
    const std::size_t t = static_cast<std::size_t>(omp_get_thread_num()),
                      nt = static_cast<std::size_t>(omp_get_num_threads());
    std::vector<BandEntry>& part = band_parts_[t];
    part.clear();
    NearSolid near[kMaxNear];
    for (std::size_t f = nf * t / nt; f < nf * (t + 1) / nt; ++f) {
      // buffer particles of open boundaries are set, not integrated: they carry no momentum balance
      const int count = in_load_band(nb + f) ? near_solids(x[nb + f], reach, near, kMaxNear) : 0;
      if (count == 0) continue;
      const real area = band_cell_area(nb + f, x, nl);
      weigh_near_solids(near, count, reach);
      real S;
      Vec2 gradS;
      band_partition_sum(near, count, reach, S, gradS);
      // the particle is in a film between solid k and another when d_k plus the smallest
      // distance to another solid is below kFilmGap h
      int closest = 0;
      for (int k = 1; k < count; ++k)
        if (near[k].d < near[closest].d) closest = k;
      real second = std::numeric_limits<real>::infinity();
      for (int k = 0; k < count; ++k)
        if (k != closest && near[k].d < second) second = near[k].d;
      if (kept_limit > 0) {
        band_anchor_[nb + f] = near[closest].group;
        if (count > 1)
          band_limit2_[nb + f] =
              band_moved_limit2(facing_gap(near, count, closest), kept_limit, kBandGapFloor * prm_.d0);
      }
      for (int k = 0; k < count; ++k) {
        BandEntry e;
        e.particle = static_cast<std::uint32_t>(nb + f);
        e.group = near[k].group;
        band_partition_of(near[k], S, gradS, reach, e.phi, e.grad_phi);
        e.area = area;
        e.in_film = near[k].d + (k == closest ? second : near[closest].d) < film;
        part.push_back(e);
      }
    }
    band_part_first_[t + 1] = part.size();
#pragma omp barrier
#pragma omp single
    {
      for (std::size_t u = 0; u < nt; ++u) band_part_first_[u + 1] += band_part_first_[u];
      band_.resize(band_part_first_[nt]);
    }
    std::copy(part.begin(), part.end(), band_.begin() + static_cast<std::ptrdiff_t>(band_part_first_[t]));
  }
  assign_band_slots();
  if (dev_) dev_->set_load_band(band_);
}

void Solver::assign_band_slots() {
  // Each block of kBandBlock entries numbers the groups it holds in the order they first appear
  // (BandEntry::slot); band_block_first_[b] is where block b's groups start in band_slot_group_.
  const std::size_t ne = band_.size(), nblocks = (ne + kBandBlock - 1) / kBandBlock;
  band_block_first_.assign(nblocks + 1, 0);
#pragma omp parallel
  {
    std::vector<std::int32_t> slot_of(groups_.size(), -1);
#pragma omp for schedule(static)
    for (std::size_t b = 0; b < nblocks; ++b) {
      const std::size_t e0 = b * kBandBlock, e1 = std::min(ne, e0 + kBandBlock);
      std::int32_t count = 0;
      for (std::size_t e = e0; e < e1; ++e) {
        std::int32_t& slot = slot_of[static_cast<std::size_t>(band_[e].group)];
        if (slot < 0) slot = count++;
        band_[e].slot = static_cast<std::uint16_t>(slot);
      }
      for (std::size_t e = e0; e < e1; ++e) slot_of[static_cast<std::size_t>(band_[e].group)] = -1;
      band_block_first_[b + 1] = static_cast<std::size_t>(count);
    }
  }
  for (std::size_t b = 0; b < nblocks; ++b) band_block_first_[b + 1] += band_block_first_[b];
  band_slot_group_.resize(band_block_first_[nblocks]);
#pragma omp parallel for schedule(static)
  for (std::size_t b = 0; b < nblocks; ++b)
    for (std::size_t e = b * kBandBlock; e < std::min(ne, (b + 1) * kBandBlock); ++e)
      band_slot_group_[band_block_first_[b] + band_[e].slot] = band_[e].group;
}

template <class T, class BlockSum>
void Solver::sum_band(std::vector<T>& partial, std::vector<T>& total, BlockSum block_sum) const {
  // Each block's sum per group (slots), in parallel, then the blocks' sums added per group in
  // block order: one fixed order of additions whatever the thread count.
  const std::size_t ne = band_.size(), nblocks = band_block_first_.size() - 1;
  partial.assign(band_block_first_[nblocks], T{});
#pragma omp parallel for schedule(static)
  for (std::size_t b = 0; b < nblocks; ++b)
    block_sum(b * kBandBlock, std::min(ne, (b + 1) * kBandBlock), partial.data() + band_block_first_[b]);
  total.assign(groups_.size(), T{});
  for (std::size_t s = 0; s < partial.size(); ++s) total[static_cast<std::size_t>(band_slot_group_[s])] += partial[s];
}

LoadArrays Solver::load_arrays() const {
  LoadArrays a;
  a.domain = domain_;
  a.x = P_.x.data();
  a.m = P_.m.data();
  a.rho = P_.rho.data();
  a.p = P_.p.data();
  a.grad_v = gradV_.data();
  a.lap_v = lapV_.data();
  // the damping's accelerations of the stage (rhie_chow_and_momentum; on a device, the device's own
  // array: CudaBackend::device_load_arrays)
  a.odd_even = prm_.odd_even_damping > 0 && odd_even_.size() == P_.size() ? odd_even_.data() : nullptr;
  a.grad_p_over_rho = G_.data();
  a.group_pos = group_pos_.data();
  a.group_level = group_level_.data();
  a.mu = prm_.nu * prm_.rho0;
  a.nu = prm_.nu;
  a.rho0 = prm_.rho0;
  a.c2 = prm_.c * prm_.c;
  a.p0 = prm_.p0;
  // The smooth pressure taken out of the stress: hydrostatic for gravity in the fluid and for a
  // body force along a closed side (along a periodic side no mean pressure gradient exists).
  Vec2 g = prm_.body_force;
  if (prm_.gravity_in_fluid) g += prm_.gravity;
  if (domain_.periodic_x) g.x = 0;
  if (domain_.periodic_y) g.y = 0;
  a.g_h = g;
  a.x_ref = domain_.lo;
  return a;
}

void Solver::momentum_group_loads() {
  const std::size_t ng = groups_.size(), ne = band_.size();
  group_pos_.resize(ng);
  for (std::size_t k = 0; k < ng; ++k) group_pos_[k] = groups_[k].pos;
  group_level_.assign(ng, prm_.rho0 * prm_.c * prm_.c);  // P_h = p0 for a group without fluid near it
  const LoadArrays a = load_arrays();
  // On the CPU each particle's sample is read once for all its entries (consecutive in the band)
  // and each entry evaluated inside its block's sum; the device evaluates every entry and the
  // host sums its results in the same blocks.
  // Pass 1: each group's level K_B, the smooth field that best matches the fluid in its band
  // (the pressure's constant is set by the fluid's mass in a closed box: a P_h off by a
  // constant C adds C times the band's quadrature error of int grad(phi) = 0).
  if (dev_) {
    band_fp_.resize(ne);
    dev_->band_levels(a, band_fp_);  // (num, den) per entry
  }
  sum_band(band_level_partial_, band_level_total_, [&](std::size_t e0, std::size_t e1, Vec2* sums) {
    std::uint32_t sampled = std::numeric_limits<std::uint32_t>::max();
    BandSample s;
    for (std::size_t e = e0; e < e1; ++e) {
      const BandEntry& be = band_[e];
      Vec2 nd;
      if (dev_) {
        nd = band_fp_[e];
      } else {
        if (be.particle != sampled) s = band_sample(a, sampled = be.particle, be.area);
        band_share_level(s, be.phi, nd.x, nd.y);
      }
      sums[be.slot] += nd;
    }
  });
  for (std::size_t k = 0; k < ng; ++k)
    if (band_level_total_[k].y > 0) group_level_[k] = band_level_total_[k].x / band_level_total_[k].y;
  // Pass 2: the loads of the entries, summed per group. A circle takes no torque from pressure
  // about its centre (P r x n = 0 on its surface), and the band's pressure torque, exact in the
  // continuum and resolved elsewhere, is not in a film between the circle and another surface
  // thinner than about two spacings: P grad(phi) there is normal to the film, not to the circle,
  // and nothing in the unresolved film cancels its moment (docs/method-notes.md, "Forces on
  // solids"). So a circle takes only the viscous part of the torque of its entries in such a film.
  group_circle_.resize(ng);
  for (std::size_t k = 0; k < ng; ++k)
    group_circle_[k] = !groups_[k].is_wall &&
                       prm_.bodies[static_cast<std::size_t>(groups_[k].body)].shape.kind() == ShapeKind::Circle;
  if (dev_) {
    band_fp_.resize(ne);
    band_fv_.resize(ne);
    band_torque_.resize(ne);
    band_fd_.resize(ne);
    dev_->band_loads(a, group_pos_, group_level_, band_fp_, band_fv_, band_torque_, band_fd_);
  }
  sum_band(band_load_partial_, band_load_total_, [&](std::size_t e0, std::size_t e1, BandLoadSum* sums) {
    std::uint32_t sampled = std::numeric_limits<std::uint32_t>::max();
    BandSample s;
    for (std::size_t e = e0; e < e1; ++e) {
      const BandEntry& be = band_[e];
      Vec2 efp, efv, et, efd;
      if (dev_) {
        efp = band_fp_[e];
        efv = band_fv_[e];
        et = band_torque_[e];
        efd = band_fd_[e];
      } else {
        if (be.particle != sampled) s = band_sample(a, sampled = be.particle, be.area);
        band_entry_share(a, s, be, efp, efv, et);
        efd = band_share_damping(s, be.phi);
      }
      BandLoadSum& sum = sums[be.slot];
      sum.fp += efp;
      sum.fv += efv;
      sum.fd += efd;
      sum.torque += group_circle_[static_cast<std::size_t>(be.group)] && be.in_film ? et.y : et.x + et.y;
    }
  });
#pragma omp parallel for schedule(dynamic)
  for (std::size_t k = 0; k < ng; ++k) {
    RigidGroup& g = groups_[k];
    Vec2 fp;
    real torque = 0;
    smooth_pressure_load(a, k, fp, torque);
    g.force_pressure = fp + band_load_total_[k].fp;
    g.force_viscous = band_load_total_[k].fv;
    g.force_damping = band_load_total_[k].fd;
    g.torque = torque + band_load_total_[k].torque;
  }
}

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

void Solver::smooth_pressure_load(const LoadArrays& a, std::size_t k, Vec2& force, real& torque) const {
  const RigidGroup& g = groups_[k];
  const std::int32_t gk = static_cast<std::int32_t>(k);
  const auto p_h = [&](Vec2 x) { return smooth_pressure(a, gk, x); };
  force = Vec2{};
  torque = 0;
  if (g.removed) return;
  if (g.is_wall) {
    // -n int P_h ds over the wall's wetted stretches: not where a fixed body stands on it or
    // crosses it (the body carries those, below).
    std::vector<std::pair<real, real>> dry;
    for (const BodyParams& b : prm_.bodies)
      for (const BodyParams::Cover& c : b.covers)
        if (c.wall == k) dry.emplace_back(c.s0, c.s1);
    std::sort(dry.begin(), dry.end());
    const WallPiece w = wall_now(k);
    real s = 0;
    for (const auto& [d0, d1] : dry) {
      wall_stretch_load(w, s, d0, p_h, domain_, g.pos, force, torque);
      s = std::max(s, d1);
    }
    wall_stretch_load(w, s, 1, p_h, domain_, g.pos, force, torque);
    return;
  }
  const BodyParams& b = prm_.bodies[static_cast<std::size_t>(g.body)];
  if (b.motion == BodyMotion::Fixed && (!b.covers.empty() || b.area_in != b.shape.area())) {
    // A fixed body standing on walls or crossing them: its wetted surface and the wall stretches
    // it covers close its part in the fluid region (area A_in), so by Gauss's theorem
    // -int_wetted P_h n ds = -rho_h g_h A_in - int_covered P_h n_wall ds.
    const Vec2 f_area =
        (-a.group_level[k] * smooth_pressure_shape(a, b.centroid_in) / a.c2 * b.area_in) * a.g_h;
    force = f_area;
    torque = cross(domain_.separation(b.centroid_in, g.pos), f_area);
    for (const BodyParams::Cover& c : b.covers)
      wall_stretch_load(wall_now(c.wall), c.s0, c.s1, p_h, domain_, g.pos, force, torque);
    return;
  }
  std::size_t surface = 0;
  for (std::size_t i = g.first; i < g.first + g.count; ++i) surface += P_.kind[i] == Kind::Boundary;
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
    if (P_.kind[i] != Kind::Boundary) continue;
    const Vec2 xs = surface_position(domain_, mo, P_.local[i]);
    const Vec2 t =
        (-smooth_pressure(a, gk, xs) * P_.ds[i]) * rotate(P_.normal_local[i], mo.cos_angle, mo.sin_angle);
    force += t;
    torque += cross(domain_.separation(xs, g.pos), t);
  }
}

}  // namespace particula
