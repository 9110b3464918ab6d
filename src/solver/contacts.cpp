// Contacts between solids (solver/contacts.hpp; bodies/collision.hpp has the laws).
#include "particula/solver/contacts.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "particula/bodies/rigid_motion.hpp"

namespace particula {

namespace {

/// Solids that overlap by more than this are a failure (beyond the sampling noise of the gap).
real overlap_limit(const PhysicsParams& prm) { return -0.25 * prm.d0; }

/// Failure of solids overlapping by more than the sampling noise (exit code 3).
Failure overlap_failure(const PhysicsParams& prm, const RigidGroup& a, const std::string& other, real gap) {
  const char* cause =
      prm.collision_model == ContactModel::Paper ? "the P.38 repulsion did not keep them apart: raise "
                                                   "collision.stiffness (or collision.range), or use "
                                                   "collision.model = \"spring_dashpot\""
      : prm.collision_stiffness > 0
          ? "contact too soft for this impact speed: raise collision.stiffness, or set it to 0 to derive it"
          : "contact too soft for this impact speed: lower collision.max_overlap or set collision.stiffness";
  Failure f;
  char buf[640];
  std::snprintf(buf, sizeof buf, "body '%s' overlaps %s by %.3g m (%.2f d0): %s",
                prm.bodies[static_cast<std::size_t>(a.body)].name.c_str(), other.c_str(), -gap, -gap / prm.d0,
                cause);
  f.what = buf;
  f.position = a.pos;
  return f;
}

/// The name of body group g in a message.
std::string body_name(const PhysicsParams& prm, const RigidGroup& g) {
  return "body '" + prm.bodies[static_cast<std::size_t>(g.body)].name + "'";
}

/// The fluid force and reduced weight of a body (what presses it into its contacts).
Vec2 non_contact_load(const PhysicsParams& prm, const RigidGroup& g) {
  return g.force_pressure + g.force_viscous + body_weight(g.mass, g.area, prm.rho0, prm.gravity, prm.gravity_in_fluid);
}

/// Raises the held contact speed of a contact's free bodies so that the derived stiffness holds
/// the part of their non-contact loads that presses them into it within delta_max / 4.
void hold_sustained_load(const PhysicsParams& prm, RigidGroup& a, RigidGroup* b, Vec2 normal, real k,
                         real delta_max) {
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
  if (prm.collision_stiffness > 0) return;
  real load = std::max(0.0, -dot(non_contact_load(prm, a), normal));  // normal: from the partner towards a
  if (b) load = std::max(load, dot(non_contact_load(prm, *b), normal));
  if (!(load > 0.25 * k * delta_max)) return;
  const real m_eff = effective_mass(a.mass, b ? b->mass : 0.0);
  const real U = std::sqrt(4 * load * delta_max / m_eff);
  a.contact_speed = std::max(a.contact_speed, U);
  if (b) b->contact_speed = std::max(b->contact_speed, U);
}

}  // namespace

std::optional<Failure> Contacts::find(const PhysicsParams& prm, const Domain& domain, std::vector<RigidGroup>& groups) {
  for (auto& g : groups) {
    g.force_collision = Vec2{};
    g.torque_collision = 0;
  }
  contacts_.clear();
  dt_limit_ = 0;
  bodies_.list(prm, groups);
  const Scene s{prm, domain, groups};
  if (prm.collision_model == ContactModel::Paper) return paper_forces(s);
  const ContactLaw law = contact_law(prm);
  // Imminent contacts (within one particle spacing of the contact distance) already limit the
  // step: no solid crosses d0 in one step at a Mach number below 1/2.
  const real imminent = law.delta_c + prm.d0;
  const real reach = std::max(imminent, law.lubrication ? law.lub_range : 0.0);
  if (auto f = find_pairs(s, reach)) return f;
  hold_contact_speeds(s, imminent);
  set_stiffness(s, imminent);
  return std::nullopt;
}

std::optional<Failure> Contacts::find_pairs(const Scene& s, real reach) {
  const PhysicsParams& prm = s.prm;
  std::vector<RigidGroup>& groups = s.groups;
  const auto is_free = [&](std::size_t k) { return groups[k].motion == Motion::Free; };
  contact_candidates(bodies_.pos, bodies_.bound, reach, s.domain, pairs_);
  for (const BodyPair& p : pairs_) {
    std::size_t a = bodies_.groups[p.first], b = bodies_.groups[p.second];
    Contact c = body_contact(placed_body(prm, groups[a]), placed_body(prm, groups[b]), s.domain);
    if (c.gap < overlap_limit(prm)) return overlap_failure(prm, groups[a], body_name(prm, groups[b]), c.gap);
    if (!(c.gap < reach) || (!is_free(a) && !is_free(b))) continue;
    if (!is_free(a)) {  // the force law gives side a the force: make it the free one
      std::swap(a, b);
      c.normal = -c.normal;
    }
    contacts_.push_back({a, b, false, c, 0});
  }
  for (const std::size_t a : bodies_.groups) {
    if (!is_free(a)) continue;
    for (std::size_t w = 0; w < prm.walls.size(); ++w) {
      const Contact c = wall_contact_exact(placed_body(prm, groups[a]), wall_now(prm, groups, w));
      if (c.gap > 1e299) continue;
      if (c.gap < overlap_limit(prm)) return overlap_failure(prm, groups[a], "wall '" + groups[w].name + "'", c.gap);
      if (c.gap < reach) contacts_.push_back({a, w, false, c, 0});  // wall groups come first, in wall order
    }
    // the open boundaries' screens hold bodies back like fixed walls (Case::open_screen_offset)
    for (std::size_t z = 0; z < prm.open_screens.size(); ++z) {
      if (removes_bodies(prm, z)) continue;  // that screen removes the body instead (OpenBoundaries)
      const Contact c = wall_contact_exact(placed_body(prm, groups[a]), prm.open_screens[z]);
      if (c.gap > 1e299) continue;
      if (c.gap < overlap_limit(prm))
        return overlap_failure(prm, groups[a], "the screen of open boundary '" + prm.open_specs[z].name + "'",
                               c.gap);
      if (c.gap < reach) contacts_.push_back({a, z, true, c, 0});
    }
  }
  return std::nullopt;
}

const RigidGroup& Contacts::partner(const Scene& s, const StepContact& sc) {
  static const RigidGroup screen = [] {
    RigidGroup g;  // a fixed wall at rest
    g.is_wall = true;
    g.motion = Motion::Fixed;
    return g;
  }();
  return sc.screen ? screen : s.groups[sc.b];
}

void Contacts::hold_contact_speeds(const Scene& s, real imminent) {
  std::vector<RigidGroup>& groups = s.groups;
  approach_.assign(groups.size(), -1);  // < 0: not near any solid
  for (const StepContact& sc : contacts_) {
    if (!(sc.c.gap < imminent)) continue;
    const RigidGroup &ga = groups[sc.a], &gb = partner(s, sc);
    const Vec2 v = relative_velocity(contact_side(s.prm, ga), contact_side(s.prm, gb),
                                     s.domain.separation(sc.c.point, ga.pos), s.domain.separation(sc.c.point, gb.pos));
    const real speed = std::max(0.0, -dot(v, sc.c.normal));  // relative normal approach speed
    approach_[sc.a] = std::max(approach_[sc.a], speed);
    if (!gb.is_wall) approach_[sc.b] = std::max(approach_[sc.b], speed);
  }
  for (const std::size_t k : bodies_.groups)
    groups[k].contact_speed = approach_[k] < 0 ? 0 : std::max(groups[k].contact_speed, approach_[k]);
}

void Contacts::set_stiffness(const Scene& s, real imminent) {
  const PhysicsParams& prm = s.prm;
  const real U_c = characteristic_impact_speed(prm, s.groups);
  const real delta_max = prm.collision_max_overlap * prm.d0;
  for (StepContact& sc : contacts_) {
    const RigidGroup &ga = s.groups[sc.a], &gb = partner(s, sc);
    const bool b_moves = gb.motion == Motion::Free && !gb.is_wall;
    const real m_eff = effective_mass(ga.mass, b_moves ? gb.mass : 0.0);
    const real U = std::max({U_c, ga.contact_speed, gb.is_wall ? 0.0 : gb.contact_speed});
    sc.k = prm.collision_stiffness > 0 ? prm.collision_stiffness : derived_stiffness(m_eff, U, delta_max);
    if (!(sc.c.gap < imminent)) continue;
    const real dt_limit = contact_duration(m_eff, sc.k) / kStepsPerContact;
    dt_limit_ = dt_limit_ > 0 ? std::min(dt_limit_, dt_limit) : dt_limit;
  }
}

void Contacts::apply(const PhysicsParams& prm, const Domain& domain, std::vector<RigidGroup>& groups, real dt) {
  if (contacts_.empty()) return;
  const Scene s{prm, domain, groups};
  const ContactLaw law = contact_law(prm);
  const real delta_max = prm.collision_max_overlap * prm.d0;
  for (const StepContact& sc : contacts_) {
    RigidGroup& ga = groups[sc.a];
    const RigidGroup& other = partner(s, sc);
    const ContactLoad load =
        spring_dashpot_load(sc.c, contact_side(prm, ga), contact_side(prm, other), domain.separation(sc.c.point, ga.pos),
                            domain.separation(sc.c.point, other.pos), sc.k, law, dt);
    ga.force_collision += load.force;
    ga.torque_collision += load.torque_a;
    const bool b_moves = !other.is_wall && other.motion == Motion::Free;
    hold_sustained_load(prm, ga, b_moves ? &groups[sc.b] : nullptr, sc.c.normal, sc.k, delta_max);
    if (other.is_wall) continue;
    RigidGroup& gb = groups[sc.b];
    gb.force_collision -= load.force;  // reaction (used when b is free; reported for fixed bodies)
    gb.torque_collision += load.torque_b;
  }
}

std::optional<Failure> Contacts::paper_forces(const Scene& s) {
  const PhysicsParams& prm = s.prm;
  const real eps = prm.collision_range > 0 ? prm.collision_range : 3 * prm.d0;
  const real k = prm.collision_stiffness;
  // The candidate pairs in (a, b) order, then each body's walls after its pairs: the order in
  // which the forces were always summed, so the paper's cases are unchanged bit for bit.
  contact_candidates(bodies_.pos, bodies_.bound, eps, s.domain, pairs_);
  std::size_t p = 0;
  for (std::size_t ia = 0; ia < bodies_.groups.size(); ++ia) {
    RigidGroup& ga = s.groups[bodies_.groups[ia]];
    const PlacedBody pa = placed_body(prm, ga);
    const real Ra = pa.shape->equivalent_radius();
    for (; p < pairs_.size() && pairs_[p].first == ia; ++p) {
      RigidGroup& gb = s.groups[bodies_.groups[pairs_[p].second]];
      const PlacedBody pb = placed_body(prm, gb);
      const Contact c = body_contact(pa, pb, s.domain);
      if (c.gap < overlap_limit(prm)) return overlap_failure(prm, ga, body_name(prm, gb), c.gap);
      const Vec2 F = repulsive_force(c, Ra, pb.shape->equivalent_radius(), k, eps);
      ga.force_collision += F;
      gb.force_collision -= F;
    }
    // walls and the open boundaries' screens, as the mirror image of the body (gap to the image
    // = twice the gap to the wall)
    const auto repel_from = [&](const WallPiece& w, const char* what) -> std::optional<Failure> {
      Contact c = wall_contact(pa, w);
      if (c.gap > 1e299) return std::nullopt;
      if (c.gap < overlap_limit(prm) && ga.motion == Motion::Free) return overlap_failure(prm, ga, what, c.gap);
      c.gap *= 2;
      ga.force_collision += repulsive_force(c, Ra, Ra, k, eps);
      return std::nullopt;
    };
    for (std::size_t w = 0; w < prm.walls.size(); ++w)
      if (auto f = repel_from(wall_now(prm, s.groups, w), "a wall")) return f;
    for (std::size_t z = 0; z < prm.open_screens.size(); ++z)
      if (!removes_bodies(prm, z))
        if (auto f = repel_from(prm.open_screens[z], "a screen")) return f;
  }
  return std::nullopt;
}

real characteristic_impact_speed(const PhysicsParams& prm, const std::vector<RigidGroup>& groups) {
  real U = 1e-3 * prm.c;  // floor: a speed the explicit step always resolves
  const real g = norm(prm.gravity);
  for (const RigidGroup& grp : groups) {
    if (grp.motion == Motion::Fixed || grp.removed) continue;
    const Shape* shape = grp.is_wall ? nullptr : &prm.bodies[static_cast<std::size_t>(grp.body)].shape;
    // the current speed of every moving solid (free and prescribed bodies, sliding walls)
    U = std::max(U, norm(grp.vel) + std::fabs(grp.omega) * (shape ? shape->bounding_radius() : 0.0));
    // a free body falling its own size under its reduced weight: sqrt(2 g' L), g' = g |1 - rho_f/rho_s|
    if (grp.motion == Motion::Free && shape && grp.mass > 0 && grp.area > 0) {
      const real reduced_g = g * std::fabs(1 - prm.rho0 * grp.area / grp.mass);
      U = std::max(U, std::sqrt(2 * reduced_g * 2 * shape->equivalent_radius()));
    }
  }
  return U;
}

ContactLaw contact_law(const PhysicsParams& prm) {
  ContactLaw law;
  law.delta_c = prm.collision_range > 0 ? prm.collision_range : 0.5 * prm.d0;
  law.zeta = damping_ratio(prm.collision_restitution);
  law.friction = prm.collision_friction;
  law.viscosity = prm.nu * prm.rho0;
  law.lubrication = prm.collision_lubrication && law.viscosity > 0;
  law.lub_range = prm.collision_lubrication_range > 0 ? prm.collision_lubrication_range : 2 * prm.d0;
  law.lub_min_gap = 0.1 * prm.d0;
  return law;
}

ContactSide contact_side(const PhysicsParams& prm, const RigidGroup& g) {
  ContactSide s;
  s.pos = g.pos;
  s.vel = g.vel;
  s.omega = g.omega;
  if (g.motion == Motion::Free && !g.is_wall) {
    s.mass = g.mass;
    s.inertia = g.inertia;
  }
  if (!g.is_wall) s.radius = prm.bodies[static_cast<std::size_t>(g.body)].shape.equivalent_radius();
  return s;
}

}  // namespace particula
