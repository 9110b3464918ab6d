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
      best.point = world;
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
    c.point = a.pos - (a.shape->bounding_radius() + 0.5 * c.gap) * c.normal;  // middle of the gap
    return c;
  }
  const Contact ab = one_sided(a, b, domain);  // a's points in b: normal of b, points towards a
  Contact ba = one_sided(b, a, domain);        // b's points in a: normal of a, points towards b
  ba.normal = -ba.normal;
  return ab.gap <= ba.gap ? ab : ba;
}

Contact wall_contact(const PlacedBody& a, const WallPiece& wall) {
  Contact best;
  const real ca = std::cos(a.angle), sa = std::sin(a.angle);
  for (const auto& s : *a.samples) {
    const Vec2 p = a.pos + rotate(s.x, ca, sa);
    const WallNearest n = wall.nearest(p);
    if (!n.interior) continue;  // beyond the wall's ends the wall does not act (a neighbouring wall does)
    if (n.side < best.gap) {
      best.gap = n.side;
      best.normal = n.normal;
      best.point = p;
    }
  }
  return best;
}

Contact wall_contact_exact(const PlacedBody& a, const WallPiece& wall) {
  if (a.shape->kind() != ShapeKind::Circle) return wall_contact(a, wall);
  Contact c;
  const real R = a.shape->bounding_radius();
  // the point of the circle nearest the wall: straight towards the wall from the centre
  const WallNearest n = wall.nearest(a.pos);
  if (!n.interior) return c;  // beyond the wall's ends the wall does not act
  c.gap = n.side - R;
  c.normal = n.normal;
  c.point = a.pos - R * n.normal;
  return c;
}

namespace {

/// 1 / m_t: inverse of the mass that a tangential impulse at the contact point meets on one side
/// (translation plus the rotation it causes), 0 for a side that forces do not move:
/// 1/m + (r x t)^2 / I in 2D, 1/m + (r x t) . I^-1 (r x t) in 3D.
real inverse_tangential_mass(const ContactSide& s, Vec2 r, Vec2 t_hat) {
  if (!(s.mass > 0)) return 0;
  const real arm = cross(r, t_hat);
  return 1 / s.mass + (s.inertia > 0 ? arm * arm / s.inertia : 0);
}
real inverse_tangential_mass(const ContactSide3& s, Vec3 r, Vec3 t_hat) {
  if (!(s.mass > 0)) return 0;
  const Vec3 arm = cross(r, t_hat);
  return 1 / s.mass + dot(arm, s.inertia_inv * arm);
}

}  // namespace

template <int D>
ContactLoadOf<D> spring_dashpot_load(const ContactOf<D>& c, const ContactSideOf<D>& a,
                                     const ContactSideOf<D>& b, Vec<D> r_a, Vec<D> r_b, real k,
                                     const ContactLaw& law, real dt) {
  ContactLoadOf<D> out;
  const Vec<D> n = c.normal;
  const Vec<D> v_rel = relative_velocity(a, b, r_a, r_b);
  const real v_n = dot(v_rel, n);  // < 0 when approaching
  const real m_eff = effective_mass(a.mass, b.mass);
  // Normal spring-dashpot on the mid-step overlap (see the header).
  const real overlap = law.delta_c - c.gap, overlap_rate = -v_n;
  const real gamma = dashpot_coefficient(law.zeta, m_eff, k);
  out.normal = normal_force(k, gamma, overlap + 0.5 * dt * overlap_rate, overlap_rate);
  // Friction: the viscous part gamma_t = m_t / (2 dt) would remove half of the sliding speed in
  // one step (explicit-stable, as close to sticking as an explicit step allows); Coulomb caps it.
  const Vec<D> v_t = v_rel - v_n * n;
  if (law.friction > 0 && out.normal > 0 && norm(v_t) > 0) {
    const Vec<D> t_hat = v_t / norm(v_t);
    const real inv_mt = inverse_tangential_mass(a, r_a, t_hat) + inverse_tangential_mass(b, r_b, t_hat);
    if (inv_mt > 0) out.friction = friction_force(v_t, law.friction, out.normal, 0.5 / (inv_mt * dt));
  }
  // Lubrication: the squeeze film below the resolution opposes the normal relative motion.
  if (law.lubrication) {
    const real R_star = reduced_radius(a.radius, b.radius);
    const real c_lub =
        lubrication_coefficient<D>(law.viscosity, R_star, c.gap, law.lub_min_gap, law.lub_range, m_eff, dt);
    out.lubrication = (-c_lub * v_n) * n;
  }
  out.force = out.normal * n + out.friction + out.lubrication;
  out.torque_a = cross(r_a, out.force);
  out.torque_b = -cross(r_b, out.force);
  return out;
}

template ContactLoadOf<2> spring_dashpot_load<2>(const ContactOf<2>&, const ContactSideOf<2>&,
                                                 const ContactSideOf<2>&, Vec2, Vec2, real, const ContactLaw&,
                                                 real);
template ContactLoadOf<3> spring_dashpot_load<3>(const ContactOf<3>&, const ContactSideOf<3>&,
                                                 const ContactSideOf<3>&, Vec3, Vec3, real, const ContactLaw&,
                                                 real);

}  // namespace particula
