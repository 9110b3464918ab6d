// The rigid-body side of Solver: group poses and motions, surface placement and kinematics,
// loads (P.26-P.27), the body stages of the predictor-corrector and the P.38 contacts.
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
    for (std::size_t i = g.first; i < g.first + g.count; ++i) surface_kinematics(m, P_.local[i], P_.v[i], P_.acc[i]);
  }
}

void Solver::group_loads() {
  const real mu = prm_.nu * prm_.rho0;
  if (dev_) {
    dev_->group_loads(groups_, mu, loads_);
    for (std::size_t k = 0; k < groups_.size(); ++k) {
      groups_[k].force_pressure = loads_[k].force_pressure;
      groups_[k].force_viscous = loads_[k].force_viscous;
      groups_[k].torque = loads_[k].torque;
    }
    return;
  }
  for (auto& g : groups_) {
    Vec2 fp, fv;
    real torque = 0;
    for (std::size_t i = g.first; i < g.first + g.count; ++i) {
      if (P_.kind[i] != Kind::Boundary) continue;
      Vec2 tp, tv;
      surface_traction(P_.p[i], P_.ds[i], P_.normal[i], gradV_[i], mu, tp, tv);
      fp += tp;
      fv += tv;
      torque += cross(domain_.separation(P_.x[i], g.pos), tp + tv);
    }
    g.force_pressure = fp;
    g.force_viscous = fv;
    g.torque = torque;
  }
}

// ---------------------------------------------------------------------------------------------
// Rigid bodies

void Solver::body_stage(real dt, real t_stage_end, const std::vector<Vec2>& v0, const std::vector<real>& omega0) {
  for (std::size_t k = 0; k < groups_.size(); ++k) {
    RigidGroup& g = groups_[k];
    if (g.motion == Motion::Free) {
      const Vec2 weight = body_weight(g.mass, g.area, prm_.rho0, prm_.gravity, prm_.gravity_in_fluid);
      const Vec2 force = g.force_pressure + g.force_viscous + g.force_collision + weight;
      free_body_stage(g, v0[k], omega0[k], force, g.torque, dt);
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
      const PrescribedState st = prescribed_state(knots ? *knots : std::vector<MotionKnot>{}, vel, omega, t_new);
      g.pos = g.pos0 + st.displacement;
      g.angle = g.angle0 + st.rotation;
      g.vel = st.vel;
      g.omega = st.omega;
      g.acc = st.acc;
      g.alpha = st.alpha;
    }
  }
}

std::optional<Failure> Solver::collisions() {
  for (auto& g : groups_) g.force_collision = Vec2{};
  const real eps = prm_.collision_range > 0 ? prm_.collision_range : 3 * prm_.d0;
  const real k = prm_.collision_stiffness;
  const real overlap_limit = -0.25 * prm_.d0;  // interpenetration beyond sampling noise
  auto placed = [&](const RigidGroup& g) {
    const BodyParams& b = prm_.bodies[static_cast<std::size_t>(g.body)];
    return PlacedBody{&b.shape, &b.samples, g.pos, g.angle};
  };
  auto overlap = [&](const std::string& a, const std::string& b, real gap, Vec2 where) {
    Failure f;
    char buf[512];
    std::snprintf(buf, sizeof buf, "body '%s' overlaps %s by %.3g m (%.2f d0): the collision force did not keep them apart",
                  a.c_str(), b.c_str(), -gap, -gap / prm_.d0);
    f.what = buf;
    f.position = where;
    return f;
  };
  for (std::size_t a = 0; a < groups_.size(); ++a) {
    RigidGroup& ga = groups_[a];
    if (ga.is_wall) continue;
    const PlacedBody pa = placed(ga);
    const real Ra = prm_.bodies[static_cast<std::size_t>(ga.body)].shape.equivalent_radius();
    // bodies
    for (std::size_t b = a + 1; b < groups_.size(); ++b) {
      RigidGroup& gb = groups_[b];
      if (gb.is_wall) continue;
      const PlacedBody pb = placed(gb);
      if (norm(domain_.separation(ga.pos, gb.pos)) > pa.shape->bounding_radius() + pb.shape->bounding_radius() + eps)
        continue;
      const Contact c = body_contact(pa, pb, domain_);
      if (c.gap < overlap_limit) return overlap(prm_.bodies[ga.body].name, "body '" + prm_.bodies[gb.body].name + "'", c.gap, ga.pos);
      const real Rb = pb.shape->equivalent_radius();
      const Vec2 F = repulsive_force(c, Ra, Rb, k, eps);
      ga.force_collision += F;
      gb.force_collision -= F;
    }
    // walls, as the mirror image of the body (gap to the image = twice the gap to the wall)
    for (const auto& w : prm_.walls) {
      Contact c = wall_contact(pa, w.from, w.to, w.normal);
      if (c.gap > 1e299) continue;
      if (c.gap < overlap_limit && ga.motion == Motion::Free)
        return overlap(prm_.bodies[ga.body].name, "a wall", c.gap, ga.pos);
      c.gap *= 2;
      ga.force_collision += repulsive_force(c, Ra, Ra, k, eps);
    }
  }
  return std::nullopt;
}

}  // namespace particula
