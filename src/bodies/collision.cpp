#include "particula/bodies/collision.hpp"

#include <algorithm>
#include <cmath>

namespace particula {

namespace {

/// Smallest signed distance of `a`'s surface samples to the solid `b` (b's frame), with the
/// outward normal of b there (world frame).
Contact one_sided(const PlacedBody& a, const PlacedBody& b, const Domain& domain) {
  Contact best;
  const real ca = std::cos(a.angle), sa = std::sin(a.angle);
  const real cb = std::cos(b.angle), sb = std::sin(b.angle);
  for (const auto& s : *a.samples) {
    const Vec2 world = a.pos + rotate(s.x, ca, sa);
    const Vec2 rel = domain.separation(world, b.pos);
    const Vec2 local = rotate(rel, cb, -sb);  // rotate by -angle_b
    const real d = b.shape->signed_distance(local);
    if (d < best.gap) {
      best.gap = d;
      best.normal = rotate(b.shape->closest_normal(local), cb, sb);
    }
  }
  return best;
}

}  // namespace

Contact body_contact(const PlacedBody& a, const PlacedBody& b, const Domain& domain) {
  if (a.shape->kind() == ShapeKind::Circle && b.shape->kind() == ShapeKind::Circle) {
    const Vec2 r = domain.separation(a.pos, b.pos);
    const real d = norm(r);
    Contact c;
    c.gap = d - a.shape->bounding_radius() - b.shape->bounding_radius();
    c.normal = d > 0 ? r / d : Vec2{0, 1};
    return c;
  }
  const Contact ab = one_sided(a, b, domain);  // a's points in b: normal of b, points towards a
  Contact ba = one_sided(b, a, domain);        // b's points in a: normal of a, points towards b
  ba.normal = -ba.normal;
  return ab.gap <= ba.gap ? ab : ba;
}

Contact wall_contact(const PlacedBody& a, Vec2 from, Vec2 to, Vec2 normal) {
  Contact best;
  const real ca = std::cos(a.angle), sa = std::sin(a.angle);
  const Vec2 t = to - from;
  const real L2 = norm2(t);
  for (const auto& s : *a.samples) {
    const Vec2 p = a.pos + rotate(s.x, ca, sa);
    const real u = dot(p - from, t) / L2;
    // beyond the segment's ends the wall does not act (a neighbouring wall does)
    if (u < 0 || u > 1) continue;
    const real d = dot(p - from, normal);
    if (d < best.gap) {
      best.gap = d;
      best.normal = normal;
    }
  }
  return best;
}

}  // namespace particula
