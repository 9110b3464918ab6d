// The geometry of contacts in 3D (bodies/contact_geometry3.hpp).
#include "particula/bodies/contact_geometry3.hpp"

namespace particula {

namespace {

/// Smallest signed distance of a's surface samples to the solid b, with b's outward normal there
/// (world frame) and the sample as the contact point.
ContactOf<3> one_sided(const PlacedBody3& a, const PlacedBody3& b, const Domain3& domain) {
  ContactOf<3> best;
  const Mat3 Ra = rotation_matrix(a.q), Rb = rotation_matrix(b.q);
  const Mat3 Rb_t = transpose(Rb);
  for (const SurfaceSample3& s : *a.samples) {
    const Vec3 world = a.pos + Ra * s.x;
    const Vec3 local = Rb_t * domain.separation(world, b.pos);
    real d = 0;
    Vec3 n;
    b.shape->distance_and_gradient(local, d, n);
    if (d < best.gap) {
      best.gap = d;
      best.normal = Rb * n;
      best.point = world;
    }
  }
  return best;
}

}  // namespace

ContactOf<3> body_contact(const PlacedBody3& a, const PlacedBody3& b, const Domain3& domain) {
  if (a.shape->kind() == Shape3Kind::Sphere && b.shape->kind() == Shape3Kind::Sphere) {
    const Vec3 r = domain.separation(a.pos, b.pos);
    const real d = norm(r), Ra = a.shape->bounding_radius(), Rb = b.shape->bounding_radius();
    ContactOf<3> c;
    c.gap = d - Ra - Rb;
    c.normal = d > 0 ? r / d : Vec3{0, 0, 1};
    c.point = a.pos - (Ra + 0.5 * c.gap) * c.normal;  // the middle of the gap
    return c;
  }
  const ContactOf<3> ab = one_sided(a, b, domain);  // a's points in b: b's normal, towards a
  ContactOf<3> ba = one_sided(b, a, domain);        // b's points in a: a's normal, towards b
  ba.normal = -ba.normal;
  return ab.gap <= ba.gap ? ab : ba;
}

ContactOf<3> wall_contact(const PlacedBody3& a, const WallPlane& wall) {
  ContactOf<3> c;
  c.normal = wall.normal;
  if (a.shape->kind() == Shape3Kind::Sphere) {  // straight towards the wall from the centre
    const real R = a.shape->bounding_radius();
    c.gap = dot(a.pos - wall.point, wall.normal) - R;
    c.point = a.pos - R * wall.normal;
    return c;
  }
  const Mat3 R = rotation_matrix(a.q);
  for (const SurfaceSample3& s : *a.samples) {
    const Vec3 p = a.pos + R * s.x;
    const real d = dot(p - wall.point, wall.normal);
    if (d < c.gap) {
      c.gap = d;
      c.point = p;
    }
  }
  return c;
}

}  // namespace particula
