// Segments and arcs of walls: points, normals on the fluid side and the nearest point.
#include "particula/geometry/wall_piece.hpp"

#include <algorithm>
#include <cmath>

namespace particula {

WallPiece WallPiece::segment(Vec2 from, Vec2 to) {
  WallPiece w;
  w.from_ = from;
  w.to_ = to;
  w.len_ = norm(to - from);
  return w;
}

WallPiece WallPiece::arc(Vec2 center, real radius, real start, real end) {
  WallPiece w;
  w.center_ = center;
  w.radius_ = radius;
  w.start_ = start;
  w.sweep_ = end - start;
  w.len_ = radius * std::fabs(w.sweep_);
  w.from_ = w.point_at(0);
  w.to_ = w.point_at(1);
  return w;
}

bool WallPiece::is_full_circle() const { return is_arc() && std::fabs(std::fabs(sweep_) - 2 * M_PI) < 1e-9; }

Vec2 WallPiece::point_at(real s) const {
  if (!is_arc()) return from_ + s * (to_ - from_);
  const real a = start_ + s * sweep_;
  return center_ + radius_ * Vec2{std::cos(a), std::sin(a)};
}

Vec2 WallPiece::tangent_at(real s) const {
  if (!is_arc()) return (to_ - from_) / len_;
  const real a = start_ + s * sweep_;
  const real dir = sweep_ > 0 ? 1 : -1;
  return dir * Vec2{-std::sin(a), std::cos(a)};
}

Vec2 WallPiece::normal_at(real s) const {
  const Vec2 t = tangent_at(s);
  return {-t.y, t.x};  // the left of the direction of travel
}

WallNearest WallPiece::nearest(Vec2 x) const {
  WallNearest r;
  if (!is_arc()) {
    const Vec2 ab = to_ - from_;
    const real u = dot(x - from_, ab) / norm2(ab);
    r.s = std::clamp(u, real(0), real(1));
    r.interior = u >= 0 && u <= 1;
  } else {
    // Angle of x from the start, measured in the arc's direction of travel, in [0, 2 pi).
    const Vec2 d = x - center_;
    const real dir = sweep_ > 0 ? 1 : -1;
    real phi = dir * (std::atan2(d.y, d.x) - start_);
    phi = std::fmod(phi, 2 * M_PI);
    if (phi < 0) phi += 2 * M_PI;
    const real span = std::fabs(sweep_);
    if (phi <= span) {
      r.s = phi / span;
      r.interior = true;
    } else {
      // beyond the end: the nearer end point (measured round the rest of the circle)
      r.s = (phi - span < 2 * M_PI - phi) ? 1 : 0;
    }
    if (is_full_circle()) r.interior = true;
    if (norm(d) == 0) r.s = 0;  // the centre: every point is nearest; take the start
  }
  r.point = point_at(r.s);
  r.normal = normal_at(r.s);
  r.distance = norm(x - r.point);
  // The side: the normal component inside the ends; beyond an end the sign of the normal
  // component at the end point (a sharp-cornered chain resolves the sign from the next wall).
  r.side = dot(x - r.point, r.normal) >= 0 ? r.distance : -r.distance;
  return r;
}

WallPiece WallPiece::moved(Vec2 pivot, real angle, Vec2 shift) const {
  const real c = std::cos(angle), s = std::sin(angle);
  auto place = [&](Vec2 p) { return pivot + rotate(p - pivot, c, s) + shift; };
  WallPiece w = *this;
  w.from_ = place(from_);
  w.to_ = place(to_);
  if (is_arc()) {
    w.center_ = place(center_);
    w.start_ = start_ + angle;
  }
  return w;
}

real WallPiece::reach_from(Vec2 pivot) const {
  if (!is_arc()) return std::max(norm(from_ - pivot), norm(to_ - pivot));
  // the farthest point of the circle from the pivot, if the arc holds it, else an end point
  const Vec2 d = center_ - pivot;
  real far = std::max(norm(from_ - pivot), norm(to_ - pivot));
  const Vec2 away = norm(d) > 0 ? center_ + (radius_ / norm(d)) * d : center_ + Vec2{radius_, 0};
  const WallNearest n = nearest(away);
  if (n.distance < 1e-12 * radius_) far = std::max(far, norm(away - pivot));
  if (norm(d) == 0) far = radius_;
  return far;
}

}  // namespace particula
