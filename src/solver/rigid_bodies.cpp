// The rigid groups and their part in the step (solver/rigid_bodies.hpp).
#include "particula/solver/rigid_bodies.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>
#include <utility>

#include "particula/bodies/collision.hpp"
#include "particula/bodies/rigid_motion.hpp"
#include "particula/solver/solids.hpp"

namespace particula {

RigidBodies::RigidBodies(const PhysicsParams& prm, std::vector<RigidGroup> groups)
    : prm_(prm), groups_(std::move(groups)), surface_(groups_.size()) {
  for (std::size_t k = 0; k < groups_.size(); ++k)
    if (groups_[k].body >= 0)
      surface_[k] = surface_moments(prm_.bodies[static_cast<std::size_t>(groups_[k].body)].samples);
}

const std::vector<GroupMotion>& RigidBodies::motions() {
  motions_.resize(groups_.size());
  for (std::size_t k = 0; k < groups_.size(); ++k) motions_[k] = group_motion(groups_[k]);
  return motions_;
}

void RigidBodies::place(Backend& backend) { backend.surface_motion(motions(), true); }

void RigidBodies::start_stage(StageStart from) {
  v0_.resize(groups_.size());
  w0_.resize(groups_.size());
  for (std::size_t k = 0; k < groups_.size(); ++k) {
    RigidGroup& g = groups_[k];
    v0_[k] = g.vel;
    w0_[k] = g.omega;
    if (from == StageStart::StepStart) {
      g.vel_n = g.vel;
      g.omega_n = g.omega;
    }
  }
}

void RigidBodies::surface_loads(Backend& backend) {
  backend.group_loads(groups_, prm_.nu * prm_.rho0, loads_);
  for (std::size_t k = 0; k < groups_.size(); ++k) {
    groups_[k].force_pressure = loads_[k].force_pressure;
    groups_[k].force_viscous = loads_[k].force_viscous;
    groups_[k].torque = loads_[k].torque;
  }
}

void RigidBodies::advance_free(RigidGroup& g, std::size_t k, real dt) const {
  const Vec2 weight = body_weight(g.mass, g.area, prm_.rho0, prm_.gravity, prm_.gravity_in_fluid);
  const Vec2 force = g.force_pressure + g.force_viscous + g.force_collision + weight;
  // the fluid's one-stage answer to the body's accelerations (docs/method.md, "Light bodies")
  const real m1 = stage_added_mass(prm_.rho0, prm_.d0, prm_.nu, dt, surface_[k]);
  const real i1 = stage_added_inertia(prm_.rho0, prm_.d0, prm_.nu, dt, surface_[k]);
  free_body_stage(g, v0_[k], w0_[k], force, g.torque + g.torque_collision, dt,
                  stabilizing_added_mass(prm_.rho0, g.area, g.mass, m1),
                  stabilizing_added_inertia(i1, g.inertia));
}

void RigidBodies::set_prescribed(RigidGroup& g, real t, bool place) const {
  // a body's schedule, or a turning wall's constant motion
  Vec2 vel = g.vel;
  real omega = g.omega;
  const std::vector<MotionKnot>* knots = nullptr;
  if (g.body >= 0) {
    const BodyParams& b = prm_.bodies[static_cast<std::size_t>(g.body)];
    vel = b.velocity;
    omega = b.omega;
    knots = &b.schedule;
  }
  const PrescribedState st = prescribed_state(knots ? *knots : std::vector<MotionKnot>{}, vel, omega, t);
  if (place) {
    g.pos = g.pos0 + st.displacement;
    g.angle = g.angle0 + st.rotation;
  }
  g.vel = st.vel;
  g.omega = st.omega;
  g.acc = st.acc;
  g.alpha = st.alpha;
}

void RigidBodies::stage(Backend& backend, real dt, real t_stage_end) {
  for (std::size_t k = 0; k < groups_.size(); ++k) {
    RigidGroup& g = groups_[k];
    if (g.removed) continue;
    if (g.motion == Motion::Free)
      advance_free(g, k, dt);
    else if (g.motion == Motion::Prescribed && g.body >= 0)
      set_prescribed(g, t_stage_end, false);
  }
  backend.surface_motion(motions(), false);
}

void RigidBodies::update(Backend& backend, real dt, real t_new) {
  for (RigidGroup& g : groups_) {
    if (g.removed) continue;
    if (g.motion == Motion::Free)
      free_body_update(g, g.vel_n, g.omega_n, dt);
    else if (g.motion == Motion::Prescribed)
      set_prescribed(g, t_new, true);
  }
  place(backend);
}

std::optional<Failure> RigidBodies::at_open_boundary() const {
  for (const RigidGroup& g : groups_) {
    if (g.is_wall || g.removed || prm_.open.empty()) continue;
    for (std::size_t z = 0; z < prm_.open.size(); ++z) {
      const OpenZone& oz = prm_.open[z];
      // the body's surface against the line itself (its screen lies farther in and holds it back)
      const Contact c =
          wall_contact_exact(placed_body(prm_, g), WallPiece::segment(oz.from, oz.from + oz.width * oz.t));
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

std::optional<Failure> RigidBodies::unhealthy() const {
  for (const RigidGroup& g : groups_) {
    const real values[] = {g.pos.x,
                           g.pos.y,
                           g.vel.x,
                           g.vel.y,
                           g.angle,
                           g.omega,
                           g.torque,
                           g.force_pressure.x,
                           g.force_pressure.y,
                           g.force_viscous.x,
                           g.force_viscous.y,
                           g.force_collision.x,
                           g.force_collision.y,
                           g.force_damping.x,
                           g.force_damping.y};
    if (std::all_of(std::begin(values), std::end(values), [](real v) { return std::isfinite(v); })) continue;
    Failure f;
    f.position = std::isfinite(g.pos.x) && std::isfinite(g.pos.y) ? g.pos : Vec2{};
    f.what = std::string("non-finite value (NaN or Inf) in the motion or force of ") +
             (g.is_wall ? "wall '" : "body '") + g.name + "'";
    return f;
  }
  return std::nullopt;
}

}  // namespace particula
