// Consistency of the renormalized operators on a randomly perturbed lattice with walls
// (docs/method.md sections 3, 4 and 6): exact gradients of linear fields, exact Fatehi-Manzari
// Laplacians of quadratic fields, P.18 normals, and the Morris baseline's wall error.
#include <gtest/gtest.h>

#include <cmath>

#include "case_builders.hpp"
#include "particula/scene/scene.hpp"
#include "particula/solver/solver.hpp"
#include "particula/sph/operators.hpp"

using namespace particula;

namespace {

struct Setup {
  Scene scene;
  std::unique_ptr<Solver> solver;
};

/// A 1 x 0.8 box at d0 = 0.04 with a 20 % random perturbation of the fluid lattice.
Setup make_box(bool fatehi_manzari = true, real perturbation = 0.2,
               GradientScheme gradient = GradientScheme::Consistent) {
  Case c = cases::closed_box(1.0, 0.8, 0.04);
  c.perturbation = perturbation;
  c.gradient = gradient;
  c.seed = 7;
  c.laplacian = fatehi_manzari ? LaplacianScheme::FatehiManzari : LaplacianScheme::Morris;
  Setup s{build_scene(c), nullptr};
  s.solver = std::make_unique<Solver>(s.scene.params, s.scene.domain, s.scene.particles, s.scene.groups);
  return s;
}

enum class Where { Interior, NearWall, Wall };

/// Classifies particle i: boundary, fluid within h of the box edge, or interior (farther
/// than h from every edge).
Where where(const Solver& s, std::size_t i) {
  if (!s.particles().is_fluid(i)) return Where::Wall;
  const Vec2 x = s.particles().x[i];
  const Domain& d = s.domain();
  const real dist = std::min({x.x - d.lo.x, d.hi.x - x.x, x.y - d.lo.y, d.hi.y - x.y});
  return dist > s.params().h ? Where::Interior : Where::NearWall;
}

/// Is boundary particle i a corner particle (within 2 h of two walls)?
bool near_corner(const Solver& s, std::size_t i) {
  const Vec2 x = s.particles().x[i];
  const Domain& d = s.domain();
  const real h = 2 * s.params().h;
  const bool nx = x.x - d.lo.x < h || d.hi.x - x.x < h;
  const bool ny = x.y - d.lo.y < h || d.hi.y - x.y < h;
  return nx && ny;
}

}  // namespace

class GradientSchemes : public ::testing::TestWithParam<GradientScheme> {};
INSTANTIATE_TEST_SUITE_P(Operators, GradientSchemes,
                         ::testing::Values(GradientScheme::Consistent, GradientScheme::Paper));

TEST_P(GradientSchemes, GradientOfLinearFieldIsExact) {
  auto s = make_box(true, 0.2, GetParam());
  Solver& sv = *s.solver;
  // A random linear vector field V = A x + b, and a linear pressure.
  const Mat2 A{0.37, -1.21, 0.83, 0.52};
  const Vec2 b{0.3, -0.7};
  const Vec2 gp{2.5, -1.75};
  const auto& P = sv.particles();
  std::vector<Vec2> v(P.size());
  std::vector<real> p(P.size()), rho(P.size(), 1.0);
  for (std::size_t i = 0; i < P.size(); ++i) {
    v[i] = A * P.x[i] + b;
    p[i] = dot(gp, P.x[i]) + 4.0;
  }
  sv.host().compute_velocity_derivatives(v);
  sv.host().compute_pressure_gradient(p, rho);
  // grad V has L_ab = d_a V_b = A_ba.
  const Mat2 L = transpose(A);
  int counted[3] = {0, 0, 0};
  for (std::size_t i = 0; i < P.size(); ++i) {
    const Where w = where(sv, i);
    const Mat2 e = sv.host().grad_v()[i] - L;
    const real err = std::sqrt(ddot(e, e)) / std::sqrt(ddot(L, L));
    const real errp = norm(sv.host().grad_p_over_rho()[i] - gp) / norm(gp);
    EXPECT_LT(err, 1e-10) << "particle " << i << " kind " << static_cast<int>(w);
    EXPECT_LT(errp, 1e-10) << "particle " << i;
    ++counted[static_cast<int>(w)];
  }
  EXPECT_GT(counted[0], 100);
  EXPECT_GT(counted[1], 50);
  EXPECT_GT(counted[2], 50);
  EXPECT_EQ(sv.counters().singular_B, 0);
  // The bound of sparse supports leaves full and half (wall) supports alone.
  EXPECT_EQ(sv.counters().sparse_support, 0);
}

// A particle's own pressure must not enter its own gradient: with the paper's weights (P.7) it
// enters as -P_i B sum_j w_j gradW_ij, which on an irregular distribution or beside a
// single-layer wall is of order P_i / h and, paired with the same term of the divergence, makes
// a mode that grows at the rate c |B sum_j w_j gradW_ij| (docs/method.md, "The self-coupled
// mode: zeroth-order gradient correction"). A unit pressure on particles more than h apart, zero
// elsewhere: each one's gradient is its own term only.
TEST(Operators, ConsistentGradientLeavesOutAParticlesOwnPressure) {
  real largest[2] = {0, 0};
  int scheme = 0;
  for (GradientScheme g : {GradientScheme::Consistent, GradientScheme::Paper}) {
    auto s = make_box(true, 0.2, g);
    Solver& sv = *s.solver;
    const auto& P = sv.particles();
    const real h = sv.params().h;
    std::vector<real> p(P.size(), 0.0), rho(P.size(), 1.0);
    std::vector<std::size_t> picked;
    for (std::size_t i = P.n_boundary; i < P.size(); ++i) {
      bool apart = true;
      for (std::size_t k : picked) apart = apart && norm(P.x[i] - P.x[k]) > 1.01 * h;
      if (apart) picked.push_back(i);
    }
    for (std::size_t i : picked) p[i] = 1.0;
    sv.host().compute_pressure_gradient(p, rho);
    int near_wall = 0;
    for (std::size_t i : picked) {
      largest[scheme] = std::max(largest[scheme], norm(sv.host().grad_p_over_rho()[i]) * h);
      near_wall += where(sv, i) == Where::NearWall ? 1 : 0;
    }
    EXPECT_GT(picked.size(), 40U);
    EXPECT_GT(near_wall, 15);
    ++scheme;
  }
  EXPECT_LT(largest[0], 1e-10);  // consistent: the weights of every particle sum to zero
  EXPECT_GT(largest[1], 0.3);    // paper: an own term of order P_i / h
}

TEST(Operators, FatehiManzariLaplacianOfQuadraticIsExact) {
  auto s = make_box(true);
  Solver& sv = *s.solver;
  const auto& P = sv.particles();
  // u = 1/2 x.H.x + g.x + c per component, with different H for each component.
  const Mat2 H1{1.3, 0.4, 0.4, -0.7}, H2{-2.1, 0.9, 0.9, 0.6};
  const Vec2 g1{0.2, -0.5}, g2{1.1, 0.3};
  std::vector<Vec2> v(P.size());
  for (std::size_t i = 0; i < P.size(); ++i) {
    const Vec2 x = P.x[i];
    v[i] = {0.5 * dot(x, H1 * x) + dot(g1, x) + 0.1, 0.5 * dot(x, H2 * x) + dot(g2, x) - 0.2};
  }
  sv.host().compute_velocity_derivatives(v);
  const Vec2 exact{trace(H1), trace(H2)};
  int interior = 0, near = 0;
  for (std::size_t i = 0; i < P.size(); ++i) {
    const Where w = where(sv, i);
    if (w == Where::Wall) continue;
    const real err = norm(sv.host().lap_v()[i] - exact) / norm(exact);
    EXPECT_LT(err, 1e-8) << "particle " << i << (w == Where::Interior ? " interior" : " near wall");
    (w == Where::Interior ? interior : near)++;
  }
  EXPECT_GT(interior, 100);
  EXPECT_GT(near, 50);
  // The counter counts fluid particles only (boundary particles take k I by design): none of
  // them may have a singular system here, next to the walls included.
  EXPECT_EQ(sv.counters().singular_Bhat, 0);
}

TEST(Operators, MorrisLaplacianIsNotExactNextToWalls) {
  auto s = make_box(false, 0.0);
  Solver& sv = *s.solver;
  const auto& P = sv.particles();
  const Mat2 H{1.3, 0.4, 0.4, -0.7};
  std::vector<Vec2> v(P.size());
  for (std::size_t i = 0; i < P.size(); ++i) v[i] = {0.5 * dot(P.x[i], H * P.x[i]), 0};
  sv.host().compute_velocity_derivatives(v);
  real worst_near = 0;
  for (std::size_t i = 0; i < P.size(); ++i)
    if (where(sv, i) == Where::NearWall)
      worst_near = std::max(worst_near, std::fabs(sv.host().lap_v()[i].x - trace(H)) / std::fabs(trace(H)));
  EXPECT_GT(worst_near, 0.01) << "the Morris form should show a wall error above 1 %";
}

namespace {
/// Angles (degrees) between P.18 and exact normals of the boundary particles away from corners.
std::vector<real> normal_errors(real perturbation) {
  auto s = make_box(true, perturbation);
  const Solver& sv = *s.solver;
  const auto& P = sv.particles();
  std::vector<real> out;
  for (std::size_t i = 0; i < P.n_boundary; ++i) {
    if (near_corner(sv, i)) continue;
    const Vec2 exact = P.normal_local[i];  // walls: body frame = world frame
    out.push_back(std::acos(std::min(1.0, dot(P.normal[i], exact))) * 180 / M_PI);
  }
  return out;
}
}  // namespace

TEST(Operators, KernelNormalsAlongStraightWalls) {
  // Regular fluid lattice: P.18 gives the exact normal along a straight wall.
  const auto regular = normal_errors(0.0);
  ASSERT_GT(regular.size(), 40u);
  for (real a : regular) EXPECT_LT(a, 1.0);
  // The paper's 5 % random perturbation: the nearest fluid particles dominate the sum, so
  // single normals wobble by a few degrees (measured: mean 1.3, max 3.4 degrees at seed 7).
  const auto perturbed = normal_errors(0.05);
  real mean = 0, worst = 0;
  for (real a : perturbed) {
    mean += a / perturbed.size();
    worst = std::max(worst, a);
  }
  EXPECT_LT(mean, 2.0);
  EXPECT_LT(worst, 5.0);
  std::printf("P.18 normal error, 5%% perturbation: mean %.3f deg, max %.3f deg\n", mean, worst);
}

TEST(Operators, BhatSolvesItsDefiningSystem) {
  // Random moments: Bhat : M = -I must hold to round-off for the symmetric pairs cd.
  LaplacianMoments m;
  const real r[] = {0.9, 1.3, 2.1, 1.7, 0.6, 2.4};
  const real ang[] = {0.1, 1.9, 2.7, 4.0, 5.1, 3.3};
  for (int k = 0; k < 6; ++k)
    laplacian_moments_pair(m, 0.8 + 0.1 * k, r[k], -0.3 * k - 0.2, {std::cos(ang[k]), std::sin(ang[k])});
  const Mat2 B{1.2, 0.1, 0.1, 0.9};
  Mat2 Bh;
  ASSERT_TRUE(laplacian_correction_tensor(m, B, Bh, BhatCheck::None));
  const real Bm[2][2] = {{B.xx, B.xy}, {B.yx, B.yy}}, Bhm[2][2] = {{Bh.xx, Bh.xy}, {Bh.yx, Bh.yy}};
  for (int c = 0; c < 2; ++c)
    for (int d = 0; d < 2; ++d) {
      real sum = 0;
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) {
          real M = sym4_at(m.T4, a, b, c, d);
          for (int e = 0; e < 2; ++e)
            for (int f = 0; f < 2; ++f) M += sym3_at(m.T3, a, b, e) * Bm[e][f] * sym3_at(m.Q3, f, c, d);
          sum += Bhm[a][b] * M;
        }
      EXPECT_NEAR(sum, c == d ? -1.0 : 0.0, 1e-12);
    }
}

TEST(Operators, UnsoundBhatFallsBackToNormalizedIdentity) {
  // Moments of a one-sided, nearly collinear support: the solve gives an indefinite tensor,
  // which a boundary particle must not use.
  LaplacianMoments m;
  for (int k = 0; k < 5; ++k)
    laplacian_moments_pair(m, 1.0, 1.0 + 0.2 * k, -1.0, {std::cos(0.05 * k), std::sin(0.05 * k)});
  Mat2 raw, guarded;
  laplacian_correction_tensor(m, identity2(), raw, BhatCheck::None);
  const bool ok = laplacian_correction_tensor(m, identity2(), guarded, BhatCheck::Sound);
  if (!laplacian_correction_is_sound(raw)) {
    EXPECT_FALSE(ok);
    EXPECT_TRUE(laplacian_correction_is_sound(guarded) || (guarded.xx == 1 && guarded.yy == 1));
    EXPECT_EQ(guarded.xy, 0.0);
  } else {
    EXPECT_TRUE(ok);
  }
  EXPECT_FALSE(laplacian_correction_is_sound(Mat2{-27.5, -7.4, -7.4, 0.48}));
  EXPECT_FALSE(laplacian_correction_is_sound(Mat2{1444, 793, 793, 439}));
  EXPECT_TRUE(laplacian_correction_is_sound(Mat2{1.1, 0.1, 0.1, 0.9}));
  // Fluid particles: indefinite but diffusive on average and bounded is kept (the exact Bhat
  // beside a box corner); anti-diffusive (the one seen beside a void) or huge is not.
  EXPECT_TRUE(laplacian_correction_is_bounded_diffusive(Mat2{-1.25, -0.02, -0.02, 6.26}));
  EXPECT_FALSE(laplacian_correction_is_bounded_diffusive(Mat2{-459, -159, -159, -77}));
  EXPECT_FALSE(laplacian_correction_is_bounded_diffusive(Mat2{-80, 0, 0, 90}));
  EXPECT_FALSE(laplacian_correction_is_bounded_diffusive(Mat2{1444, 793, 793, 439}));
}

TEST(Operators, SingularRenormalizationFallsBackToIdentity) {
  Mat2 B;
  // Collinear neighbours: S has rank one.
  Mat2 S = renormalization_pair(1.0, -2.0, Vec2{1.0, 0.0});
  S += renormalization_pair(1.0, -2.0, Vec2{-2.0, 0.0});
  EXPECT_FALSE(renormalization_tensor(S, B));
  EXPECT_EQ(B.xx, 1.0);
  EXPECT_EQ(B.xy, 0.0);
}

/// The largest singular value of a 2 x 2 matrix.
static real largest_singular_value(const Mat2& m) {
  const real a = ddot(m, m), d = det(m);
  return std::sqrt(0.5 * (a + std::sqrt(std::max(real(0), a * a - 4 * d * d))));
}

// A fluid particle at the edge of a void with three neighbours almost on one line (seen under a
// cylinder lifting off the floor): its moment matrix is nearly singular across the line, and the
// renormalized gradient amplified the neighbours' pressure differences a thousandfold. The bound
// lifts the smallest eigenvalue of M = -S to kMinMomentEigenvalue, so |B| <= 1 / that.
TEST(Operators, SparseSupportBoundsTheRenormalizedGradient) {
  const WendlandC2 kernel(2.0);
  const real w = 1.0;  // d0 = 1
  Mat2 S;
  Vec2 normal_sum, support_r;
  real support = 0;
  for (Vec2 xj : {Vec2{1.0, 0.0}, Vec2{-1.0, 0.01}, Vec2{0.5, -0.01}}) {
    const Vec2 rij = Vec2{0, 0} - xj;
    const real r = norm(rij);
    S += renormalization_pair(w, kernel.F(r), rij);
    normal_sum += (w * kernel.F(r)) * rij;
    support += w * kernel.W(r);
    support_r += (w * kernel.W(r)) * rij;
  }
  Mat2 B;
  ASSERT_TRUE(renormalization_tensor(S, B));  // passes the singularity test...
  EXPECT_GT(largest_singular_value(B), 1e3);  // ...with a gradient amplified a thousandfold
  Mat2 bounded = S;
  EXPECT_TRUE(bound_sparse_moment(bounded));
  ASSERT_TRUE(renormalization_tensor(bounded, B));
  EXPECT_LT(largest_singular_value(B), 1 / kMinMomentEigenvalue + 1e-9);
  // The zeroth-order-corrected moment is bounded the same way, and says so.
  Vec2 gamma;
  bool sparse = false;
  ASSERT_TRUE(consistent_gradient_correction(S, normal_sum, support, support_r, B, gamma, sparse));
  EXPECT_TRUE(sparse);
  EXPECT_LT(largest_singular_value(B), 1 / kMinMomentEigenvalue + 1e-9);
}

// A full support on a lattice is left alone (M = I there for the kernel's normalization).
TEST(Operators, SparseSupportBoundLeavesFullSupportsAlone) {
  const real d0 = 1.0;
  const WendlandC2 kernel(3.0 * d0);
  Mat2 S;
  for (int a = -3; a <= 3; ++a)
    for (int b = -3; b <= 3; ++b) {
      if (a == 0 && b == 0) continue;
      const Vec2 rij{-a * d0, -b * d0};
      S += renormalization_pair(d0 * d0, kernel.F(norm(rij)), rij);
    }
  EXPECT_NEAR(-S.xx, 1.0, 0.02);
  EXPECT_NEAR(-S.yy, 1.0, 0.02);
  Mat2 same = S;
  EXPECT_FALSE(bound_sparse_moment(same));
  EXPECT_EQ(same.xx, S.xx);
  EXPECT_EQ(same.yy, S.yy);
}
