// The rigid groups of a run (walls and bodies; docs/architecture.md, "Rigid groups") and their
// part in the step (docs/method.md, "One time step"): their surface particles placed and moved
// through the backend, the stage start they advance from, free bodies advanced in each stage from
// their loads, weight and contact loads, prescribed ones set from their schedule, their update at
// the end of the step, and their health. The loads come from the load band or from the backend's
// surface sums (surface_loads), the contact loads from Contacts; the physics is that of
// bodies/rigid_motion.hpp.
#pragma once

#include <optional>
#include <vector>

#include "particula/bodies/rigid_motion.hpp"
#include "particula/core/types.hpp"
#include "particula/solver/backend.hpp"
#include "particula/solver/failure.hpp"
#include "particula/solver/physics_params.hpp"
#include "particula/solver/rigid_group.hpp"

namespace particula {

class RigidBodies {
 public:
  /// The groups of a run with the physics `prm` (which outlives this component).
  RigidBodies(const PhysicsParams& prm, std::vector<RigidGroup> groups);

  const std::vector<RigidGroup>& groups() const { return groups_; }
  /// The groups for the components that set their loads (the load band, the contacts) or take a
  /// body out of the run (an outlet).
  std::vector<RigidGroup>& groups() { return groups_; }

  /// Places every group's surface particles from its pose: positions, analytic normals,
  /// velocities and accelerations.
  void place(Backend& backend);
  /// The start of a stage: each group's velocities the stage advances from, and at the step's
  /// start its V^n, Omega^n (RigidGroup::vel_n, omega_n).
  void start_stage(StageStart from);
  /// Each group's loads from the backend's surface sum P.26-P.27 (numerics.force = paper).
  void surface_loads(Backend& backend);
  /// One stage of dt ending at t_stage_end: free bodies from their loads, prescribed ones from
  /// their schedule; their surface particles then carry the stage's velocity and acceleration.
  void stage(Backend& backend, real dt, real t_stage_end);
  /// The end of a step of dt ending at t_new: the groups' poses, then their surfaces placed.
  void update(Backend& backend, real dt, real t_new);
  /// A body whose surface has come within h of an open boundary's line (its screen should have
  /// held it back, or removed it): a failure naming both.
  std::optional<Failure> at_open_boundary() const;
  /// The first group with a non-finite motion or load (what bodies.csv and walls.csv hold).
  std::optional<Failure> unhealthy() const;

 private:
  /// Each group's motion as the backend places surfaces from it.
  const std::vector<GroupMotion>& motions();
  /// Free bodies' velocities over one stage from the stage start (free_body_stage).
  void advance_free(RigidGroup& g, std::size_t k, real dt) const;
  /// A prescribed group's pose (with `place`), velocities and accelerations at time t.
  void set_prescribed(RigidGroup& g, real t, bool place) const;

  const PhysicsParams& prm_;
  std::vector<RigidGroup> groups_;
  std::vector<Vec2> v0_;   // each group's velocity at the stage start
  std::vector<real> w0_;   // and its angular velocity
  // each body's surface moments (stage_added_mass, stage_added_inertia)
  std::vector<SurfaceMoments> surface_;
  std::vector<GroupMotion> motions_;
  std::vector<GroupLoads> loads_;  // the backend's surface sums
};

}  // namespace particula
