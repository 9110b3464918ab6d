// The exact solutions reproduce the table of reference/README.md.
#include <gtest/gtest.h>

#include "particula/analytic/solutions.hpp"

using namespace particula;

TEST(Analytic, MatchesReferenceTable) {
  const real L = 1e-3, nu = 1e-6, F = 1e-4, V0 = 1.25e-5;
  struct Row { real t, pm, pq, cq, cm, c3q; };
  const Row rows[] = {{0.0225, 2.233e-6, 2.024e-6, 5.09e-9, 2.303e-7, 2.982e-6},
                      {0.045, 4.235e-6, 3.518e-6, 1.549e-7, 1.195e-6, 5.058e-6},
                      {0.1125, 8.250e-6, 6.370e-6, 1.318e-6, 3.628e-6, 7.474e-6},
                      {0.225, 1.110e-5, 8.385e-6, 2.515e-6, 5.386e-6, 8.764e-6},
                      {1e3, 1.250e-5, 9.375e-6, 3.125e-6, 6.250e-6, 9.375e-6}};
  for (const auto& r : rows) {
    EXPECT_NEAR(analytic::poiseuille_startup(L / 2, r.t, L, F, nu), r.pm, 2e-3 * r.pm) << r.t;
    EXPECT_NEAR(analytic::poiseuille_startup(L / 4, r.t, L, F, nu), r.pq, 2e-3 * r.pq) << r.t;
    EXPECT_NEAR(analytic::couette_startup(L / 4, r.t, L, V0, nu), r.cq, 1e-2 * r.cq + 1e-10) << r.t;
    EXPECT_NEAR(analytic::couette_startup(L / 2, r.t, L, V0, nu), r.cm, 2e-3 * r.cm) << r.t;
    EXPECT_NEAR(analytic::couette_startup(3 * L / 4, r.t, L, V0, nu), r.c3q, 2e-3 * r.c3q) << r.t;
  }
  EXPECT_NEAR(analytic::taylor_green_decay(0.5, 100), 0.6738, 1e-4);
  EXPECT_NEAR(analytic::taylor_green_decay(2.0, 100), 0.2062, 1e-4);
}

TEST(Analytic, DuctStartUpReachesTheSquareDuctsSteadyFlowAndThePlatesInAWideDuct) {
  const real F = 1e-4, nu = 1e-6, L = 1e-3;
  // the steady centre speed of a square duct of side L: 0.0736713 F L^2 / nu (the classical
  // series, e.g. White, Viscous Fluid Flow, eq. 3-48 with a = b = L / 2)
  EXPECT_NEAR(analytic::duct_startup(0.5 * L, 0.5 * L, 100, L, L, F, nu) / (F * L * L / nu), 0.0736713, 2e-7);
  // symmetric in y and z, zero on the walls, at rest at t = 0
  EXPECT_NEAR(analytic::duct_startup(0.2 * L, 0.7 * L, 0.05, L, L, F, nu), analytic::duct_startup(0.7 * L, 0.2 * L, 0.05, L, L, F, nu),
              1e-18);
  EXPECT_NEAR(analytic::duct_startup(0.2 * L, 0.7 * L, 0.05, L, L, F, nu), analytic::duct_startup(0.8 * L, 0.3 * L, 0.05, L, L, F, nu),
              1e-18);
  EXPECT_NEAR(analytic::duct_startup(0.3 * L, 0, 0.05, L, L, F, nu), 0, 1e-15);
  EXPECT_EQ(analytic::duct_startup(0.3 * L, 0.4 * L, 0, L, L, F, nu), 0);
  // a duct 40 times wider than high is the plates' start-up flow at its middle
  for (const real t : {0.01, 0.1, 1.0})
    for (const real y : {0.1 * L, 0.5 * L, 0.8 * L})
      EXPECT_NEAR(analytic::duct_startup(y, 20 * L, t, L, 40 * L, F, nu), analytic::poiseuille_startup(y, t, L, F, nu), 1e-10 * F * L * L / nu)
          << t << " " << y;
}
