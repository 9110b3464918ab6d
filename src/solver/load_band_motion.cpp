// The kept band of the momentum loads (numerics.load_band_motion; solver/load_band.hpp): when the
// band may be kept for another step, and its restoration from a checkpoint (docs/method.md,
// "The kept band").
#include <algorithm>
#include <cmath>

#include "particula/bodies/contact_pairs.hpp"
#include "particula/solver/backend.hpp"
#include "particula/solver/load_band.hpp"

namespace particula {

void LoadBand::update(const BandScene& s, Backend& backend, bool reordered) {
  // The band's phi_B, grad phi_B, areas and films change with the particles' and the solids'
  // positions only; kept (numerics.load_band_motion > 0), it stands for the positions it was
  // built at until something has moved farther than that. A reordering renumbers the
  // particles, an open boundary changes them every step: both rebuild it.
  const bool keep = s.prm.load_band_motion > 0 && s.prm.open.empty();
  const std::size_t ng = s.groups.size();
  const std::vector<Vec2>& x = backend.host_positions();
  if (keep && restore_) {
    // a checkpoint's band: built again where the uninterrupted run built it, from its positions
    // binned here as the step's neighbour search bins them (a kept band has no open boundary, so
    // the grid has no margin)
    restore_ = false;
    if (built_.x.size() == x.size() && built_.pos.size() == ng && built_.angle.size() == ng) {
      pos_ = built_.pos;
      angle_ = built_.angle;
      grid_.setup(s.domain, s.prm.h);
      grid_.bin(built_.x);
      build(s, built_.x, HostNeighbors{nullptr, &grid_, s.prm.h * s.prm.h}, backend);
    } else {
      built_ = LoadBandState{};
    }
  }
  if (keep && built_.held() && !reordered && built_.x.size() == x.size() && !moved(s, x)) return;
  pos_.resize(ng);
  angle_.resize(ng);
  for (std::size_t k = 0; k < ng; ++k) {
    pos_[k] = s.groups[k].pos;
    angle_[k] = s.groups[k].angle;
  }
  build(s, x, backend.band_neighbors(x), backend);
  if (keep) {
    built_.x = x;
    built_.pos = pos_;
    built_.angle = angle_;
  } else {
    built_ = LoadBandState{};
  }
}

bool LoadBand::moved(const BandScene& s, const std::vector<Vec2>& x) {
  real largest_solid = 0;
  if (solid_moved(s, largest_solid)) return true;
  // two surfaces together can have closed their gap by at most twice the largest motion
  if (2 * largest_solid > kBandGapShare * kBandGapFloor * s.prm.d0 && solids_closed_in(s)) return true;
  return particle_moved(s, x);
}

bool LoadBand::solid_moved(const BandScene& s, real& largest) {
  // A solid's surface moves at most by its displacement plus its turn times its farthest point
  // from its pivot (a circle's turn does not move its surface); a wall turns about its pivot.
  const real limit = s.prm.load_band_motion;
  const std::size_t ng = s.groups.size();
  shift_.resize(ng);
  turn_reach_.resize(ng);
  turn_cs_.resize(ng);
  for (std::size_t k = 0; k < ng; ++k) {
    const RigidGroup& g = s.groups[k];
    const real turned = g.angle - built_.angle[k], turn = std::fabs(turned);
    turn_cs_[k] = Vec2{std::cos(turned), std::sin(turned)};
    if (g.is_wall) {
      const WallPiece& w = s.prm.walls[k];
      shift_[k] = Vec2{};
      turn_reach_[k] = turn * (norm(s.domain.separation(w.middle(), g.pos0)) + 0.5 * w.length());
    } else {
      const Shape& shape = s.prm.bodies[static_cast<std::size_t>(g.body)].shape;
      shift_[k] = s.domain.separation(g.pos, built_.pos[k]);
      turn_reach_[k] = shape.kind() == ShapeKind::Circle ? 0 : turn * shape.bounding_radius();
    }
    const real moved = norm(shift_[k]) + turn_reach_[k];
    if (!(moved <= limit)) return true;
    largest = std::max(largest, moved);
  }
  return false;
}

bool LoadBand::particle_moved(const BandScene& s, const std::vector<Vec2>& x) const {
  // Every particle, the surface particles too (they close or open the fluid's Voronoi cells),
  // within its limit (band_moved_limit2, load_band.cpp). A particle in the band moves relative to
  // its closest solid: its phi, grad phi and cell hold while it and its neighbours move with that
  // solid, as the fluid next to a moving body does (a drop onto a wall at St 380 rebounded 3 % too
  // slowly with the particles' own motion against the band's limit: docs/method.md).
  const std::size_t n = x.size();
  if (limit2_.size() != n || anchor_.size() != n) return true;
  real largest = 0;
#pragma omp parallel for schedule(static) reduction(max : largest)
  for (std::size_t i = 0; i < n; ++i) {
    const std::int32_t k = anchor_[i];
    Vec2 moved = s.domain.separation(x[i], built_.x[i]);
    if (k >= 0) {
      // x relative to the solid's pivot now, against the build's relative position turned with it
      const std::size_t a = static_cast<std::size_t>(k);
      const RigidGroup& g = s.groups[a];
      const Vec2 now = s.domain.separation(x[i], g.is_wall ? g.pos0 : g.pos),
                 then = s.domain.separation(built_.x[i], g.is_wall ? g.pos0 : built_.pos[a]);
      moved = now - rotate(then, turn_cs_[a].x, turn_cs_[a].y);
    }
    largest = std::max(largest, norm2(moved) / limit2_[i]);
  }
  return !(largest <= 1);
}

bool LoadBand::solids_closed_in(const BandScene& s) {
  // Between two surfaces a gap g apart, the partition phi_B = w_B / (1 + sum_C w_C) with
  // w ~ s^-4 changes by about 4 delta / g when they close in by delta: there the band is kept
  // only while their relative motion stays below kBandGapShare g (g at least kBandGapFloor d0),
  // which is tighter than load_band_motion for gaps below load_band_motion / kBandGapShare.
  const PhysicsParams& prm = s.prm;
  const real near = prm.load_band_motion / kBandGapShare, floor = kBandGapFloor * prm.d0;
  // how far the two surfaces can have closed in, from a bound on their relative shift
  const auto closing = [&](std::size_t a, std::size_t b, real shift) {
    return shift + turn_reach_[a] + turn_reach_[b];
  };
  const auto closed_in = [&](std::size_t a, std::size_t b, real gap) {
    return closing(a, b, norm(shift_[a] - shift_[b])) > kBandGapShare * std::max(gap, floor);
  };
  const auto may_close = [&](std::size_t a, std::size_t b) {  // before the gap is known
    return closing(a, b, norm(shift_[a]) + norm(shift_[b])) > kBandGapShare * floor;
  };
  body_list_.list(prm, s.groups);
  contact_candidates(body_list_.pos, body_list_.bound, near, s.domain, pairs_);
  for (const BodyPair& p : pairs_) {
    const std::size_t a = body_list_.groups[p.first], b = body_list_.groups[p.second];
    if (!may_close(a, b)) continue;
    const real gap = body_contact(placed_body(prm, s.groups[a]), placed_body(prm, s.groups[b]), s.domain).gap;
    if (gap < near && closed_in(a, b, gap)) return true;
  }
  for (const std::size_t a : body_list_.groups)
    for (std::size_t w = 0; w < prm.walls.size(); ++w) {
      if (!may_close(a, w)) continue;
      const real gap = wall_contact_exact(placed_body(prm, s.groups[a]), wall_now(prm, s.groups, w)).gap;
      if (gap < near && closed_in(a, w, gap)) return true;
    }
  return false;
}

}  // namespace particula
