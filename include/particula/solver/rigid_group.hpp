// A rigid group: the set of boundary particles that move together (a wall segment, a fixed
// obstacle, a free body). Surface particles are placed from the group's position and angle
// every step, never advanced by x += dt*u.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "particula/core/types.hpp"

namespace particula {

enum class Motion { Fixed, Prescribed, Free };

struct RigidGroup {
  std::string name;
  Motion motion = Motion::Fixed;
  bool is_wall = true;
  // a body taken out of the run at an outlet with `bodies = "removed"` (Solver::remove_body): from
  // then on it has no particles, loads, contacts or motion, and no rows in bodies.csv
  bool removed = false;
  std::int32_t removed_at = -1;  // the open boundary (index into PhysicsParams::open) that removed it
  real removed_time = 0;         // s

  // kinematic state (the frame origin is the centre of mass for bodies)
  Vec2 pos, vel, acc;
  real angle = 0, omega = 0, alpha = 0;
  Vec2 pos0;  // position at t = 0 (prescribed motion: pos = pos0 + vel t)
  real angle0 = 0;

  // boundary particles [first, first + count) of the particle arrays
  std::size_t first = 0, count = 0;

  // bodies (is_wall == false): index into PhysicsParams::bodies, mass properties
  int body = -1;
  real mass = 0, inertia = 0, area = 0;

  // hydrodynamic loads of the last evaluation (P.26-P.27), split by origin, and the
  // contact force and its torque of the step (bodies/collision.hpp)
  Vec2 force_pressure, force_viscous, force_collision;
  real torque = 0;
  // the momentum per unit time the odd-even velocity damping took from the fluid in this solid's
  // load band (numerics.force = momentum; solver/momentum_loads.hpp, band_share_damping), with the
  // sign of a load. Reported (bodies.csv, walls.csv), not a load: the solid does not feel it.
  Vec2 force_damping;
  real torque_collision = 0;

  // spring-dashpot contacts: the largest approach speed of the body's current contact episode
  // (from its first contact until it is clear of every other solid again; 0 when clear). It
  // keeps the derived stiffness of an impact while the bodies slow down in it. Raised also to the
  // speed whose stiffness holds a sustained load within delta_max / 4 (Solver::hold_sustained_load).
  real contact_speed = 0;

  // velocities at the start of the step (the predictor-corrector averages with them)
  Vec2 vel_n;
  real omega_n = 0;
};

}  // namespace particula
