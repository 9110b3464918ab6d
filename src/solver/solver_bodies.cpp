// The rigid-body side of Solver: group poses and motions, surface placement and kinematics,
// the body stages of the predictor-corrector (the contacts: contacts.cpp; the loads:
// solver_loads.cpp).
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

void Solver::place_boundary() { backend_->surface_motion(group_motions(), true); }

void Solver::set_boundary_kinematics() { backend_->surface_motion(group_motions(), false); }

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

std::optional<Failure> Solver::body_at_open_boundary() const {
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

}  // namespace particula
