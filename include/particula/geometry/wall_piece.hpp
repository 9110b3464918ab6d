// The geometry of one wall: a straight segment or a circular arc, with the fluid on its left
// walking from its start to its end (so a closed container is listed counter-clockwise, and an
// arc turning counter-clockwise has the fluid on the side of its centre). Used by the scene
// (sampling, the fluid fill), the contacts and the loads (distance, smooth-pressure integral).
#pragma once

#include <cmath>

#include "particula/core/types.hpp"

namespace particula {

/// The point of a wall nearest to x.
struct WallNearest {
  real distance = 0;  // |x - point|
  real side = 0;      // signed distance: > 0 on the fluid side (the left)
  Vec2 point;         // nearest point of the wall
  Vec2 normal;        // unit normal on the fluid side at `point` (at an end point: the end's normal)
  real s = 0;         // position of `point` along the wall, 0 at the start and 1 at the end
  bool interior = false;  // x faces the wall: its foot on the wall's line or circle lies between the ends (inclusive)
};

class WallPiece {
 public:
  WallPiece() = default;
  static WallPiece segment(Vec2 from, Vec2 to);
  /// An arc of the circle (center, radius) from angle `start` to angle `end` (rad; end > start
  /// turns counter-clockwise, fluid inside the circle; end < start clockwise, fluid outside).
  /// |end - start| = 2 pi is a full circle.
  static WallPiece arc(Vec2 center, real radius, real start, real end);

  bool is_arc() const { return radius_ > 0; }
  bool is_full_circle() const;
  real length() const { return len_; }
  Vec2 start() const { return point_at(0); }
  Vec2 end() const { return point_at(1); }
  Vec2 center() const { return center_; }
  real radius() const { return radius_; }
  /// The point periodic images are measured from: a segment's midpoint, an arc's centre.
  Vec2 middle() const { return is_arc() ? center_ : point_at(0.5); }
  /// Signed sweep of an arc (rad).
  real sweep() const { return sweep_; }
  /// The point at fraction s of the length (0 = start, 1 = end).
  Vec2 point_at(real s) const;
  /// Unit normal on the fluid side at fraction s.
  Vec2 normal_at(real s) const;
  /// Unit tangent (start to end) at fraction s.
  Vec2 tangent_at(real s) const;
  /// A cheap test that x (given as x - middle()) is farther than `reach` from the wall: outside
  /// the band of half-width `reach` along a segment's line or beyond its ends, or outside the
  /// annulus round an arc's circle.
  bool surely_farther(Vec2 from_middle, real reach) const {
    if (!is_arc()) {
      const Vec2 t = to_ - from_;
      return std::fabs(cross(t, from_middle)) > reach * len_ || std::fabs(dot(t, from_middle)) > (0.5 * len_ + reach) * len_;
    }
    const real r2 = norm2(from_middle), lo = radius_ - reach;
    return r2 > (radius_ + reach) * (radius_ + reach) || (lo > 0 && r2 < lo * lo);
  }
  /// The nearest point of the wall to x.
  WallNearest nearest(Vec2 x) const;
  /// The wall moved rigidly: rotated by `angle` about `pivot`, then shifted by `shift`.
  WallPiece moved(Vec2 pivot, real angle, Vec2 shift) const;
  /// The largest distance from `pivot` to a point of the wall.
  real reach_from(Vec2 pivot) const;

 private:
  Vec2 from_, to_;          // segment
  Vec2 center_;             // arc
  real radius_ = 0, start_ = 0, sweep_ = 0;
  real len_ = 0;
};

}  // namespace particula
