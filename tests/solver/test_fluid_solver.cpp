// The fluid solver (solver/fluid_solver.hpp): in 2D a wall-bounded flow gives bitwise the fluid
// of Solver, step for step (the two time loops cannot drift apart); in 3D, on the box scene
// (scene/box3.hpp), a closed box of fluid under gravity stays at rest with the hydrostatic
// pressure, and start-up flow in a square duct follows the series solution.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "case_builders.hpp"
#include "particula/analytic/solutions.hpp"
#include "particula/scene/box3.hpp"
#include "particula/scene/scene.hpp"
#include "particula/solver/fluid_solver.hpp"
#include "particula/solver/solver.hpp"

using namespace particula;
using namespace particula::cases;

namespace {

template <class T>
bool bitwise_equal(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

/// Steps the case with Solver and with FluidSolverOf<2> and expects the same fluid after each step.
void expect_same_fluid_as_solver(const Case& c, int steps) {
  const Scene sc = build_scene(c);
  Solver solver(sc.params, sc.domain, sc.particles, sc.groups);
  FluidSolverOf<2> fluid(sc.params, sc.domain, sc.particles);
  for (int s = 0; s < steps; ++s) {
    ASSERT_FALSE(solver.step().has_value());
    ASSERT_FALSE(fluid.step().has_value());
    ASSERT_EQ(solver.last_dt(), fluid.last_dt()) << "step " << s;
    const Particles &a = solver.particles(), &b = fluid.particles();
    ASSERT_TRUE(bitwise_equal(a.x, b.x)) << "step " << s;
    ASSERT_TRUE(bitwise_equal(a.v, b.v)) << "step " << s;
    ASSERT_TRUE(bitwise_equal(a.rho, b.rho)) << "step " << s;
    ASSERT_TRUE(bitwise_equal(a.p, b.p)) << "step " << s;
  }
}

/// The fluid and numerics of a 3D case: water-like, default numerics.
FluidParamsOf<3> fluid3(real d0, real rho0, real nu, real c_sound) {
  Case c = default_case();
  c.d0 = d0;
  c.rho0 = rho0;
  c.nu = nu;
  c.c = c_sound;
  return fluid_scalars<3>(physics_params(c));
}

/// The measures of a 3D box of fluid at rest after a run (run_at_rest).
struct AtRest {
  std::int64_t steps = 0;
  real vmax = 0;         // the fastest fluid particle, m/s
  real fluid_err = 0;    // the largest |P - rho0 g (H - z)| of a fluid particle, Pa
  real surface_err = 0;  // the same at the surface particles of the group asked for, Pa
};

/// The box of `spec` under gravity g along -z kept in the fluid, started in the hydrostatic state
/// (P = rho0 g (H - z), rho from the equation of state at sound speed c) and run to t_end.
AtRest run_at_rest(const BoxSpec3& spec, real g, real c, real t_end, std::int32_t surface_group = -1) {
  BoxScene3 sc = build_box3(spec);
  const real H = spec.hi.z;
  const auto hydrostatic = [&](Vec3 x) { return spec.rho0 * g * (H - x.z); };
  for (std::size_t i = 0; i < sc.particles.size(); ++i) {
    sc.particles.p[i] = hydrostatic(sc.particles.x[i]);
    sc.particles.rho[i] = spec.rho0 + sc.particles.p[i] / (c * c);
    sc.particles.m[i] *= sc.particles.rho[i] / spec.rho0;
  }
  FluidParamsOf<3> prm = fluid3(spec.d0, spec.rho0, 1e-6, c);
  prm.gravity = {0, 0, -g};
  prm.gravity_in_fluid = true;
  FluidSolverOf<3> solver(prm, sc.domain, sc.particles);
  while (solver.time() < t_end)
    if (auto f = solver.step()) {
      ADD_FAILURE() << "t = " << solver.time() << ": " << f->what;
      break;
    }
  const Particles3& P = solver.particles();
  AtRest r;
  r.steps = solver.step_count();
  for (std::size_t i = 0; i < P.size(); ++i) {
    const real e = std::fabs(P.p[i] - hydrostatic(P.x[i]));
    if (i >= P.n_boundary) {
      r.vmax = std::fmax(r.vmax, norm(P.v[i]));
      r.fluid_err = std::fmax(r.fluid_err, e);
    } else if (P.group[i] == surface_group) {
      r.surface_err = std::fmax(r.surface_err, e);
    }
  }
  return r;
}
}  // namespace

TEST(FluidSolver, TwoDimensionalWallFlowsAreBitwiseSolvers) {
  Case box = closed_box(0.01, 0.008, 5e-4);  // hydrostatic, with box corners
  box.gravity = {0, -9.81};
  box.c = 5;
  expect_same_fluid_as_solver(box, 25);
  expect_same_fluid_as_solver(startup_channel(20, 0, 1e-4), 25);  // body force, periodic
}

TEST(FluidSolver, ClosedBoxUnderGravityStaysAtRestIn3D) {
  const real L = 0.01, g = 9.81;
  BoxSpec3 spec;
  spec.lo = {0, 0, 0};
  spec.hi = {L, 0.8 * L, 1.2 * L};
  spec.d0 = L / 10;
  spec.rho0 = 1000;
  const AtRest r = run_at_rest(spec, g, 5, 0.005);
  const real H = spec.hi.z, p_bottom = spec.rho0 * g * H;
  std::printf(
      "3D hydrostatic box: %lld steps, max |V| %.3g m/s (%.3g of sqrt(g H)), max |P - P_h| %.3g of rho0 g "
      "H\n",
      static_cast<long long>(r.steps), r.vmax, r.vmax / std::sqrt(g * H), r.fluid_err / p_bottom);
  EXPECT_LT(r.vmax, 1e-3 * std::sqrt(g * H));
  EXPECT_LT(r.fluid_err, 2e-2 * p_bottom);
}

TEST(FluidSolver, SquareDuctStartUpFollowsTheSeriesSolutionIn3D) {
  // Morris-like parameters (reference/README.md) in a duct of side L, 10 particles across,
  // periodic along x (8 spacings long), driven by F along x.
  const real L = 1e-3, d0 = L / 10, F = 1e-4, nu = 1e-6;
  BoxSpec3 spec;
  spec.lo = {0, 0, 0};
  spec.hi = {8 * d0, L, L};
  spec.periodic[0] = true;
  spec.d0 = d0;
  spec.rho0 = 1000;
  const BoxScene3 sc = build_box3(spec);
  FluidParamsOf<3> prm = fluid3(d0, spec.rho0, nu, 2.5e-4);
  prm.body_force = {F, 0, 0};
  FluidSolverOf<3> solver(prm, sc.domain, sc.particles);
  const real u_max = analytic::duct_startup(0.5 * L, 0.5 * L, 1e3, L, L, F, nu);
  for (const real t_check : {0.02, 0.1}) {
    while (solver.time() < t_check)
      ASSERT_FALSE(solver.step_to(t_check).has_value()) << "t = " << solver.time();
    const Particles3& P = solver.particles();
    real e2 = 0, transverse = 0;
    std::size_t n = 0;
    for (std::size_t i = P.n_boundary; i < P.size(); ++i) {
      const real u = analytic::duct_startup(P.x[i].y, P.x[i].z, solver.time(), L, L, F, nu);
      e2 += (P.v[i].x - u) * (P.v[i].x - u);
      transverse = std::fmax(transverse, std::hypot(P.v[i].y, P.v[i].z));
      ++n;
    }
    const real err = std::sqrt(e2 / n) / u_max;
    std::printf(
        "duct at t = %g s (%lld steps): rms error %.3g of u_max, largest transverse speed %.3g of u_max\n",
        solver.time(), static_cast<long long>(solver.step_count()), err, transverse / u_max);
    EXPECT_LT(err, 0.01) << "t = " << t_check;
    EXPECT_LT(transverse, 1e-6 * u_max) << "t = " << t_check;
  }
}

TEST(FluidSolver, StartUpCouetteBetweenPlatesIn3D) {
  // the upper plate (+y face) slides along x at V0 from t = 0; periodic along x and z
  const real L = 1e-3, d0 = L / 10, V0 = 1.25e-5, nu = 1e-6;
  BoxSpec3 spec;
  spec.lo = {0, 0, 0};
  spec.hi = {8 * d0, L, 8 * d0};
  spec.periodic[0] = true;
  spec.periodic[2] = true;
  spec.d0 = d0;
  spec.rho0 = 1000;
  spec.face_velocity[3] = {V0, 0, 0};
  const BoxScene3 sc = build_box3(spec);
  FluidSolverOf<3> solver(fluid3(d0, spec.rho0, nu, 2.5e-4), sc.domain, sc.particles);
  for (const real t_check : {0.02, 0.1}) {
    while (solver.time() < t_check)
      ASSERT_FALSE(solver.step_to(t_check).has_value()) << "t = " << solver.time();
    const Particles3& P = solver.particles();
    real e2 = 0, across = 0;
    std::size_t n = 0;
    for (std::size_t i = P.n_boundary; i < P.size(); ++i) {
      const real u = analytic::couette_startup(P.x[i].y, solver.time(), L, V0, nu);
      e2 += (P.v[i].x - u) * (P.v[i].x - u);
      across = std::fmax(across, std::hypot(P.v[i].y, P.v[i].z));
      ++n;
    }
    const real err = std::sqrt(e2 / n) / V0;
    std::printf("3D Couette at t = %g s: rms error %.3g of V0, largest speed across %.3g of V0\n",
                solver.time(), err, across / V0);
    EXPECT_LT(err, 0.01) << "t = " << t_check;
    EXPECT_LT(across, 1e-6 * V0) << "t = " << t_check;
  }
}

TEST(FluidSolver, FluidRoundAFixedSphereStaysAtRestUnderGravityIn3D) {
  // A fixed sphere (radius 3 d0, its surface by P.20 from the momentum equation) in the middle of
  // a closed box of fluid under gravity kept in the fluid: the fluid stays at rest and
  // hydrostatic round it. (With the sphere 1.8 d0 above the floor, the film between them moved
  // at 5e-3 sqrt(g H) after 120 steps.)
  const real L = 0.01, d0 = L / 12, g = 9.81;
  BoxSpec3 spec;
  spec.lo = {0, 0, 0};
  spec.hi = {L, L, L};
  spec.d0 = d0;
  spec.rho0 = 1000;
  spec.solids.push_back(FixedSolid3{Shape3::sphere(3 * d0), {0.5 * L, 0.45 * L, 0.5 * L}, Quat{}});
  const AtRest r = run_at_rest(spec, g, 5, 0.0025, 6);  // group 6: the first solid's surface
  const real p_bottom = spec.rho0 * g * L;
  std::printf(
      "3D box with a sphere: %lld steps, max |V| %.3g of sqrt(g H), max |P - P_h| %.3g (fluid) and %.3g "
      "(sphere) of rho0 g H\n",
      static_cast<long long>(r.steps), r.vmax / std::sqrt(g * L), r.fluid_err / p_bottom,
      r.surface_err / p_bottom);
  EXPECT_LT(r.vmax, 1e-3 * std::sqrt(g * L));
  EXPECT_LT(r.fluid_err, 1e-2 * p_bottom);
  EXPECT_LT(r.surface_err, 1e-2 * p_bottom);
}
