// Contacts between solids (docs/method.md, "Contacts"): each step, with the positions frozen, the
// touching and imminent pairs of bodies, walls and open boundaries' screens are found (a failure
// when two solids interpenetrate), each spring-dashpot contact gets its stiffness (the case's, or
// derived from the impact speed) and the step limit t_c / 20 it imposes; once the step's dt is
// known, their forces and torques go into the groups' collision loads. The paper's P.38
// repulsion is the other model (collision.model = "paper").
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "particula/bodies/collision.hpp"
#include "particula/bodies/contact_pairs.hpp"
#include "particula/neighbors/domain.hpp"
#include "particula/solver/failure.hpp"
#include "particula/solver/physics_params.hpp"
#include "particula/solver/rigid_group.hpp"
#include "particula/solver/solids.hpp"

namespace particula {

class Contacts {
 public:
  /// The contacts of the step: clears every group's collision load, finds the touching solids
  /// (a failure when they interpenetrate), and computes the paper's forces, or for the
  /// spring-dashpot the stiffness of each contact and the step limit they impose (dt_limit()).
  std::optional<Failure> find(const PhysicsParams& prm, const Domain& domain, std::vector<RigidGroup>& groups);
  /// The step limit t_c / 20 of the active and imminent spring-dashpot contacts; 0 = none.
  real dt_limit() const { return dt_limit_; }
  /// Spring-dashpot forces and torques of the contacts found by find(), over the step dt.
  void apply(const PhysicsParams& prm, const Domain& domain, std::vector<RigidGroup>& groups, real dt);

 private:
  /// The groups a (a body) and b (a body, a wall, or an open boundary's screen), the geometry
  /// and the stiffness of one contact.
  struct StepContact {
    std::size_t a = 0, b = 0;  // b: a group, or an open boundary's screen (screen = true)
    bool screen = false;
    Contact c;
    real k = 0;
  };
  /// What find() and apply() read: the run's parameters, the domain, the groups.
  struct Scene {
    const PhysicsParams& prm;
    const Domain& domain;
    std::vector<RigidGroup>& groups;
  };
  /// Every pair within `reach` with a free body (as side a), and the free bodies' walls and
  /// screens; a failure when solids interpenetrate.
  std::optional<Failure> find_pairs(const Scene& s, real reach);
  /// A body near another solid (gap below `imminent`) keeps the largest approach speed of the
  /// episode (RigidGroup::contact_speed), so that the derived stiffness of an impact does not drop
  /// as the impact slows the bodies down; 0 once it is clear.
  void hold_contact_speeds(const Scene& s, real imminent);
  /// The stiffness of each contact and the step limit t_c / 20 of the active and imminent ones.
  void set_stiffness(const Scene& s, real imminent);
  /// The paper's P.38 repulsion on the candidate pairs.
  std::optional<Failure> paper_forces(const Scene& s);
  /// The other side of a contact: its group, or a fixed wall at rest standing for a screen.
  static const RigidGroup& partner(const Scene& s, const StepContact& sc);

  std::vector<StepContact> contacts_;
  real dt_limit_ = 0;
  BodyList bodies_;
  std::vector<BodyPair> pairs_;
  std::vector<real> approach_;
};

/// U_c: the characteristic impact speed of the step (docs/method.md, "Contacts").
real characteristic_impact_speed(const PhysicsParams& prm, const std::vector<RigidGroup>& groups);
/// The contact parameters of a run (delta_c, damping ratio, friction, lubrication).
ContactLaw contact_law(const PhysicsParams& prm);
/// One side of a contact: a body's group, or a wall group (mass 0, radius 0).
ContactSide contact_side(const PhysicsParams& prm, const RigidGroup& g);

}  // namespace particula
