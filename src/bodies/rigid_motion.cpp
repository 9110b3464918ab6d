#include "particula/bodies/rigid_motion.hpp"

#include <cmath>

namespace particula {

SurfaceMoments surface_moments(const std::vector<SurfaceSample>& samples) {
  SurfaceMoments m;
  real nxx = 0, nxy = 0, nyy = 0;  // sum n n^T ds
  for (const SurfaceSample& s : samples) {
    const real lever = cross(s.x, s.normal);
    m.length += s.ds;
    nxx += s.normal.x * s.normal.x * s.ds;
    nxy += s.normal.x * s.normal.y * s.ds;
    nyy += s.normal.y * s.normal.y * s.ds;
    m.lever += lever * lever * s.ds;
    m.radius += dot(s.x, s.x) * s.ds;
  }
  // the larger eigenvalue of the symmetric 2x2 sum
  m.normal = 0.5 * (nxx + nyy) + std::sqrt(0.25 * (nxx - nyy) * (nxx - nyy) + nxy * nxy);
  return m;
}

void free_body_stage(RigidGroup& g, Vec2 v0, real omega0, Vec2 force, real torque, real dt, real added_mass,
                     real added_inertia) {
  if (added_mass > 0) {
    const Vec2 a = (force + added_mass * g.acc) / (g.mass + added_mass);
    g.vel = v0 + dt * a;
    g.acc = a;
  } else {
    g.vel = v0 + (dt / g.mass) * force;
    g.acc = (g.vel - v0) / dt;
  }
  if (added_inertia > 0) {
    const real alpha = (torque + added_inertia * g.alpha) / (g.inertia + added_inertia);
    g.omega = omega0 + dt * alpha;
    g.alpha = alpha;
  } else {
    g.omega = omega0 + dt * torque / g.inertia;
    g.alpha = (g.omega - omega0) / dt;
  }
}

void free_body_update(RigidGroup& g, Vec2 v_n, real omega_n, real dt) {
  g.vel = 0.5 * (g.vel + v_n);
  g.omega = 0.5 * (g.omega + omega_n);
  g.pos = g.pos + (0.5 * dt) * (v_n + g.vel);
  g.angle = g.angle + 0.5 * dt * (omega_n + g.omega);
}

PrescribedState prescribed_state(const std::vector<MotionKnot>& k, Vec2 vel, real omega, real t) {
  PrescribedState s;
  if (k.empty()) {
    s.vel = vel;
    s.omega = omega;
    s.displacement = t * vel;
    s.rotation = t * omega;
    return s;
  }
  // Integrate the piecewise-linear velocity from 0 to t segment by segment.
  auto add_segment = [&](real ta, real tb, Vec2 va, Vec2 vb, real wa, real wb) {
    if (tb <= ta) return;
    s.displacement += (0.5 * (tb - ta)) * (va + vb);
    s.rotation += 0.5 * (tb - ta) * (wa + wb);
  };
  auto at = [&](std::size_t i, real time, Vec2& v, real& w, Vec2& a, real& al) {
    const real f = (time - k[i].t) / (k[i + 1].t - k[i].t);
    v = k[i].velocity + f * (k[i + 1].velocity - k[i].velocity);
    w = k[i].omega + f * (k[i + 1].omega - k[i].omega);
    a = (k[i + 1].velocity - k[i].velocity) / (k[i + 1].t - k[i].t);
    al = (k[i + 1].omega - k[i].omega) / (k[i + 1].t - k[i].t);
  };
  real prev_t = 0;
  Vec2 prev_v = k.front().velocity;
  real prev_w = k.front().omega;
  // before the first knot: constant at the first knot's values
  if (t <= k.front().t) {
    s.vel = k.front().velocity;
    s.omega = k.front().omega;
    s.displacement = t * s.vel;
    s.rotation = t * s.omega;
    return s;
  }
  if (k.front().t > 0) {
    add_segment(0, k.front().t, prev_v, prev_v, prev_w, prev_w);
    prev_t = k.front().t;
  } else {
    // the first knot is at or before 0: start from the interpolated value at t = 0
    for (std::size_t i = 0; i + 1 < k.size(); ++i)
      if (k[i + 1].t > 0) {
        Vec2 a;
        real al;
        at(i, 0, prev_v, prev_w, a, al);
        break;
      }
  }
  for (std::size_t i = 0; i + 1 < k.size(); ++i) {
    if (k[i + 1].t <= prev_t) continue;
    const real tb = std::min(t, k[i + 1].t);
    Vec2 v, a;
    real w, al;
    at(i, tb, v, w, a, al);
    add_segment(prev_t, tb, prev_v, v, prev_w, w);
    prev_t = tb;
    prev_v = v;
    prev_w = w;
    if (t <= k[i + 1].t) {
      s.vel = v;
      s.omega = w;
      s.acc = a;
      s.alpha = al;
      return s;
    }
  }
  // after the last knot: constant
  add_segment(prev_t, t, prev_v, prev_v, prev_w, prev_w);
  s.vel = prev_v;
  s.omega = prev_w;
  return s;
}

}  // namespace particula
