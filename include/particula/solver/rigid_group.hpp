// A rigid group: the set of boundary particles that move together (a wall segment, a fixed
// obstacle, a free body). Surface particles are placed from the group's position and angle
// every step, never advanced by x += dt*u.
#pragma once

#include <string>
#include <vector>

#include "particula/core/types.hpp"

namespace particula {

enum class Motion { Fixed, Prescribed, Free };

struct RigidGroup {
  std::string name;
  Motion motion = Motion::Fixed;
  bool is_wall = true;

  // kinematic state (the frame origin is the centre of mass for bodies)
  Vec2 pos, vel, acc;
  real angle = 0, omega = 0, alpha = 0;
  Vec2 pos0;         // position at t = 0 (prescribed motion: pos = pos0 + vel t)
  real angle0 = 0;

  // boundary particles [first, first + count) of the particle arrays
  std::size_t first = 0, count = 0;

  // bodies (is_wall == false): index into PhysicsParams::bodies, mass properties
  int body = -1;
  real mass = 0, inertia = 0, area = 0;

  // hydrodynamic loads of the last evaluation (P.26-P.27), split by origin, and the
  // collision force (P.38) of the step
  Vec2 force_pressure, force_viscous, force_collision;
  real torque = 0;

  // velocities at the start of the step (the predictor-corrector averages with them)
  Vec2 vel_n;
  real omega_n = 0;
};

}  // namespace particula
