// The surface guard (boundary/surface_guard.hpp): fluid particles never cross a surface, a
// closing gap carries its particle, a gap below two particle spacings is an unresolved film,
// shifting never moves a particle into a close surface, an isolated particle is left out of a
// surface particle's Laplacian (P.20's viscous term), a film particle's Rhie-Chow bracket reads
// its fluid neighbours only; and the odd-even velocity damping (sweeps.hpp odd_even_velocity_at):
// zero on linear fields, dissipative on a checkerboard. The long hydrostatic box that the damping
// makes stable is in tests/fluid/test_flows.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdint>
#include <memory>
#include <vector>

#include "case_builders.hpp"
#include "particula/boundary/surface_guard.hpp"
#include "particula/scene/scene.hpp"
#include "particula/solver/solver.hpp"
#include "particula/solver/sweeps.hpp"

using namespace particula;

namespace {

const Domain kOpen{{-1, -1}, {1, 1}, false, false};

NearSurfaces one_surface(Vec2 x, Vec2 n, Vec2 v = {}) {
  NearSurfaces ns;
  ns.s[ns.count++] = SurfaceTangent{x, n, v};
  return ns;
}

}  // namespace

TEST(SurfaceGuard, NearestSlotsKeepTwoDifferentGroups) {
  NearestSurfaces s;
  offer_surface(s, 7, 2, 0.04);  // group 2 at distance 0.2
  offer_surface(s, 8, 2, 0.01);  // group 2, nearer: slot a, slot b stays empty
  EXPECT_EQ(s.a, 8u);
  EXPECT_EQ(s.b, kNoSurface);
  offer_surface(s, 3, 5, 0.09);  // another group, farther: slot b
  EXPECT_EQ(s.b, 3u);
  offer_surface(s, 4, 5, 0.0025);  // group 5 becomes the nearest: group 2's best moves to b
  EXPECT_EQ(s.a, 4u);
  EXPECT_EQ(s.b, 8u);
  offer_surface(s, 9, 5, 0.001);  // same group as a: replaces a, b untouched
  EXPECT_EQ(s.a, 9u);
  EXPECT_EQ(s.b, 8u);
}

TEST(SurfaceGuard, ParticleBehindASurfaceIsPutBackAndStopsMovingIn) {
  const real keep = 0.25;
  // Floor at y = 0 moving right at 1; the particle has crossed it and moves down and right.
  const NearSurfaces ns = one_surface({0, 0}, {0, 1}, {1, 0});
  Vec2 x{0.3, -0.1}, v{2, -3};
  EXPECT_EQ(guard_surfaces(ns, keep, kOpen, x, v), GuardOutcome::Pushed);
  EXPECT_NEAR(x.y, keep, 1e-15);
  EXPECT_NEAR(x.x, 0.3, 1e-15);
  EXPECT_NEAR(v.y, 0, 1e-15);  // no relative velocity into the surface
  EXPECT_NEAR(v.x, 2, 1e-15);  // tangential velocity untouched
  // Moving away from the surface: the position is corrected, the velocity kept.
  x = {0, 0.1};
  v = {0, 0.5};
  EXPECT_EQ(guard_surfaces(ns, keep, kOpen, x, v), GuardOutcome::Pushed);
  EXPECT_NEAR(v.y, 0.5, 1e-15);
  // Farther than the keep-out distance: nothing.
  x = {0, 0.26};
  v = {0, -1};
  EXPECT_EQ(guard_surfaces(ns, keep, kOpen, x, v), GuardOutcome::None);
  EXPECT_EQ(v.y, -1);
}

TEST(SurfaceGuard, ClosingGapCarriesItsParticle) {
  const real keep = 0.25;
  // Two plates 0.3 apart (narrower than 2 keep) closing at 1 each.
  NearSurfaces ns = one_surface({0, 0}, {0, 1}, {0, 1});
  ns.s[ns.count++] = SurfaceTangent{{0.1, 0.3}, {0, -1}, {0, -1}};
  Vec2 x{0.05, 0.05}, v{0.7, -4};
  EXPECT_EQ(guard_surfaces(ns, keep, kOpen, x, v), GuardOutcome::Gap);
  EXPECT_NEAR(x.y, 0.15, 1e-15);  // midway
  EXPECT_NEAR(v.y, 0, 1e-15);     // the mean of the two plates' normal velocities
  EXPECT_NEAR(v.x, 0.7, 1e-15);   // free to be squeezed out along the gap
  // A corner (perpendicular walls) is not a gap: both are enforced.
  NearSurfaces corner = one_surface({0, 0}, {0, 1});
  corner.s[corner.count++] = SurfaceTangent{{0, 0}, {1, 0}, {}};
  x = {0.1, -0.05};
  v = {-1, -1};
  EXPECT_EQ(guard_surfaces(corner, keep, kOpen, x, v), GuardOutcome::Pushed);
  EXPECT_NEAR(x.x, keep, 1e-15);
  EXPECT_NEAR(x.y, keep, 1e-15);
  EXPECT_NEAR(norm(v), 0, 1e-15);
}

TEST(SurfaceGuard, UnresolvedFilmFractionGrowsAsTheGapCloses) {
  // A floor at y = 0 and a body surface above at y = gap facing it; the particle midway.
  const real d0 = 1, film_gap = 2 * d0;
  const auto film = [&](real gap, Vec2 upper_normal) {
    NearSurfaces ns = one_surface({0, 0}, {0, 1});
    ns.s[ns.count++] = SurfaceTangent{{0.1, gap}, upper_normal, {}};
    return film_fraction(ns, film_gap, kOpen, {0.05, 0.5 * gap});
  };
  EXPECT_EQ(film(3.0, {0, -1}), 0);  // resolved: two particle layers and more
  EXPECT_EQ(film(2.0, {0, -1}), 0);
  EXPECT_NEAR(film(1.5, {0, -1}), 0.5, 1e-12);
  EXPECT_EQ(film(1.0, {0, -1}), 1);  // one layer or less: a film
  EXPECT_EQ(film(0.3, {0, -1}), 1);
  // The particle's position across the gap does not matter, only the gap width.
  NearSurfaces ns = one_surface({0, 0}, {0, 1});
  ns.s[ns.count++] = SurfaceTangent{{0, 1.5}, {0, -1}, {}};
  EXPECT_NEAR(film_fraction(ns, film_gap, kOpen, {0, 0.3}), 0.5, 1e-12);
  // Not a gap: a corner (normals at 90 degrees), one surface, or the rule turned off.
  EXPECT_EQ(film(1.0, {-1, 0}), 0);
  EXPECT_EQ(film_fraction(one_surface({0, 0}, {0, 1}), film_gap, kOpen, {0, 0.2}), 0);
  ns = one_surface({0, 0}, {0, 1});
  ns.s[ns.count++] = SurfaceTangent{{0, 0.5}, {0, -1}, {}};
  EXPECT_EQ(film_fraction(ns, 0, kOpen, {0, 0.25}), 0);
}

TEST(SurfaceGuard, ShiftingNeverMovesIntoACloseSurface) {
  const NearSurfaces ns = one_surface({0, 0}, {0, 1});
  const Vec2 dr{0.01, -0.02};
  const Vec2 near = limit_shift_at_surfaces(dr, ns, 1.0, kOpen, {0, 0.5});
  EXPECT_EQ(near.x, 0.01);
  EXPECT_EQ(near.y, 0);
  const Vec2 far = limit_shift_at_surfaces(dr, ns, 1.0, kOpen, {0, 1.5});
  EXPECT_EQ(far.y, -0.02);
  const Vec2 away = limit_shift_at_surfaces(Vec2{0, 0.02}, ns, 1.0, kOpen, {0, 0.5});
  EXPECT_EQ(away.y, 0.02);
}

namespace {

struct Box {
  Scene scene;
  std::unique_ptr<Solver> solver;
};

/// A 1 x 0.8 box at d0 = 0.04 with a 20 % random perturbation of the fluid lattice.
Box make_box() {
  Case c = cases::closed_box(1.0, 0.8, 0.04);
  c.perturbation = 0.2;
  c.seed = 11;
  Box b{build_scene(c), nullptr};
  b.solver = std::make_unique<Solver>(b.scene.params, b.scene.domain, b.scene.particles, b.scene.groups);
  return b;
}

bool interior(const Solver& s, std::size_t i) {
  const Vec2 x = s.particles().x[i];
  const Domain& d = s.domain();
  const real dist = std::min({x.x - d.lo.x, d.hi.x - x.x, x.y - d.lo.y, d.hi.y - x.y});
  return s.particles().is_fluid(i) && dist > 2 * s.params().h;
}

}  // namespace

TEST(OddEvenDamping, ExactOnLinearAndSmallOnQuadraticFields) {
  auto b = make_box();
  Solver& s = *b.solver;
  const auto& P = s.particles();
  const SweepContext c = s.host().sweep_context();
  // Linear field: both Laplacians are exactly zero (renormalized gradient exact for linear fields).
  // Quadratic field: the compact Laplacian is exact, the wide one (gradient applied twice) has
  // the gradient's truncation error, a few per cent of the Laplacian on this 20 % perturbed lattice.
  for (const real q : {0.0, 1.0}) {
    std::vector<Vec2> v(P.size());
    for (std::size_t i = 0; i < P.size(); ++i) {
      const Vec2 x = P.x[i];
      v[i] = {0.3 + 1.2 * x.x - 0.7 * x.y + q * (0.9 * x.x * x.x - 0.4 * x.x * x.y + 0.6 * x.y * x.y),
              -0.2 + 0.5 * x.x + 0.8 * x.y + q * (-0.3 * x.x * x.x + 1.1 * x.x * x.y - 0.5 * x.y * x.y)};
    }
    s.host().compute_velocity_derivatives(v);
    const Vec2 lap_exact{q * (2 * 0.9 + 2 * 0.6), q * (-2 * 0.3 - 2 * 0.5)};
    real worst = 0;
    int n = 0;
    for (std::size_t i = 0; i < P.size(); ++i) {
      if (!interior(s, i)) continue;
      worst = std::max(worst, norm(odd_even_velocity_at(c, i, s.host().grad_v().data(), s.host().lap_v()[i])));
      ++n;
    }
    ASSERT_GT(n, 50);
    std::printf("odd-even term on a %s field: worst %.3g (|lap V| = %.3g)\n", q == 0 ? "linear" : "quadratic", worst,
                norm(lap_exact));
    if (q == 0) EXPECT_LT(worst, 1e-9);
    else EXPECT_LT(worst, 0.1 * norm(lap_exact));
  }
}

TEST(OddEvenDamping, DampsACheckerboardMode) {
  auto b = make_box();
  Solver& s = *b.solver;
  const auto& P = s.particles();
  const real d0 = s.params().d0;
  // Columns moving alternately up and down (the mode seen growing under a top wall).
  std::vector<Vec2> v(P.size());
  for (std::size_t i = P.n_boundary; i < P.size(); ++i) {
    const long col = std::lround(P.x[i].x / d0);
    v[i] = {0, col % 2 == 0 ? 1.0 : -1.0};
  }
  s.host().compute_velocity_derivatives(v);
  const SweepContext c = s.host().sweep_context();
  real power = 0, scale = 0;
  for (std::size_t i = 0; i < P.size(); ++i) {
    if (!interior(s, i)) continue;
    const Vec2 d = odd_even_velocity_at(c, i, s.host().grad_v().data(), s.host().lap_v()[i]);
    power += dot(d, v[i]);
    scale += norm2(v[i]);
  }
  // d . v < 0: the term removes kinetic energy from the mode, at a rate of order 1/d0^2.
  EXPECT_LT(power / scale, -1.0 / (d0 * d0));
}

namespace {

/// Surface particle 0 and fluid particles 1 and 2, every pair neighbours (CSR: 0 -> {1, 2};
/// 1 -> {0, 2}; 2 -> {0, 1}), with the pair weights given.
struct ThreeParticles {
  std::vector<Vec2> x;
  std::vector<Vec2> grad_w;
  std::vector<real> lap_w;
  std::vector<Kind> kind{Kind::Boundary, Kind::Fluid, Kind::Fluid};
  std::vector<std::int32_t> group{0, -1, -1};
  std::vector<std::uint32_t> start{0, 2, 4, 6}, j{1, 2, 0, 2, 0, 1};

  SweepContext context() const {
    SweepContext c;
    c.domain = kOpen;
    c.start = start.data();
    c.j = j.data();
    c.n = 3;
    c.nb = 1;
    c.x = x.data();
    c.kind = kind.data();
    c.group = group.data();
    c.grad_w = grad_w.data();
    c.lap_w = lap_w.data();
    return c;
  }
};

}  // namespace

// A surface particle's viscous Laplacian, P.20's nu <lap V> term, leaves out isolated fluid
// particles, as P.20's pressure sums do; a fluid particle's own Laplacian keeps them. One surface
// particle (0) with an isolated fluid neighbour (1) moving into it and a resolved one (2) at rest;
// the pair weights are set by hand, so the sums can be read off.
TEST(IsolatedParticles, LeftOutOfASurfaceParticlesLaplacianOnly) {
  const ThreeParticles three{{{0, 0}, {0, 0.4}, {0.5, 1}}, std::vector<Vec2>(6, Vec2{}), {3, 5, 3, 7, 5, 7}};
  const std::vector<Vec2> v{{0, 0}, {0, -1}, {0, 0}};
  const std::vector<std::uint8_t> isolated{0, 1, 0};
  SweepContext c = three.context();
  Mat2 L;
  Vec2 lap;
  velocity_derivatives_at(c, 0, v.data(), L, lap);  // no flags: the isolated particle counts
  EXPECT_DOUBLE_EQ(lap.y, 3.0);  // sum lap_w (V_i - V_j) = 3 (0 - (-1))
  c.isolated = isolated.data();
  velocity_derivatives_at(c, 0, v.data(), L, lap);
  EXPECT_DOUBLE_EQ(lap.y, 0.0);  // particle 1 left out, particle 2 at rest
  velocity_derivatives_at(c, 2, v.data(), L, lap);
  EXPECT_DOUBLE_EQ(lap.y, 7.0);  // a fluid particle keeps it: 7 (V_2 - V_1) = 7 (0 - (-1))
}

TEST(UnresolvedFilms, AFilmParticleRelaxesToItsFluidNeighboursNotToTheSurfaces) {
  // surface particle 0 and fluid particle 2 around fluid particle 1, which sits in a film
  ThreeParticles three{{{0, 0}, {0, 0.4}, {1, 0.4}},
                       {{0, 1}, {1, 1}, {0, -1}, {1, 0}, {-1, -1}, {-1, 0}},
                       {-3, -5, -3, -7, -5, -7}};
  const std::vector<real> vol{1, 1, 1}, rho{1000, 1000, 1000};
  const std::vector<Vec2> G{{0, 2}, {0, 0}, {1, 0}}, lap_v(3, Vec2{}), v_start(3, Vec2{});
  const std::vector<Mat2> grad_v(3, Mat2{});
  SweepContext c = three.context();
  c.vol = vol.data();
  c.kernel = WendlandC2(2.0);
  StageParams s;
  s.dt = s.g_dt = 0.01;
  s.rho0 = 1000;
  s.c = 10;  // tau = h / c = 0.2 s
  const auto bracket = [&](real p_surface) {
    const std::vector<real> p{p_surface, 0, 10};
    std::vector<real> rc(3, 0);
    std::vector<Vec2> v(3);
    rhie_chow_and_momentum_at(c, 1, p.data(), rho.data(), G.data(), grad_v.data(), lap_v.data(),
                              v_start.data(), s, rc.data(), v.data(), nullptr);
    return rc[1];
  };
  // no film: the paper's bracket, surface included:
  // div_g = (0,-1).(G0 - G1) + (1,0).(G2 - G1) = -2 + 1; lap_p = (-3 (0 - P0) - 7 (0 - 10)) / 1000
  const real paper = -1 - (-3 * 80 + 70) / 1000.0;
  EXPECT_NEAR(bracket(-80), paper, 1e-12);
  // a film particle (fraction 1) relaxes to its fluid neighbour's pressure, 10 Pa, i.e. to
  // rho = 1000.1, over tau: -rho G dt bracket = 0.1 / 0.2; the surface's P drops out
  std::vector<real> film{0, 1, 0};
  c.film = film.data();
  EXPECT_NEAR(bracket(-80), -0.1 / 0.2 / (1000 * 0.01), 1e-12);
  EXPECT_DOUBLE_EQ(bracket(-80), bracket(+500));
  EXPECT_NEAR(continuity_rate(1000, 0, s.g_dt, bracket(-80)), 0.1 / 0.2, 1e-12);
  film[1] = 0.5;  // half way: half of each
  EXPECT_NEAR(bracket(-80), 0.5 * paper + 0.5 * (-0.05), 1e-12);
  // no faster than one step: with tau below dt the particle lands on the target in one step
  s.c = 1000;
  film[1] = 1;
  EXPECT_NEAR(continuity_rate(1000, 0, s.g_dt, bracket(-80)) * s.dt, (1000 + 10 / 1e6) - 1000, 1e-12);
}
