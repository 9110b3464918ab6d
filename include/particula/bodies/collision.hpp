// Solid-solid contacts (docs/method.md, "Contacts"):
//  - the geometry: closest approach of two placed bodies, or of a body and a straight wall, with
//    the point where the contact force acts;
//  - the paper's repulsion (docs/method.md, "Contacts", P.38), generalized to any two shapes and to a
//    body near a wall (treated as meeting its mirror image in the wall);
//  - the default spring-dashpot law: a linear spring whose stiffness is derived from the impact
//    speed, a dashpot from the coefficient of restitution, regularized Coulomb friction and the
//    analytic lubrication force for gaps the particles cannot resolve. History-free: every
//    force is a function of the current positions and velocities.
#pragma once

#include <cmath>
#include <vector>

#include "particula/core/types3.hpp"
#include "particula/geometry/shape.hpp"
#include "particula/geometry/wall_piece.hpp"
#include "particula/neighbors/domain.hpp"

namespace particula {

/// Closest approach between two solids: the surface gap (negative when they overlap), the
/// unit direction pointing from the other solid towards this one, and the point (world frame)
/// where the contact force acts: on the line of centres for two circles (spheres), otherwise the
/// surface sample of the sample-based query that came closest. In D dimensions (`Contact` the 2D one).
template <int D>
struct ContactOf {
  real gap = 1e300;
  Vec<D> normal;
  Vec<D> point;
};
using Contact = ContactOf<2>;

/// The type of an angular velocity or a torque: a scalar (about z) in 2D, a vector in 3D.
template <int D>
struct AngularOf;
template <>
struct AngularOf<2> {
  using type = real;
};
template <>
struct AngularOf<3> {
  using type = Vec3;
};
template <int D>
using Angular = typename AngularOf<D>::type;

// ---------------------------------------------------------------------------------------------
// Geometry

/// A placed body for contact queries: its shape, pose and surface samples (body frame).
struct PlacedBody {
  const Shape* shape = nullptr;
  const std::vector<SurfaceSample>* samples = nullptr;
  Vec2 pos;
  real angle = 0;
};

/// Contact of body a against body b (normal points from b towards a). Uses a's surface
/// samples against b's signed distance and b's samples against a's, so it resolves the gap
/// to the sampling spacing; exact for two circles (the point is then the middle of the gap).
Contact body_contact(const PlacedBody& a, const PlacedBody& b, const Domain& domain);

/// Contact of a body with a wall (a segment or an arc, the fluid on its left; the contact normal
/// points from the wall into the fluid, i.e. towards the body), from the body's surface
/// samples: the gap is resolved to the sampling (the paper's path). Beyond a wall's ends the
/// wall does not act (a neighbouring wall does).
Contact wall_contact(const PlacedBody& a, const WallPiece& wall);

/// The same, exact for a circle: the gap from its centre and the point straight below it, so
/// that the normal force passes through the centre (a lowest sample beside the bottom would give
/// a resting disc a spurious torque of up to F_n R sin(pi ds / 2 pi R)). Other shapes: as
/// wall_contact.
Contact wall_contact_exact(const PlacedBody& a, const WallPiece& wall);

// ---------------------------------------------------------------------------------------------
// The paper's repulsion (collision.model = "paper")

/// P.38 for two circles of radius R at centre distance d:
///   F = k (r_s - r_q) [ (2R + eps)^2 - d^2 ]  for d <= 2R + eps.
/// Generalized with the centre distance replaced by d = gap + R_s + R_q along the contact normal
/// (R the equivalent radii), which is P.38 exactly for two circles.
PARTICULA_HD Vec2 repulsive_force(const Contact& c, real Rs, real Rq, real k, real eps) {
  if (!(c.gap <= eps) || k <= 0) return {};
  const real d = c.gap + Rs + Rq;
  const real reach = Rs + Rq + eps;
  return (k * d * (reach * reach - d * d)) * c.normal;
}

// ---------------------------------------------------------------------------------------------
// The spring-dashpot law (collision.model = "spring_dashpot")

/// Damping ratio of a linear spring-dashpot whose free rebound has restitution e:
///   e = exp(-zeta pi / sqrt(1 - zeta^2))  <=>  zeta = -ln e / sqrt(pi^2 + ln^2 e).
PARTICULA_HD real damping_ratio(real e) {
  const real l = std::log(e);
  return -l / std::sqrt(M_PI * M_PI + l * l);
}

/// Effective mass of a contact: m_a m_b / (m_a + m_b) for two free bodies; m_a against a wall
/// or a body that forces do not move (pass m_b = 0).
PARTICULA_HD real effective_mass(real m_a, real m_b) { return m_b > 0 ? m_a * m_b / (m_a + m_b) : m_a; }

/// Derived stiffness k = m_eff (U_c / delta_max)^2. An undamped linear spring stops an impact at
/// speed U after the overlap U sqrt(m_eff / k) (energy: m U^2 / 2 = k delta^2 / 2), so at the
/// characteristic impact speed U_c the largest overlap is delta_max (damping makes it smaller).
PARTICULA_HD real derived_stiffness(real m_eff, real U_c, real delta_max) {
  const real s = U_c / delta_max;
  return m_eff * s * s;
}

/// Duration of an undamped contact (half a period of the spring): t_c = pi sqrt(m_eff / k).
PARTICULA_HD real contact_duration(real m_eff, real k) { return M_PI * std::sqrt(m_eff / k); }

/// Steps per contact duration: the explicit step resolves a contact with dt <= t_c / 20.
inline constexpr real kStepsPerContact = 20;

/// Dashpot coefficient gamma = 2 zeta sqrt(m_eff k) (zeta the damping ratio).
PARTICULA_HD real dashpot_coefficient(real zeta, real m_eff, real k) {
  return 2 * zeta * std::sqrt(m_eff * k);
}

/// Normal force of the spring-dashpot: F_n = max(0, k delta + gamma d(delta)/dt) for an
/// overlap delta > 0, never attractive (the dashpot cannot pull separating solids together).
PARTICULA_HD real normal_force(real k, real gamma, real overlap, real overlap_rate) {
  if (!(overlap > 0)) return 0;
  const real f = k * overlap + gamma * overlap_rate;
  return f > 0 ? f : 0;
}

/// Regularized Coulomb friction, history-free: F_t = -min(mu |F_n|, gamma_t |v_t|) t_hat with
/// v_t the tangential relative velocity at the contact point and t_hat = v_t / |v_t|. Below the
/// Coulomb limit it is a viscous force that brakes the sliding (it stands for sticking).
template <int D>
PARTICULA_HD Vec<D> friction_force(Vec<D> v_t, real mu, real Fn, real gamma_t) {
  const real s = norm(v_t);
  if (!(s > 0) || !(mu > 0)) return {};
  const real coulomb = mu * std::fabs(Fn), viscous = gamma_t * s;
  return (-(coulomb < viscous ? coulomb : viscous) / s) * v_t;
}

/// Squeeze-film force per unit approach speed at gap g between two curved surfaces of reduced
/// radius R* = R_a R_b / (R_a + R_b) (a plane: R* = R), from lubrication theory (docs/method.md,
/// "Lubrication"): in 2D between two cylinders, per unit depth,
///   F = (3 pi / 2) mu U_n (2 R* / g)^(3/2),
/// in 3D between two spheres (Reynolds),
///   F = 6 pi mu U_n R*^2 / g.
template <int D = 2>
PARTICULA_HD real squeeze_film_coefficient(real mu, real R_star, real gap);
template <>
PARTICULA_HD real squeeze_film_coefficient<2>(real mu, real R_star, real gap) {
  const real r = 2 * R_star / gap;
  return 1.5 * M_PI * mu * r * std::sqrt(r);
}
template <>
PARTICULA_HD real squeeze_film_coefficient<3>(real mu, real R_star, real gap) {
  return 6 * M_PI * mu * R_star * R_star / gap;
}

/// The lubrication correction added to the SPH force, per unit approach speed:
///   c(g) = C(g_eff) - C(g_range) for g < g_range (0 above; continuous at g_range),
///   g_eff = max(g, g_min),
/// with C the squeeze-film coefficient: the particles resolve the film down to g_range, the
/// analytic force supplies the rest. Clipped to c dt / m_eff <= 0.5 so that the explicit
/// step, which applies the force of the start-of-step velocity for the whole step, removes at
/// most half of the approach speed (forward Euler on dU/dt = -c U / m: stable and monotone).
template <int D = 2>
PARTICULA_HD real lubrication_coefficient(real mu, real R_star, real gap, real g_min, real g_range,
                                          real m_eff, real dt) {
  if (!(gap < g_range) || !(R_star > 0) || !(mu > 0)) return 0;
  const real g_eff = gap > g_min ? gap : g_min;
  const real c =
      squeeze_film_coefficient<D>(mu, R_star, g_eff) - squeeze_film_coefficient<D>(mu, R_star, g_range);
  const real c_max = 0.5 * m_eff / dt;
  return c < c_max ? c : c_max;
}

/// Reduced radius of two curved surfaces, R* = R_a R_b / (R_a + R_b); R_b = 0 stands for a
/// plane (a wall): R* = R_a.
PARTICULA_HD real reduced_radius(real R_a, real R_b) { return R_b > 0 ? R_a * R_b / (R_a + R_b) : R_a; }

/// One side of a contact as the force law sees it, in D dimensions (`ContactSide` the 2D one).
template <int D>
struct ContactSideOf;
template <>
struct ContactSideOf<2> {
  Vec2 pos;  // centre of mass (for a wall: any point; it does not turn)
  Vec2 vel;  // velocity of `pos`
  real omega = 0;
  real mass = 0;     // 0: not moved by forces (a wall, a fixed or prescribed body)
  real inertia = 0;  // moment of inertia per unit depth
  real radius = 0;   // equivalent radius for lubrication; 0 for a wall (a plane)
};
using ContactSide = ContactSideOf<2>;
template <>
struct ContactSideOf<3> {
  Vec3 pos, vel, omega;  // as in 2D, the angular velocity a vector
  real mass = 0;
  Mat3 inertia_inv;  // the inverse of the world-frame inertia tensor (0 with mass 0)
  real radius = 0;
};
using ContactSide3 = ContactSideOf<3>;

/// Velocity of side a relative to side b at the contact point (r_a, r_b: the point relative to
/// each side's centre): (v_a + Omega_a x r_a) - (v_b + Omega_b x r_b).
template <int D>
PARTICULA_HD Vec<D> relative_velocity(const ContactSideOf<D>& a, const ContactSideOf<D>& b, Vec<D> r_a,
                                      Vec<D> r_b) {
  return (a.vel + cross(a.omega, r_a)) - (b.vel + cross(b.omega, r_b));
}

/// Parameters of the spring-dashpot law that do not change during a run.
struct ContactLaw {
  real delta_c = 0;   // contact distance: the spring acts for gap < delta_c
  real zeta = 0;      // damping ratio, from the restitution
  real friction = 0;  // Coulomb coefficient mu
  bool lubrication = false;
  real viscosity = 0;    // dynamic viscosity of the fluid (lubrication)
  real lub_range = 0;    // g_range
  real lub_min_gap = 0;  // g_min of g_eff = max(g, g_min)
};

/// The contact force on side a (side b gets the opposite), its parts and where it acts.
template <int D>
struct ContactLoadOf {
  Vec<D> force;     // total on a: normal + friction + lubrication
  real normal = 0;  // F_n of the spring-dashpot (>= 0)
  Vec<D> friction;
  Vec<D> lubrication;
  Angular<D> torque_a{}, torque_b{};  // about each side's centre, from the force at the contact point
};
using ContactLoad = ContactLoadOf<2>;

/// The spring-dashpot load of one contact over a step dt. r_a, r_b: contact point relative to
/// each side's centre (minimum image). The overlap is delta = delta_c - gap and its rate
/// d(delta)/dt = -(v_rel . n), v_rel = (v_a + Omega_a x r_a) - (v_b + Omega_b x r_b). The
/// spring acts on the overlap at the middle of the step, delta + (dt/2) d(delta)/dt: the step
/// applies one force for the whole step, and the mid-step overlap makes that update conserve
/// the spring's energy (the start-of-step overlap adds (omega dt)^2 / 4 of it per step, 13 % of
/// the rebound speed over a contact at dt = t_c / 20). k: the stiffness of this contact.
/// The same law in 2D and 3D; only the squeeze film (cylinders or spheres) and the tangential
/// mass (a scalar or a tensor inertia) differ, through the types.
template <int D>
ContactLoadOf<D> spring_dashpot_load(const ContactOf<D>& c, const ContactSideOf<D>& a,
                                     const ContactSideOf<D>& b, Vec<D> r_a, Vec<D> r_b, real k,
                                     const ContactLaw& law, real dt);

}  // namespace particula
