// No success with broken numbers: every output row is checked before it is
// written; a non-finite value writes nothing of that stream and is returned as a Failure, which
// the run loop turns into exit code 3 (src/run/runner.cpp).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include "../../src/run/outputs.hpp"
#include "case_builders.hpp"
#include "particula/io/csv.hpp"
#include "particula/run/observers.hpp"
#include "particula/scene/scene.hpp"
#include "scratch_dir.hpp"

using namespace particula;
namespace fs = std::filesystem;

namespace {

constexpr real kNaN = std::numeric_limits<real>::quiet_NaN();

fs::path fresh_dir(const std::string& name) { return test_scratch::scratch_dir(name); }

/// A closed 0.02 m box at d0 = 1e-3 m with a probe up its middle.
Case probed_box() {
  Case c = cases::closed_box(0.02, 0.02, 1e-3);
  c.output_interval = 0.1;
  c.snapshots = false;
  c.probes = {{"mid", {0.01, 0}, {0.01, 0.02}, 11, 0.1, ProbeKind::Line, {}}};
  return c;
}

/// The scene of `c` after `edit`, as a restarted solver (the state taken exactly as it is).
template <class Edit>
Solver solver_with(const Case& c, Edit edit) {
  Scene s = build_scene(c);
  edit(s.particles, s.groups);
  return Solver(s.params, s.domain, std::move(s.particles), std::move(s.groups), SolverStart::Restart, 0.1,
                10);
}

/// Index of the fluid particle nearest to x.
std::size_t nearest_fluid(const Particles& P, Vec2 x) {
  std::size_t best = P.n_boundary;
  for (std::size_t i = P.n_boundary; i < P.size(); ++i)
    if (norm(P.x[i] - x) < norm(P.x[best] - x)) best = i;
  return best;
}

}  // namespace

TEST(RunOutputs, FiniteStateIsWritten) {
  const fs::path dir = fresh_dir("outputs_finite");
  const Case c = probed_box();
  const Solver s = solver_with(c, [](Particles&, std::vector<RigidGroup>&) {});
  {
    run_detail::RunOutputs out(dir, c);
    EXPECT_FALSE(out.write(s, true).has_value());
  }
  EXPECT_EQ(io::read_csv(dir / "probe_mid.csv").size(), 11u);
  EXPECT_EQ(io::read_csv(dir / "walls.csv").size(), 4u);
  fs::remove_all(dir);
}

TEST(RunOutputs, NonFiniteProbeValueIsAFailureAndNotWritten) {
  const fs::path dir = fresh_dir("outputs_probe_nan");
  const Case c = probed_box();
  const Solver s = solver_with(c, [](Particles& P, std::vector<RigidGroup>&) {
    P.p[nearest_fluid(P, {0.01, 0.01})] = kNaN;  // points 4 to 6 (y = 0.008 to 0.012) see it
  });
  {
    run_detail::RunOutputs out(dir, c);
    const auto f = out.write(s, true);
    ASSERT_TRUE(f.has_value());
    EXPECT_NE(f->what.find("non-finite value (NaN or Inf) in probe 'mid' (point 4): p = nan"),
              std::string::npos)
        << f->what;
    EXPECT_NEAR(f->position.x, 0.01, 1e-12);
  }
  EXPECT_EQ(io::read_csv(dir / "probe_mid.csv").size(), 0u) << "no row of a broken output";
  EXPECT_EQ(io::read_csv(dir / "walls.csv").size(), 4u) << "the other streams are written";
  fs::remove_all(dir);
}

TEST(RunOutputs, NonFiniteWallForceIsAFailureAndNotWritten) {
  const fs::path dir = fresh_dir("outputs_wall_inf");
  const Case c = probed_box();
  const Solver s = solver_with(c, [](Particles&, std::vector<RigidGroup>& g) {
    g[1].force_viscous.y = std::numeric_limits<real>::infinity();
  });
  BodyHistoryWriter w(dir);
  const auto f = w.write(s);
  ASSERT_TRUE(f.has_value());
  EXPECT_NE(f->what.find("in walls.csv of wall 'right': fy = inf"), std::string::npos) << f->what;
  EXPECT_EQ(io::read_csv(dir / "walls.csv").size(), 0u);
  EXPECT_EQ(io::read_csv(dir / "bodies.csv").size(), 0u);
  fs::remove_all(dir);
}

TEST(RunOutputs, NonFiniteBodyStateIsAFailure) {
  const fs::path dir = fresh_dir("outputs_body_nan");
  Case c = probed_box();
  BodySpec disc;
  disc.name = "disc";
  disc.center = {0.01, 0.012};
  disc.radius = 0.005;
  disc.density = 1200;
  c.bodies = {disc};
  const Solver s = solver_with(c, [](Particles&, std::vector<RigidGroup>& g) { g.back().omega = kNaN; });
  BodyHistoryWriter w(dir);
  const auto f = w.write(s);
  ASSERT_TRUE(f.has_value());
  EXPECT_NE(f->what.find("in bodies.csv of body 'disc': omega = nan"), std::string::npos) << f->what;
  EXPECT_EQ(io::read_csv(dir / "bodies.csv").size(), 0u);
  fs::remove_all(dir);
}

TEST(RunOutputs, NonFiniteGroupStateEndsTheStep) {
  // A NaN in a wall's or a body's state ends the run at the step where it appears: the health
  // check at the end of Solver::step covers the rigid groups (motion and loads, what bodies.csv and
  // walls.csv hold) as well as the particles, whichever shows it first.
  const Case c = probed_box();
  for (const auto& edit : {+[](std::vector<RigidGroup>& g) { g[2].vel.x = kNaN; },
                           +[](std::vector<RigidGroup>& g) { g[0].angle = kNaN; }}) {
    Solver s = solver_with(c, [&](Particles&, std::vector<RigidGroup>& g) { edit(g); });
    const auto f = s.step();
    ASSERT_TRUE(f.has_value());
    EXPECT_NE(f->what.find("non-finite value (NaN or Inf)"), std::string::npos) << f->what;
  }
  Solver ok = solver_with(c, [](Particles&, std::vector<RigidGroup>&) {});
  EXPECT_FALSE(ok.step().has_value());
}

// ---- derived quantities -----------------------------------------------------------------------

TEST(DerivedOutputs, FlowRateIsTheIntegralOfTheNormalVelocity) {
  // uniform u = (2, 0) through a vertical line 0.5 m long, walked upwards: n = +x, Q = 1 m^2/s
  EXPECT_DOUBLE_EQ(flow_rate_of({0, 0}, {0, 0.5}, std::vector<Vec2>(7, Vec2{2, 0})), 1.0);
  EXPECT_DOUBLE_EQ(flow_rate_of({0, 0.5}, {0, 0}, std::vector<Vec2>(7, Vec2{2, 0})), -1.0);  // walked down
  EXPECT_DOUBLE_EQ(flow_rate_of({0, 0}, {0, 0.5}, std::vector<Vec2>(7, Vec2{0, 3})), 0.0);   // along the line
  // a parabola u = 6 y (1 - y) across [0, 1] carries 1 m^2/s (trapezoidal error 1/(N-1)^2)
  std::vector<Vec2> v;
  for (int k = 0; k <= 100; ++k) v.push_back({6 * (k / 100.0) * (1 - k / 100.0), 0});
  EXPECT_NEAR(flow_rate_of({0.3, 0}, {0.3, 1}, v), 1.0, 2e-4);
}

TEST(DerivedOutputs, CoefficientsFollowTheirDefinitions) {
  // U = (0, 2) m/s upwards, L = 0.5 m, rho0 = 1000, nu = 1e-3: q = 0.5 rho0 U^2 L = 1000 N/m
  const BodyReference ref{{0, 2}, 0.5};
  const Coefficients k = body_coefficients(ref, {3, 4}, 50, {0, -0.5}, 1000, 1e-3);
  EXPECT_DOUBLE_EQ(k.re, 1000.0);      // U L / nu
  EXPECT_DOUBLE_EQ(k.re_body, 250.0);  // |v| L / nu
  EXPECT_DOUBLE_EQ(k.cd, 4e-3);        // the force along U
  EXPECT_DOUBLE_EQ(k.cl, -3e-3);       // the force along U turned 90 degrees counter-clockwise: -x
  EXPECT_DOUBLE_EQ(k.cm, 0.1);         // T / (q L)
}

TEST(DerivedOutputs, RunWritesCoefficientsFlowAndPointProbes) {
  const fs::path dir = fresh_dir("outputs_derived");
  Case c = probed_box();
  c.bodies.push_back({});
  BodySpec& b = c.bodies.back();
  b.name = "disc";
  b.center = {0.01, 0.012};
  b.radius = 0.005;
  b.motion = BodyMotion::Fixed;
  b.reference_velocity = {0.01, 0};
  b.reference_length = 0.01;
  ProbeSpec spot_probe;
  spot_probe.name = "spots";
  spot_probe.kind = ProbeKind::Points;
  spot_probe.interval = 0.1;
  spot_probe.at = {Vec2{0.003, 0.003}, Vec2{0.003, 0.0}};
  c.probes.push_back(spot_probe);
  // a linear shear u = y / s (the particles around the points: the bottom wall, at rest, and fluid)
  const Solver s = solver_with(c, [](Particles& P, std::vector<RigidGroup>&) {
    for (std::size_t i = P.n_boundary; i < P.size(); ++i) P.v[i] = {P.x[i].y, 0};
  });
  {
    run_detail::RunOutputs out(dir, c);
    EXPECT_FALSE(out.write(s, true).has_value());
  }
  const io::CsvTable coef = io::read_csv(dir / "coefficients.csv");
  EXPECT_EQ(coef.header, (std::vector<std::string>{"time", "body", "re", "re_body", "cd", "cl", "cm"}));
  ASSERT_EQ(coef.size(), 1u);
  EXPECT_DOUBLE_EQ(coef.column("re").at(0), 0.01 * 0.01 / 1e-6);
  const io::CsvTable flow = io::read_csv(dir / "flow_mid.csv");
  // (the probe line x = 0.01 crosses the disc, whose surface particles are at rest: Q > 0 only)
  EXPECT_EQ(flow.header, (std::vector<std::string>{"time", "flow_rate"}));
  ASSERT_EQ(flow.size(), 1u);
  EXPECT_FALSE(fs::exists(dir / "flow_spots.csv"));  // points have no flow rate
  const io::CsvTable spots = io::read_csv(dir / "probe_spots.csv");
  ASSERT_EQ(spots.size(), 2u);
  EXPECT_NEAR(spots.column("vx").at(0), 0.003, 1e-9);  // inside: the (linear) field
  EXPECT_NEAR(spots.column("vx").at(1), 0.0, 1e-9);    // on the wall: the wall's velocity
  fs::remove_all(dir);
}
