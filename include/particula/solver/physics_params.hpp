// What the physics of a run needs, in SI units: the parameters the scene builder derives from a
// Case (physics never reads the case file). They carry no defaults of their own (value-initialised):
// physics_params() (src/scene/scene.cpp) sets every one from a Case, whose defaults are the
// schema's (default_case()).
#pragma once

#include <string>
#include <vector>

#include "particula/bodies/collision.hpp"
#include "particula/boundary/open_boundary.hpp"
#include "particula/case/case.hpp"
#include "particula/core/types.hpp"
#include "particula/core/types3.hpp"
#include "particula/geometry/shape.hpp"
#include "particula/geometry/wall_piece.hpp"

namespace particula {

/// A rigid body's shape and motion law (index = RigidGroup::body).
struct BodyParams {
  std::string name;
  Shape shape;
  std::vector<SurfaceSample> samples;  // body frame, used by the contact model
  BodyMotion motion{};
  Vec2 velocity;  // prescribed constant velocity (no schedule)
  real omega{};
  std::vector<MotionKnot> schedule;  // prescribed piecewise-linear motion
  // A fixed body standing on walls or crossing them (scene: its part beyond the walls left out):
  // the stretches of walls it covers, and the area of its part in the fluid region with that
  // part's centroid (world frame). The smooth pressure's force on it is taken over its wetted
  // surface from these (Solver::smooth_pressure_load). Other bodies: the whole body.
  struct Cover {
    std::size_t wall{};
    real s0{}, s1{};  // fractions along the wall
  };
  std::vector<Cover> covers;
  real area_in{};
  Vec2 centroid_in;
};

/// Steps between cell reorderings of the fluid block (a cost setting, not a case key).
inline constexpr int kReorderInterval = 50;

/// The fluid and the numerics of its passes, in D dimensions: what the particle passes of a step
/// read (solver/cpu_sweeps.hpp), the same in 2D and 3D.
template <int D>
struct FluidParamsOf {
  real d0{}, h{};
  real rho0{}, nu{}, c{}, p0{};
  Vec<D> gravity;
  bool gravity_in_fluid{};
  Vec<D> body_force;
  real cfl{};
  real dt_max{};
  bool fatehi_manzari{};         // false: Morris Laplacian (baseline)
  bool zeroth_order_gradient{};  // numerics.gradient = "consistent" (sweeps.hpp, geometry_at)
  bool single_layer{};           // false: dummy-particle boundary (baseline)
  bool kernel_normals{};         // false: analytic normals
  bool momentum_force{};         // loads from the fluid's momentum balance (true) or P.26-P.27 (false)
  real rhie_chow_factor{};
  real odd_even_damping{};  // alpha of the velocity odd-even damping, kappa = alpha c h
  real shifting_beta{};
  real surface_guard{};  // keep-out distance of fluid from surfaces, in d0 (0: off)
  real film_gap{};       // gap below which fluid between two surfaces is an unresolved film, in d0 (0: off)
  int wall_pressure_sweeps{};
  real rho_min_ratio{}, rho_max_ratio{};
  int reorder_interval{};  // steps between cell reorderings of the fluid block (kReorderInterval)
};

/// The scalar parameters and numerics of `from` for a fluid in D dimensions, its vectors (gravity,
/// body force) left zero for the caller: a 3D fluid with a 2D case's numerics (the schema's
/// defaults, physics_params of a Case) while cases are 2D.
template <int D, int E>
FluidParamsOf<D> fluid_scalars(const FluidParamsOf<E>& from) {
  FluidParamsOf<D> p;
  p.d0 = from.d0;
  p.h = from.h;
  p.rho0 = from.rho0;
  p.nu = from.nu;
  p.c = from.c;
  p.p0 = from.p0;
  p.gravity_in_fluid = from.gravity_in_fluid;
  p.cfl = from.cfl;
  p.dt_max = from.dt_max;
  p.fatehi_manzari = from.fatehi_manzari;
  p.zeroth_order_gradient = from.zeroth_order_gradient;
  p.single_layer = from.single_layer;
  p.kernel_normals = from.kernel_normals;
  p.momentum_force = from.momentum_force;
  p.rhie_chow_factor = from.rhie_chow_factor;
  p.odd_even_damping = from.odd_even_damping;
  p.shifting_beta = from.shifting_beta;
  p.surface_guard = from.surface_guard;
  p.film_gap = from.film_gap;
  p.wall_pressure_sweeps = from.wall_pressure_sweeps;
  p.rho_min_ratio = from.rho_min_ratio;
  p.rho_max_ratio = from.rho_max_ratio;
  p.reorder_interval = from.reorder_interval;
  return p;
}

/// Everything the physics needs, in SI units (filled from a Case by the scene builder): the
/// fluid's parameters and the 2D solids, contacts and open boundaries.
struct PhysicsParams : FluidParamsOf<2> {
  // numerics.load_band_motion (m): the band of the momentum loads is kept until a solid surface
  // or a particle (relative to its closest solid) has moved this far since it was built, less
  // between two solids close together (0: built every step)
  real load_band_motion{};
  std::vector<BodyParams> bodies;
  std::vector<WallPiece> walls;  // at t = 0 (a turning wall: Solver::wall_now)
  // contacts (bodies/collision.hpp; docs/method.md, "Contacts")
  ContactModel collision_model{};
  real collision_stiffness{};  // spring_dashpot: k_n (0 = derived); paper: k of P.38
  real collision_range{};      // contact distance delta_c (m); 0 = 0.5 d0 (spring_dashpot), 3 d0 (paper)
  real collision_restitution{};
  real collision_friction{};
  real collision_max_overlap{};  // delta_max / d0
  bool collision_lubrication{};
  real collision_lubrication_range{};  // m; 0 = 2 d0
  bool cuda{};                         // particle passes on the GPU (--backend cuda)
  // open boundaries (boundary/open_boundary.hpp): inlets then outlets, the zone and its case entry
  std::vector<OpenZone> open;
  std::vector<OpenSpec> open_specs;
  // each open boundary's screen (Case::open_screen_offset): a segment inside the fluid, parallel to
  // the line, that bodies meet like a fixed wall; the fluid passes it
  std::vector<WallPiece> open_screens;
};

}  // namespace particula
