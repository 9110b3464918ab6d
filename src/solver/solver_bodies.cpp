// The rigid-body side of Solver: group poses and motions, surface placement and kinematics,
// the body stages of the predictor-corrector and the contacts (the loads: solver_loads.cpp).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "particula/bodies/collision.hpp"
#include "particula/bodies/rigid_motion.hpp"
#include "particula/solver/solver.hpp"

namespace particula {

const std::vector<GroupMotion>& Solver::group_motions() {
  motions_.resize(groups_.size());
  for (std::size_t k = 0; k < groups_.size(); ++k) motions_[k] = group_motion(groups_[k]);
  return motions_;
}

GroupMotion Solver::group_motion(const RigidGroup& g) const {
  GroupMotion m;
  m.pos = g.pos;
  m.vel = g.vel;
  m.acc = g.acc;
  m.cos_angle = std::cos(g.angle);
  m.sin_angle = std::sin(g.angle);
  m.omega = g.omega;
  m.alpha = g.alpha;
  return m;
}

void Solver::place_boundary(real t) {
  (void)t;  // group poses are advanced by body_update
  if (dev_) return dev_->surface_motion(group_motions(), true);
  for (auto& g : groups_) {
    const GroupMotion m = group_motion(g);
    for (std::size_t i = g.first; i < g.first + g.count; ++i) {
      P_.x[i] = surface_position(domain_, m, P_.local[i]);
      // Analytic normal; replaced by P.18 in the geometry sweep when kernel normals are used.
      P_.normal[i] = rotate(P_.normal_local[i], m.cos_angle, m.sin_angle);
    }
  }
  set_boundary_kinematics();
}

void Solver::set_boundary_kinematics() {
  if (dev_) return dev_->surface_motion(group_motions(), false);
  for (const auto& g : groups_) {
    const GroupMotion m = group_motion(g);
    for (std::size_t i = g.first; i < g.first + g.count; ++i)
      surface_kinematics(m, P_.local[i], P_.v[i], P_.acc[i]);
  }
}

// ---------------------------------------------------------------------------------------------
// Rigid bodies

void Solver::body_stage(real dt, real t_stage_end, const std::vector<Vec2>& v0,
                        const std::vector<real>& omega0) {
  for (std::size_t k = 0; k < groups_.size(); ++k) {
    RigidGroup& g = groups_[k];
    if (g.removed) continue;
    if (g.motion == Motion::Free) {
      const Vec2 weight = body_weight(g.mass, g.area, prm_.rho0, prm_.gravity, prm_.gravity_in_fluid);
      const Vec2 force = g.force_pressure + g.force_viscous + g.force_collision + weight;
      free_body_stage(g, v0[k], omega0[k], force, g.torque + g.torque_collision, dt,
                      stabilizing_added_mass(prm_.rho0, g.area, g.mass));
    } else if (g.motion == Motion::Prescribed && g.body >= 0) {
      const BodyParams& b = prm_.bodies[static_cast<std::size_t>(g.body)];
      const PrescribedState st = prescribed_state(b.schedule, b.velocity, b.omega, t_stage_end);
      g.vel = st.vel;
      g.omega = st.omega;
      g.acc = st.acc;
      g.alpha = st.alpha;
    }
  }
}

void Solver::body_update(real dt, real t_new) {
  for (auto& g : groups_) {
    if (g.removed) continue;
    if (g.motion == Motion::Free) {
      free_body_update(g, g.vel_n, g.omega_n, dt);
    } else if (g.motion == Motion::Prescribed) {
      Vec2 vel = g.vel;
      real omega = g.omega;
      const std::vector<MotionKnot>* knots = nullptr;
      if (g.body >= 0) {
        const BodyParams& b = prm_.bodies[static_cast<std::size_t>(g.body)];
        vel = b.velocity;
        omega = b.omega;
        knots = &b.schedule;
      }
      const PrescribedState st =
          prescribed_state(knots ? *knots : std::vector<MotionKnot>{}, vel, omega, t_new);
      g.pos = g.pos0 + st.displacement;
      g.angle = g.angle0 + st.rotation;
      g.vel = st.vel;
      g.omega = st.omega;
      g.acc = st.acc;
      g.alpha = st.alpha;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Contacts (bodies/collision.hpp; docs/method-notes.md, Contacts)

namespace {

/// Solids that overlap by more than this are a failure (beyond the sampling noise of the gap).
real overlap_limit(const PhysicsParams& prm) { return -0.25 * prm.d0; }

}  // namespace

PlacedBody Solver::placed_body(const RigidGroup& g) const {
  const BodyParams& b = prm_.bodies[static_cast<std::size_t>(g.body)];
  return PlacedBody{&b.shape, &b.samples, g.pos, g.angle};
}

void Solver::list_bodies() {
  body_groups_.clear();
  body_pos_.clear();
  body_bound_.clear();
  for (std::size_t k = 0; k < groups_.size(); ++k) {
    if (groups_[k].is_wall || groups_[k].removed) continue;
    body_groups_.push_back(k);
    body_pos_.push_back(groups_[k].pos);
    body_bound_.push_back(prm_.bodies[static_cast<std::size_t>(groups_[k].body)].shape.bounding_radius());
  }
}

Failure Solver::overlap_failure(const RigidGroup& a, const std::string& other, real gap) const {
  const char* cause =
      prm_.collision_model == ContactModel::Paper ? "the P.38 repulsion did not keep them apart: raise "
                                                    "collision.stiffness (or collision.range), or use "
                                                    "collision.model = \"spring_dashpot\""
      : prm_.collision_stiffness > 0
          ? "contact too soft for this impact speed: raise collision.stiffness, or set it to 0 to derive it"
          : "contact too soft for this impact speed: lower collision.max_overlap or set collision.stiffness";
  Failure f;
  char buf[640];
  std::snprintf(buf, sizeof buf, "body '%s' overlaps %s by %.3g m (%.2f d0): %s",
                prm_.bodies[static_cast<std::size_t>(a.body)].name.c_str(), other.c_str(), -gap,
                -gap / prm_.d0, cause);
  f.what = buf;
  f.position = a.pos;
  return f;
}

std::optional<Failure> Solver::collisions() {
  for (auto& g : groups_) {
    g.force_collision = Vec2{};
    g.torque_collision = 0;
  }
  contacts_.clear();
  contact_dt_ = 0;
  list_bodies();
  if (prm_.collision_model == ContactModel::Paper) return paper_collisions();
  const ContactLaw law = contact_law();
  // Imminent contacts (within one particle spacing of the contact distance) already limit the
  // step: no solid crosses d0 in one step at a Mach number below 1/2.
  const real imminent = law.delta_c + prm_.d0;
  const real reach = std::max(imminent, law.lubrication ? law.lub_range : 0.0);
  if (auto f = find_contacts(reach)) return f;
  hold_contact_speeds(imminent);
  contact_stiffness(imminent);
  return std::nullopt;
}

std::optional<Failure> Solver::find_contacts(real reach) {
  const auto is_free = [&](std::size_t k) { return groups_[k].motion == Motion::Free; };
  contact_candidates(body_pos_, body_bound_, reach, domain_, body_pairs_);
  for (const BodyPair& p : body_pairs_) {
    std::size_t a = body_groups_[p.first], b = body_groups_[p.second];
    Contact c = body_contact(placed_body(groups_[a]), placed_body(groups_[b]), domain_);
    if (c.gap < overlap_limit(prm_))
      return overlap_failure(
          groups_[a], "body '" + prm_.bodies[static_cast<std::size_t>(groups_[b].body)].name + "'", c.gap);
    if (!(c.gap < reach) || (!is_free(a) && !is_free(b))) continue;
    if (!is_free(a)) {  // the force law gives side a the force: make it the free one
      std::swap(a, b);
      c.normal = -c.normal;
    }
    contacts_.push_back({a, b, false, c, 0});
  }
  for (const std::size_t a : body_groups_) {
    if (!is_free(a)) continue;
    for (std::size_t w = 0; w < prm_.walls.size(); ++w) {
      const Contact c = wall_contact_exact(placed_body(groups_[a]), wall_now(w));
      if (c.gap > 1e299) continue;
      if (c.gap < overlap_limit(prm_))
        return overlap_failure(groups_[a], "wall '" + groups_[w].name + "'", c.gap);
      if (c.gap < reach) contacts_.push_back({a, w, false, c, 0});  // wall groups come first, in wall order
    }
    // the open boundaries' screens hold bodies back like fixed walls (Case::open_screen_offset)
    for (std::size_t z = 0; z < prm_.open_screens.size(); ++z) {
      if (removes_bodies(z)) continue;  // that screen removes the body instead (remove_bodies_at_outlets)
      const Contact c = wall_contact_exact(placed_body(groups_[a]), prm_.open_screens[z]);
      if (c.gap > 1e299) continue;
      if (c.gap < overlap_limit(prm_))
        return overlap_failure(groups_[a], "the screen of open boundary '" + prm_.open_specs[z].name + "'",
                               c.gap);
      if (c.gap < reach) contacts_.push_back({a, z, true, c, 0});
    }
  }
  return std::nullopt;
}

const RigidGroup& Solver::contact_partner(const StepContact& sc) const {
  static const RigidGroup screen = [] {
    RigidGroup g;  // a fixed wall at rest
    g.is_wall = true;
    g.motion = Motion::Fixed;
    return g;
  }();
  return sc.screen ? screen : groups_[sc.b];
}

void Solver::hold_contact_speeds(real imminent) {
  std::vector<real>& approach = contact_approach_;
  approach.assign(groups_.size(), -1);  // < 0: not near any solid
  for (const StepContact& sc : contacts_) {
    if (!(sc.c.gap < imminent)) continue;
    const RigidGroup &ga = groups_[sc.a], &gb = contact_partner(sc);
    const Vec2 v =
        relative_velocity(contact_side(ga), contact_side(gb), domain_.separation(sc.c.point, ga.pos),
                          domain_.separation(sc.c.point, gb.pos));
    const real speed = std::max(0.0, -dot(v, sc.c.normal));  // relative normal approach speed
    approach[sc.a] = std::max(approach[sc.a], speed);
    if (!gb.is_wall) approach[sc.b] = std::max(approach[sc.b], speed);
  }
  for (const std::size_t k : body_groups_)
    groups_[k].contact_speed = approach[k] < 0 ? 0 : std::max(groups_[k].contact_speed, approach[k]);
}

void Solver::contact_stiffness(real imminent) {
  const real U_c = characteristic_impact_speed();
  const real delta_max = prm_.collision_max_overlap * prm_.d0;
  for (StepContact& sc : contacts_) {
    const RigidGroup &ga = groups_[sc.a], &gb = contact_partner(sc);
    const bool b_moves = gb.motion == Motion::Free && !gb.is_wall;
    const real m_eff = effective_mass(ga.mass, b_moves ? gb.mass : 0.0);
    const real U = std::max({U_c, ga.contact_speed, gb.is_wall ? 0.0 : gb.contact_speed});
    sc.k = prm_.collision_stiffness > 0 ? prm_.collision_stiffness : derived_stiffness(m_eff, U, delta_max);
    if (!(sc.c.gap < imminent)) continue;
    const real dt_limit = contact_duration(m_eff, sc.k) / kStepsPerContact;
    contact_dt_ = contact_dt_ > 0 ? std::min(contact_dt_, dt_limit) : dt_limit;
  }
}

void Solver::contact_forces(real dt) {
  if (contacts_.empty()) return;
  const ContactLaw law = contact_law();
  const real delta_max = prm_.collision_max_overlap * prm_.d0;
  for (const StepContact& sc : contacts_) {
    RigidGroup& ga = groups_[sc.a];
    const RigidGroup& partner = contact_partner(sc);
    const ContactLoad load = spring_dashpot_load(sc.c, contact_side(ga), contact_side(partner),
                                                 domain_.separation(sc.c.point, ga.pos),
                                                 domain_.separation(sc.c.point, partner.pos), sc.k, law, dt);
    ga.force_collision += load.force;
    ga.torque_collision += load.torque_a;
    const bool b_moves = !partner.is_wall && partner.motion == Motion::Free;
    hold_sustained_load(ga, b_moves ? &groups_[sc.b] : nullptr, sc.c.normal, sc.k, delta_max);
    if (partner.is_wall) continue;
    RigidGroup& gb = groups_[sc.b];
    gb.force_collision -= load.force;  // reaction (used when b is free; reported for fixed bodies)
    gb.torque_collision += load.torque_b;
  }
}

Vec2 Solver::non_contact_load(const RigidGroup& g) const {
  return g.force_pressure + g.force_viscous +
         body_weight(g.mass, g.area, prm_.rho0, prm_.gravity, prm_.gravity_in_fluid);
}

void Solver::hold_sustained_load(RigidGroup& a, RigidGroup* b, Vec2 normal, real k, real delta_max) {
  // The derived stiffness stops an impact at the characteristic speed within delta_max; nothing
  // in it sizes the contact for a load that no impact explains: the flow pressing a body onto a
  // screen or a wall, or onto the bodies queued in front of it. The part of each free body's
  // non-contact load (fluid force and reduced weight) that presses it into the contact, L, must
  // compress the spring by at most delta_max / 4 (so that a queue of a few such bodies still
  // stays within delta_max): the held contact speed of the contact's free bodies rises to the U
  // of k = 4 L / delta_max (k = m_eff (U / delta_max)^2), and falls back once they leave every
  // contact (hold_contact_speeds). L does not depend on k, so the rise cannot feed on itself (a
  // rule on the spring force did: raised at a fixed overlap, the force rose with k, and so did the
  // next k; that injected energy and threw bodies apart in a jam at a screen).
  if (prm_.collision_stiffness > 0) return;
  real load = std::max(0.0, -dot(non_contact_load(a), normal));  // normal: from the partner towards a
  if (b) load = std::max(load, dot(non_contact_load(*b), normal));
  if (!(load > 0.25 * k * delta_max)) return;
  const real m_eff = effective_mass(a.mass, b ? b->mass : 0.0);
  const real U = std::sqrt(4 * load * delta_max / m_eff);
  a.contact_speed = std::max(a.contact_speed, U);
  if (b) b->contact_speed = std::max(b->contact_speed, U);
}

real Solver::characteristic_impact_speed() const {
  real U = 1e-3 * prm_.c;  // floor: a speed the explicit step always resolves
  const real g = norm(prm_.gravity);
  for (const RigidGroup& grp : groups_) {
    if (grp.motion == Motion::Fixed || grp.removed) continue;
    const Shape* shape = grp.is_wall ? nullptr : &prm_.bodies[static_cast<std::size_t>(grp.body)].shape;
    // the current speed of every moving solid (free and prescribed bodies, sliding walls)
    U = std::max(U, norm(grp.vel) + std::fabs(grp.omega) * (shape ? shape->bounding_radius() : 0.0));
    // a free body falling its own size under its reduced weight: sqrt(2 g' L), g' = g |1 - rho_f/rho_s|
    if (grp.motion == Motion::Free && shape && grp.mass > 0 && grp.area > 0) {
      const real reduced_g = g * std::fabs(1 - prm_.rho0 * grp.area / grp.mass);
      U = std::max(U, std::sqrt(2 * reduced_g * 2 * shape->equivalent_radius()));
    }
  }
  return U;
}

ContactLaw Solver::contact_law() const {
  ContactLaw law;
  law.delta_c = prm_.collision_range > 0 ? prm_.collision_range : 0.5 * prm_.d0;
  law.zeta = damping_ratio(prm_.collision_restitution);
  law.friction = prm_.collision_friction;
  law.viscosity = prm_.nu * prm_.rho0;
  law.lubrication = prm_.collision_lubrication && law.viscosity > 0;
  law.lub_range = prm_.collision_lubrication_range > 0 ? prm_.collision_lubrication_range : 2 * prm_.d0;
  law.lub_min_gap = 0.1 * prm_.d0;
  return law;
}

ContactSide Solver::contact_side(const RigidGroup& g) const {
  ContactSide s;
  s.pos = g.pos;
  s.vel = g.vel;
  s.omega = g.omega;
  if (g.motion == Motion::Free && !g.is_wall) {
    s.mass = g.mass;
    s.inertia = g.inertia;
  }
  if (!g.is_wall) s.radius = prm_.bodies[static_cast<std::size_t>(g.body)].shape.equivalent_radius();
  return s;
}

std::optional<Failure> Solver::paper_collisions() {
  const real eps = prm_.collision_range > 0 ? prm_.collision_range : 3 * prm_.d0;
  const real k = prm_.collision_stiffness;
  // The candidate pairs in (a, b) order, then each body's walls after its pairs: the order in
  // which the forces were always summed, so the paper's cases are unchanged bit for bit.
  contact_candidates(body_pos_, body_bound_, eps, domain_, body_pairs_);
  std::size_t p = 0;
  for (std::size_t ia = 0; ia < body_groups_.size(); ++ia) {
    RigidGroup& ga = groups_[body_groups_[ia]];
    const PlacedBody pa = placed_body(ga);
    const real Ra = pa.shape->equivalent_radius();
    for (; p < body_pairs_.size() && body_pairs_[p].first == ia; ++p) {
      RigidGroup& gb = groups_[body_groups_[body_pairs_[p].second]];
      const PlacedBody pb = placed_body(gb);
      const Contact c = body_contact(pa, pb, domain_);
      if (c.gap < overlap_limit(prm_))
        return overlap_failure(ga, "body '" + prm_.bodies[static_cast<std::size_t>(gb.body)].name + "'",
                               c.gap);
      const Vec2 F = repulsive_force(c, Ra, pb.shape->equivalent_radius(), k, eps);
      ga.force_collision += F;
      gb.force_collision -= F;
    }
    // walls, as the mirror image of the body (gap to the image = twice the gap to the wall)
    for (std::size_t w = 0; w < prm_.walls.size(); ++w) {
      Contact c = wall_contact(pa, wall_now(w));
      if (c.gap > 1e299) continue;
      if (c.gap < overlap_limit(prm_) && ga.motion == Motion::Free)
        return overlap_failure(ga, "a wall", c.gap);
      c.gap *= 2;
      ga.force_collision += repulsive_force(c, Ra, Ra, k, eps);
    }
    for (std::size_t z = 0; z < prm_.open_screens.size(); ++z) {  // the open boundaries' screens, as walls
      if (removes_bodies(z)) continue;
      Contact c = wall_contact(pa, prm_.open_screens[z]);
      if (c.gap > 1e299) continue;
      if (c.gap < overlap_limit(prm_) && ga.motion == Motion::Free)
        return overlap_failure(ga, "a screen", c.gap);
      c.gap *= 2;
      ga.force_collision += repulsive_force(c, Ra, Ra, k, eps);
    }
  }
  return std::nullopt;
}

std::optional<Failure> Solver::body_at_open_boundary() const {
  for (const RigidGroup& g : groups_) {
    if (g.is_wall || g.removed || prm_.open.empty()) continue;
    for (std::size_t z = 0; z < prm_.open.size(); ++z) {
      const OpenZone& oz = prm_.open[z];
      // the body's surface against the line itself (its screen lies farther in and holds it back)
      const Contact c =
          wall_contact_exact(placed_body(g), WallPiece::segment(oz.from, oz.from + oz.width * oz.t));
      if (!(c.gap < prm_.h)) continue;
      Failure f;
      f.position = g.pos;
      f.what = fmt::format(
          "body '{}' has come within h of {} '{}' ({:.3g} d0 from the line): it was pushed "
          "through the boundary's screen, which holds bodies {:.3g} d0 inside the line, and the "
          "buffer's fit and the body's loads would be cut off there",
          g.name, oz.inlet ? "inlet" : "outlet", prm_.open_specs[z].name, c.gap / prm_.d0,
          dot(prm_.open_screens[z].start() - oz.from, oz.n) / prm_.d0);
      return f;
    }
  }
  return std::nullopt;
}

}  // namespace particula
