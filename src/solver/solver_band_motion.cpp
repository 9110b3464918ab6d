// The kept band of the momentum loads (numerics.load_band_motion): when the band built by
// Solver::build_load_band (solver_loads.cpp) may be kept for another step, and its restoration
// from a checkpoint (docs/method-notes.md, "The kept band").
#include <algorithm>
#include <cmath>

#include "particula/solver/solver.hpp"

namespace particula {

void Solver::set_load_band_state(const LoadBandState& s) {
  band_built_ = s;
  band_restore_ = s.held();
}

bool Solver::load_band_moved(const std::vector<Vec2>& x) {
  // A solid's surface moves at most by its displacement plus its turn times its farthest point
  // from its pivot (a circle's turn does not move its surface); a wall turns about its pivot.
  const real limit = prm_.load_band_motion;
  const std::size_t ng = groups_.size();
  band_shift_.resize(ng);
  band_turn_reach_.resize(ng);
  band_turn_cs_.resize(ng);
  real largest_solid = 0;
  for (std::size_t k = 0; k < ng; ++k) {
    const RigidGroup& g = groups_[k];
    const real turned = g.angle - band_built_.angle[k], turn = std::fabs(turned);
    band_turn_cs_[k] = Vec2{std::cos(turned), std::sin(turned)};
    if (g.is_wall) {
      const WallPiece& w = prm_.walls[k];
      band_shift_[k] = Vec2{};
      band_turn_reach_[k] = turn * (norm(domain_.separation(w.middle(), g.pos0)) + 0.5 * w.length());
    } else {
      const Shape& shape = prm_.bodies[static_cast<std::size_t>(g.body)].shape;
      band_shift_[k] = domain_.separation(g.pos, band_built_.pos[k]);
      band_turn_reach_[k] = shape.kind() == ShapeKind::Circle ? 0 : turn * shape.bounding_radius();
    }
    const real moved = norm(band_shift_[k]) + band_turn_reach_[k];
    if (!(moved <= limit)) return true;
    largest_solid = std::max(largest_solid, moved);
  }
  // two surfaces together can have closed their gap by at most twice the largest motion
  if (2 * largest_solid > kBandGapShare * kBandGapFloor * prm_.d0 && solids_closed_in()) return true;
  // Every particle, the surface particles too (they close or open the fluid's Voronoi cells),
  // within its limit (band_moved_limit2, solver_loads.cpp). A particle in the band moves relative to its
  // closest solid: its phi, grad phi and cell hold while it and its neighbours move with that solid, as the
  // fluid next to a moving body does (a drop onto a wall at St 380 rebounded 3 % too slowly with the
  // particles' own motion against the band's limit: docs/method-notes.md).
  const std::size_t n = x.size();
  if (band_limit2_.size() != n || band_anchor_.size() != n) return true;
  real largest = 0;
#pragma omp parallel for schedule(static) reduction(max : largest)
  for (std::size_t i = 0; i < n; ++i) {
    const std::int32_t k = band_anchor_[i];
    Vec2 moved = domain_.separation(x[i], band_built_.x[i]);
    if (k >= 0) {
      // x relative to the solid's pivot now, against the build's relative position turned with it
      const std::size_t a = static_cast<std::size_t>(k);
      const RigidGroup& g = groups_[a];
      const Vec2 now = domain_.separation(x[i], g.is_wall ? g.pos0 : g.pos),
                 then = domain_.separation(band_built_.x[i], g.is_wall ? g.pos0 : band_built_.pos[a]);
      moved = now - rotate(then, band_turn_cs_[a].x, band_turn_cs_[a].y);
    }
    largest = std::max(largest, norm2(moved) / band_limit2_[i]);
  }
  return !(largest <= 1);
}

bool Solver::solids_closed_in() {
  // Between two surfaces a gap g apart, the partition phi_B = w_B / (1 + sum_C w_C) with
  // w ~ s^-4 changes by about 4 delta / g when they close in by delta: there the band is kept
  // only while their relative motion stays below kBandGapShare g (g at least kBandGapFloor d0),
  // which is tighter than load_band_motion for gaps below load_band_motion / kBandGapShare.
  const real near = prm_.load_band_motion / kBandGapShare, floor = kBandGapFloor * prm_.d0;
  // how far the two surfaces can have closed in, from a bound on their relative shift
  const auto closing = [&](std::size_t a, std::size_t b, real shift) {
    return shift + band_turn_reach_[a] + band_turn_reach_[b];
  };
  const auto closed_in = [&](std::size_t a, std::size_t b, real gap) {
    return closing(a, b, norm(band_shift_[a] - band_shift_[b])) > kBandGapShare * std::max(gap, floor);
  };
  const auto may_close = [&](std::size_t a, std::size_t b) {  // before the gap is known
    return closing(a, b, norm(band_shift_[a]) + norm(band_shift_[b])) > kBandGapShare * floor;
  };
  list_bodies();
  contact_candidates(body_pos_, body_bound_, near, domain_, band_pairs_);
  for (const BodyPair& p : band_pairs_) {
    const std::size_t a = body_groups_[p.first], b = body_groups_[p.second];
    if (!may_close(a, b)) continue;
    const real gap = body_contact(placed_body(groups_[a]), placed_body(groups_[b]), domain_).gap;
    if (gap < near && closed_in(a, b, gap)) return true;
  }
  for (const std::size_t a : body_groups_)
    for (std::size_t w = 0; w < prm_.walls.size(); ++w) {
      if (!may_close(a, w)) continue;
      const real gap = wall_contact_exact(placed_body(groups_[a]), wall_now(w)).gap;
      if (gap < near && closed_in(a, w, gap)) return true;
    }
  return false;
}

void Solver::update_load_band(bool reordered) {
  // The band's phi_B, grad phi_B, areas and films change with the particles' and the solids'
  // positions only; kept (numerics.load_band_motion > 0), it stands for the positions it was
  // built at until something has moved farther than that. A reordering renumbers the
  // particles, an open boundary changes them every step: both rebuild it.
  const bool keep = prm_.load_band_motion > 0 && prm_.open.empty();
  const std::size_t ng = groups_.size();
  if (dev_) dev_->download_positions(band_x_);
  const std::vector<Vec2>& x = dev_ ? band_x_ : P_.x;
  if (keep && band_restore_) {
    // a checkpoint's band: built again where the uninterrupted run built it
    band_restore_ = false;
    if (band_built_.x.size() == x.size() && band_built_.pos.size() == ng && band_built_.angle.size() == ng) {
      band_pos_ = band_built_.pos;
      band_angle_ = band_built_.angle;
      CellGrid grid = grid_;
      NeighborList nl;
      if (!dev_) build_neighbor_list(band_built_.x, domain_, kernel_, grid, nl);
      build_load_band(band_built_.x, nl);
    } else {
      band_built_ = LoadBandState{};
    }
  }
  if (keep && band_built_.held() && !reordered && band_built_.x.size() == x.size() && !load_band_moved(x))
    return;
  band_pos_.resize(ng);
  band_angle_.resize(ng);
  for (std::size_t k = 0; k < ng; ++k) {
    band_pos_[k] = groups_[k].pos;
    band_angle_[k] = groups_[k].angle;
  }
  build_load_band(x, nl_);
  if (keep) {
    band_built_.x = x;
    band_built_.pos = band_pos_;
    band_built_.angle = band_angle_;
  } else {
    band_built_ = LoadBandState{};
  }
}

}  // namespace particula
