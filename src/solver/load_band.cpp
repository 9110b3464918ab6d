// The band of the momentum loads (solver/load_band.hpp): its build and its sums per stage (when
// a kept band is rebuilt: load_band_motion.cpp).
#include "particula/solver/load_band.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "particula/solver/backend.hpp"

namespace particula {

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

/// Whether fluid-block particle i takes part in the band momentum balance (not a buffer particle
/// of an open boundary: those are set, not integrated).
bool in_load_band(const BandScene& s, std::size_t i) {
  return s.prm.open.empty() || !is_buffer(s.particles.kind[i]);
}

}  // namespace

bool LoadBand::offer_near_solid(const BandScene& s, Vec2 x, real reach, std::size_t k, NearSolid& out) const {
  const RigidGroup& g = s.groups[k];
  real d = 0;
  Vec2 n;
  if (g.is_wall) {
    // Distance to the wall, from x's periodic image nearest the wall's middle (an arc's
    // centre), so that a wall spanning a periodic side is found from either end.
    const WallPiece& w = walls_[k];
    const Vec2 rel = s.domain.separation(x, w.middle());
    if (w.surely_farther(rel, reach)) return false;
    const Vec2 xi = w.middle() + rel;
    const WallNearest near = w.nearest(xi);
    d = near.distance;
    if (!(d < reach)) return false;
    n = d > 1e-12 * w.length() ? (xi - near.point) / d : near.normal;
  } else {
    const BodyParams& b = s.prm.bodies[static_cast<std::size_t>(g.body)];
    const Vec2 rel = s.domain.separation(x, pos_[k]);
    // Most of the bodies offered lie beyond the reach: those are rejected from the squared
    // distance, without a square root. The margin keeps the decision that of norm(rel) > outer.
    const real outer = b.shape.bounding_radius() + reach;
    if (norm2(rel) > outer * outer * (1 + 1e-10) || norm(rel) > outer) return false;
    const real c = turn_[k].x, sn = turn_[k].y;
    Vec2 nl;
    b.shape.distance_and_gradient(rotate(rel, c, -sn), d, nl);
    if (!(d < reach)) return false;
    n = rotate(nl, c, sn);
  }
  out = NearSolid{static_cast<std::int32_t>(k), std::max(d, real(0)), n};
  return true;
}

void LoadBand::place_solids(const BandScene& s) {
  // Each wall at the band's pose and each body's cos / sin of its angle, once a build rather
  // than once per fluid particle.
  walls_.clear();
  turn_.assign(s.groups.size(), Vec2{});
  for (std::size_t k = 0; k < s.groups.size(); ++k) {
    if (s.groups[k].is_wall)
      walls_.push_back(wall_at(s.prm, s.groups[k], k, angle_[k]));
    else
      turn_[k] = Vec2{std::cos(angle_[k]), std::sin(angle_[k])};
  }
}

void LoadBand::bin_bodies(const BandScene& s, real reach) {
  // Cells at least (largest bounding radius + reach) wide: a particle's solids are among the
  // bodies of its own and the 8 surrounding cells.
  real bound = 0;
  body_items_.clear();
  for (std::size_t k = 0; k < s.groups.size(); ++k) {
    const RigidGroup& g = s.groups[k];
    if (g.is_wall || g.removed) continue;
    bound = std::max(bound, s.prm.bodies[static_cast<std::size_t>(g.body)].shape.bounding_radius());
    body_items_.push_back({static_cast<std::uint32_t>(k), pos_[k]});
  }
  bodies_.build(s.domain, bound + reach, body_items_);
}

int LoadBand::near_solids(const BandScene& s, Vec2 x, real reach, NearSolid* out, int max) const {
  int count = 0;
  for (std::size_t k = 0; k < s.groups.size() && s.groups[k].is_wall && count < max; ++k)
    if (offer_near_solid(s, x, reach, k, out[count])) ++count;
  if (count < max)
    bodies_.visit(x, [&](std::uint32_t k) {
      if (offer_near_solid(s, x, reach, k, out[count])) ++count;
      return count < max;
    });
  return count;
}

real LoadBand::cell_area(const BandScene& s, std::size_t i, const std::vector<Vec2>& x,
                         const HostNeighbors& nbrs) const {
  const std::size_t nb = s.particles.n_boundary;
  Vec2 d[kVoronoiMaxVertices - 4];
  int count = 0;
  bool closed_by_fluid = true;
  auto take = [&](std::uint32_t j) {
    if (j < nb || count == kVoronoiMaxVertices - 4) {
      closed_by_fluid = false;
      return;
    }
    d[count++] = s.domain.separation(x[j], x[i]);
  };
  nbrs.visit(x.data(), static_cast<std::uint32_t>(i), take);
  return closed_by_fluid ? voronoi_cell_area(d, count, s.prm.h) : 0;
}

void LoadBand::build_entries(const BandScene& s, const std::vector<Vec2>& x, const HostNeighbors& nbrs,
                             std::size_t f0, std::size_t f1, std::vector<BandEntry>& part) {
  constexpr int kMaxNear = 16;
  const real reach = kLoadBandReach * s.prm.h;
  const real film = kFilmGap * s.prm.h;
  const std::size_t nb = s.particles.n_boundary;
  // numerics.load_band_motion: each particle's limit, squared (band_moved_limit2)
  const real kept_limit = s.prm.open.empty() ? s.prm.load_band_motion : 0;
  part.clear();
  NearSolid near[kMaxNear];
  for (std::size_t f = f0; f < f1; ++f) {
    const int count = in_load_band(s, nb + f) ? near_solids(s, x[nb + f], reach, near, kMaxNear) : 0;
    if (count == 0) continue;
    const real area = cell_area(s, nb + f, x, nbrs);
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
      anchor_[nb + f] = near[closest].group;
      if (count > 1)
        limit2_[nb + f] =
            band_moved_limit2(facing_gap(near, count, closest), kept_limit, kBandGapFloor * s.prm.d0);
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
}

void LoadBand::build(const BandScene& s, const std::vector<Vec2>& x, const HostNeighbors& nbrs,
                     Backend& backend) {
  ++builds_;
  const std::size_t nb = s.particles.n_boundary, nf = x.size() - nb;
  bin_bodies(s, kLoadBandReach * s.prm.h);
  place_solids(s);
  const real kept_limit = s.prm.open.empty() ? s.prm.load_band_motion : 0;
  if (kept_limit > 0) {
    limit2_.assign(x.size(), kept_limit * kept_limit);
    anchor_.assign(x.size(), -1);
  }
  // One pass: each thread takes a contiguous range of fluid particles and lists their entries in
  // particle order; the threads' lists are then joined in thread order, so the band is in
  // particle order whatever the thread count.
  const std::size_t threads = static_cast<std::size_t>(omp_get_max_threads());
  parts_.resize(threads);
  part_first_.assign(threads + 1, 0);
#pragma omp parallel num_threads(static_cast <int>(threads))
  {
    const std::size_t t = static_cast<std::size_t>(omp_get_thread_num()),
                      nt = static_cast<std::size_t>(omp_get_num_threads());
    std::vector<BandEntry>& part = parts_[t];
    build_entries(s, x, nbrs, nf * t / nt, nf * (t + 1) / nt, part);
    part_first_[t + 1] = part.size();
#pragma omp barrier
#pragma omp single
    {
      for (std::size_t u = 0; u < nt; ++u) part_first_[u + 1] += part_first_[u];
      band_.resize(part_first_[nt]);
    }
    std::copy(part.begin(), part.end(), band_.begin() + static_cast<std::ptrdiff_t>(part_first_[t]));
  }
  assign_slots(s.groups.size());
  backend.set_load_band(band_);
}

void LoadBand::assign_slots(std::size_t groups) {
  // Each block of kBandBlock entries numbers the groups it holds in the order they first appear
  // (BandEntry::slot); block_first_[b] is where block b's groups start in slot_group_.
  const std::size_t ne = band_.size(), nblocks = (ne + kBandBlock - 1) / kBandBlock;
  block_first_.assign(nblocks + 1, 0);
#pragma omp parallel
  {
    std::vector<std::int32_t> slot_of(groups, -1);
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
      block_first_[b + 1] = static_cast<std::size_t>(count);
    }
  }
  for (std::size_t b = 0; b < nblocks; ++b) block_first_[b + 1] += block_first_[b];
  slot_group_.resize(block_first_[nblocks]);
#pragma omp parallel for schedule(static)
  for (std::size_t b = 0; b < nblocks; ++b)
    for (std::size_t e = b * kBandBlock; e < std::min(ne, (b + 1) * kBandBlock); ++e)
      slot_group_[block_first_[b] + band_[e].slot] = band_[e].group;
}

template <class T>
void LoadBand::add_up(std::size_t groups, const std::vector<T>& partial, std::vector<T>& total) const {
  total.assign(groups, T{});
  for (std::size_t q = 0; q < partial.size(); ++q)
    total[static_cast<std::size_t>(slot_group_[q])] += partial[q];
}

LoadArrays LoadBand::load_arrays(const BandScene& s) const {
  const PhysicsParams& prm = s.prm;
  LoadArrays a;
  a.domain = s.domain;
  a.group_pos = group_pos_.data();
  a.group_level = group_level_.data();
  a.mu = prm.nu * prm.rho0;
  a.nu = prm.nu;
  a.rho0 = prm.rho0;
  a.c2 = prm.c * prm.c;
  a.p0 = prm.p0;
  // The smooth pressure taken out of the stress: hydrostatic for gravity in the fluid and for a
  // body force along a closed side (along a periodic side no mean pressure gradient exists).
  Vec2 g = prm.body_force;
  if (prm.gravity_in_fluid) g += prm.gravity;
  if (s.domain.periodic_x) g.x = 0;
  if (s.domain.periodic_y) g.y = 0;
  a.g_h = g;
  a.x_ref = s.domain.lo;
  return a;
}

void LoadBand::group_loads(const BandScene& s, Backend& backend, std::vector<RigidGroup>& groups) {
  const std::size_t ng = s.groups.size();
  group_pos_.resize(ng);
  for (std::size_t k = 0; k < ng; ++k) group_pos_[k] = s.groups[k].pos;
  group_level_.assign(ng, s.prm.rho0 * s.prm.c * s.prm.c);  // P_h = p0 for a group without fluid near it
  const LoadArrays a = load_arrays(s);
  sum_levels(s, a, backend);
  sum_loads(s, a, backend);
#pragma omp parallel for schedule(dynamic)
  for (std::size_t k = 0; k < ng; ++k) {
    RigidGroup& g = groups[k];
    Vec2 fp;
    real torque = 0;
    smooth_pressure_load(s, a, k, fp, torque);
    g.force_pressure = fp + load_total_[k].fp;
    g.force_viscous = load_total_[k].fv;
    g.force_damping = load_total_[k].fd;
    g.torque = torque + load_total_[k].torque;
  }
}

void LoadBand::sum_levels(const BandScene& s, const LoadArrays& a, Backend& backend) {
  // Each group's level K_B, the smooth field that best matches the fluid in its band (the
  // pressure's constant is set by the fluid's mass in a closed box: a P_h off by a constant C
  // adds C times the band's quadrature error of int grad(phi) = 0). The backend evaluates every
  // entry, and the entries are summed here in blocks.
  backend.band_level_sums(a, block_first_, level_partial_);  // (num, den) per block slot
  add_up(s.groups.size(), level_partial_, level_total_);
  for (std::size_t k = 0; k < s.groups.size(); ++k)
    if (level_total_[k].y > 0) group_level_[k] = level_total_[k].x / level_total_[k].y;
}

void LoadBand::sum_loads(const BandScene& s, const LoadArrays& a, Backend& backend) {
  // The circles: their pressure torque in a film is left out (add_band_entry_load).
  const std::size_t ng = s.groups.size();
  group_circle_.resize(ng);
  for (std::size_t k = 0; k < ng; ++k)
    group_circle_[k] =
        !s.groups[k].is_wall &&
        s.prm.bodies[static_cast<std::size_t>(s.groups[k].body)].shape.kind() == ShapeKind::Circle;
  backend.band_load_sums(a, group_pos_, group_level_, group_circle_, block_first_, load_partial_);
  add_up(ng, load_partial_, load_total_);
}

}  // namespace particula
