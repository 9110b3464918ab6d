// Consistent SPH operators (docs/method.md sections 3-5): the per-pair and per-particle pieces
// of the renormalized gradient, the Fatehi-Manzari Laplacian, the Morris Laplacian and the
// Rhie-Chow terms. One source of truth shared by the CPU loops and CUDA kernels.
//
// Conventions: r_ij = r_i - r_j, e_ij = r_ij / |r_ij|, gradW_ij = grad_i W_ij = W'(r) e_ij,
// w_j the volume of neighbour j. A gradient tensor L has L_ab = d_a u_b.
#pragma once

#include "particula/core/types.hpp"

namespace particula {

/// Renormalization tensor (P.6): B_i = -[ sum_j w_j r_ij (x) gradW_ij ]^-1, computed from the
/// accumulated sum S = sum_j w_j r_ij (x) gradW_ij. Returns false (and B = I) when S is (near)
/// singular: |det S| below `rel_tol` times the square of its trace, e.g. a particle with too few
/// or collinear neighbours. The caller counts such events.
PARTICULA_HD bool renormalization_tensor(const Mat2& S, Mat2& B, real rel_tol = 1e-6) {
  const real d = det(S);
  const real t = trace(S);
  if (!(std::fabs(d) > rel_tol * t * t)) {
    B = identity2();
    return false;
  }
  const real inv = -1.0 / d;  // minus sign of the definition folded in
  B = {inv * S.yy, -inv * S.xy, -inv * S.yx, inv * S.xx};
  return true;
}

/// Smallest eigenvalue accepted for the moment matrix M = -S of a fluid particle's gradient (1 for
/// a full support on any lattice, about 0.5 for half a support, e.g. at a free surface).
inline constexpr real kMinMomentEigenvalue = 0.25;

/// Bounds the renormalized gradient of a sparse support: where the symmetric part of M = -S has an
/// eigenvalue below `floor`, M is lifted by (floor - that eigenvalue) I, so that |B| = |M^-1| <=
/// 1 / floor (x . M x >= floor |x|^2 gives |M x| >= floor |x|). Why (docs/method.md, "Sparse
/// supports: the gradient bounded at the edge of a void"): a fluid particle left with three or four
/// neighbours at the edge of a void (under a body lifting off a wall) has an eigenvalue near 0 and
/// a gradient amplified a thousandfold; its neighbours' small pressure differences then threw it
/// across the void at 1 m/s, and the compression where it landed ended the run (`drop_rebound` at
/// d0 = 1e-4). Full and half supports (eigenvalues 0.5-1.3) are untouched, so the gradient stays
/// exact for linear fields there. Returns true when it lifted.
PARTICULA_HD bool bound_sparse_moment(Mat2& S, real floor = kMinMomentEigenvalue) {
  const real a = -S.xx, d = -S.yy, b = -0.5 * (S.xy + S.yx);
  const real half_diff = 0.5 * (a - d);
  const real lambda_min = 0.5 * (a + d) - std::sqrt(half_diff * half_diff + b * b);
  if (!(lambda_min < floor)) return false;
  const real lift = floor - lambda_min;
  S.xx -= lift;
  S.yy -= lift;
  return true;
}

/// The zeroth-order correction of the renormalized gradient (Bonet and Lok 1999, the gradient of a
/// Shepard-corrected kernel): gradW_ij becomes gradW_ij - gamma_i W_ij with
///   gamma_i = sum_j w_j gradW_ij / sum_j w_j W_ij   (`normal_sum` / `support`, j != i),
/// so that the weights sum to zero, and B~ renormalizes the corrected gradient:
///   B~ = -[ S - gamma (x) sum_j w_j W_ij r_ij ]^-1   (`support_r` the last sum),
/// which keeps the gradient exact for linear fields. Why (docs/method.md, "The self-coupled mode:
/// zeroth-order gradient correction"): with P.7 alone a particle's own pressure enters its gradient
/// as -P_i B sum_j w_j gradW_ij and its own velocity its divergence as -V_i . B sum_j w_j gradW_ij;
/// on an irregular distribution (that sum, n_i, nonzero: compressed fluid, a single-layer wall) the
/// pair (P', V' along n_i) obeys d^2 P'/dt^2 = c^2 |n_i|^2 P' and grows at the rate c |n_i|. With
/// the weights summing to zero neither own value enters, as on a regular lattice. The corrected
/// moment is bounded below as P.7's is (bound_sparse_moment; `sparse` set when it lifted). Returns
/// false (B, gamma untouched) without support or with a singular corrected moment.
/// The same in 3D (sph/operators3.hpp has the 3D bound and inverse).
template <int D>
PARTICULA_HD bool consistent_gradient_correction(const Mat<D>& S, Vec<D> normal_sum, real support, Vec<D> support_r,
                                                 Mat<D>& B, Vec<D>& gamma, bool& sparse) {
  if (!(support > 0)) return false;
  const Vec<D> g = (1 / support) * normal_sum;
  Mat<D> Sz = S - outer(g, support_r);
  sparse = bound_sparse_moment(Sz) || sparse;
  Mat<D> Bz;
  if (!renormalization_tensor(Sz, Bz)) return false;
  B = Bz;
  gamma = g;
  return true;
}

/// Contribution of neighbour j to S = sum_j w_j r_ij (x) gradW_ij, with gradW_ij = F r_ij.
template <int D>
PARTICULA_HD Mat<D> renormalization_pair(real w_j, real F, Vec<D> r_ij) {
  return (w_j * F) * outer(r_ij, r_ij);
}

/// Contribution of neighbour j to the renormalized gradient of a scalar (P.7):
/// w_j (B_i . gradW_ij) (u_j - u_i). `BgW` is B_i . gradW_ij already multiplied by w_j.
template <int D>
PARTICULA_HD Vec<D> gradient_pair(Vec<D> wBgW, real du_ji) {
  return du_ji * wBgW;
}

/// Contribution to the gradient of a vector field: (w B gradW) (x) (V_j - V_i).
template <int D>
PARTICULA_HD Mat<D> vector_gradient_pair(Vec<D> wBgW, Vec<D> dV_ji) {
  return outer(wBgW, dV_ji);
}

// ---- Fatehi-Manzari second derivative (P.10-P.11) -------------------------------------------

/// Fully symmetric 3rd-order 2D tensor: components xxx, xxy, xyy, yyy.
struct Sym3 {
  real c[4] = {0, 0, 0, 0};
};
/// Fully symmetric 4th-order 2D tensor: components xxxx, xxxy, xxyy, xyyy, yyyy.
struct Sym4 {
  real c[5] = {0, 0, 0, 0, 0};
};

/// Index of a component of a fully symmetric tensor = number of y indices.
PARTICULA_HD real sym3_at(const Sym3& t, int a, int b, int c) { return t.c[a + b + c]; }
PARTICULA_HD real sym4_at(const Sym4& t, int a, int b, int c, int d) { return t.c[a + b + c + d]; }

/// Adds s * e(x)e(x)e to a Sym3.
PARTICULA_HD void add_eee(Sym3& t, real s, Vec2 e) {
  const real xx = e.x * e.x, yy = e.y * e.y;
  t.c[0] += s * xx * e.x;
  t.c[1] += s * xx * e.y;
  t.c[2] += s * e.x * yy;
  t.c[3] += s * yy * e.y;
}
/// Adds s * e(x)e(x)e(x)e to a Sym4.
PARTICULA_HD void add_eeee(Sym4& t, real s, Vec2 e) {
  const real xx = e.x * e.x, yy = e.y * e.y, xy = e.x * e.y;
  t.c[0] += s * xx * xx;
  t.c[1] += s * xx * xy;
  t.c[2] += s * xx * yy;
  t.c[3] += s * xy * yy;
  t.c[4] += s * yy * yy;
}

/// The three moment sums that define Bhat_i (docs/method.md section 4), all fully symmetric because
/// gradW_ij is parallel to e_ij:
///   T4 = sum_j w_j r_ij e(x)gradW(x)e(x)e  = sum w r W' e e e e
///   T3 = sum_j w_j e(x)e(x)gradW           = sum w W' e e e
///   Q3 = sum_j w_j r(x)r(x)gradW           = sum w r^2 W' e e e
struct LaplacianMoments {
  Sym4 T4;
  Sym3 T3;
  Sym3 Q3;
};

/// Adds neighbour j to the moments. `dW` = W'(r_ij), `e` = e_ij.
PARTICULA_HD void laplacian_moments_pair(LaplacianMoments& m, real w_j, real r, real dW, Vec2 e) {
  const real s = w_j * dW;
  add_eeee(m.T4, s * r, e);
  add_eee(m.T3, s, e);
  add_eee(m.Q3, s * r * r, e);
}

/// Largest eigenvalue accepted for Bhat (about 1 in the interior, a few next to a wall).
inline constexpr real kMaxLaplacianCorrection = 50;

/// A usable correction tensor at a boundary particle is symmetric positive definite (so that
/// every pair term of the Laplacian keeps the diffusive sign) and not huge. Near a convex body
/// the one-sided moment system can be nearly singular and return an indefinite Bhat with entries
/// of 1e4 that turn the Laplacian at a surface particle into noise (seen: wall pressure spikes of
/// 3e3 Pa).
PARTICULA_HD bool laplacian_correction_is_sound(const Mat2& Bh) {
  const real tr = Bh.xx + Bh.yy, dt = Bh.xx * Bh.yy - Bh.xy * Bh.yx;
  if (!(tr > 0 && dt > 0)) return false;
  const real lmax = 0.5 * tr + std::sqrt(std::fmax(0.0, 0.25 * tr * tr - dt));
  return lmax < kMaxLaplacianCorrection;
}

/// A usable correction tensor at a fluid particle is diffusive on average over directions
/// (trace > 0) and bounded (both eigenvalues below kMaxLaplacianCorrection in magnitude). It may
/// be indefinite: next to a box corner the exact second-order Bhat has one negative eigenvalue
/// (e.g. diag(-1.25, 6.26)), and rejecting it costs the operator its exactness for quadratic
/// fields there. What must go is the anti-diffusive solution beside a void in the particle
/// distribution (seen: [-459 -159; -159 -77] under bodies resting on a floor, which amplified
/// the particle's velocity by 10 % per step).
PARTICULA_HD bool laplacian_correction_is_bounded_diffusive(const Mat2& Bh) {
  const real tr = Bh.xx + Bh.yy, dt = Bh.xx * Bh.yy - Bh.xy * Bh.yx;
  if (!(tr > 0)) return false;
  const real half = 0.5 * tr, disc = std::sqrt(std::fmax(0.0, half * half - dt));
  return std::fmax(std::fabs(half + disc), std::fabs(half - disc)) < kMaxLaplacianCorrection;
}

/// Which solutions of the Bhat system are accepted (the others fall back to k I).
enum class BhatCheck : int {
  None,              ///< any non-singular solution
  BoundedDiffusive,  ///< fluid particles: laplacian_correction_is_bounded_diffusive
  Sound              ///< boundary particles: laplacian_correction_is_sound
};

/// Solves Bhat : M = -I for the symmetric Bhat (P.11), with
///   M_abcd = T4_abcd + sum_ef T3_abe B_ef Q3_fcd.
/// In 2D a 3x3 system in (Bhat_xx, Bhat_xy, Bhat_yy). Returns false when the system is singular
/// or its solution fails `check`; then Bhat = k I, normalized for |x|^2, or I.
PARTICULA_HD bool laplacian_correction_tensor(const LaplacianMoments& m, const Mat2& B, Mat2& Bhat,
                                              BhatCheck check = BhatCheck::None, real rel_tol = 1e-9) {
  const real Bm[2][2] = {{B.xx, B.xy}, {B.yx, B.yy}};
  // BQ_ecd = sum_f B_ef Q3_fcd for the symmetric pairs cd (c <= d): index cd -> (0,0),(0,1),(1,1).
  const int pc[3] = {0, 0, 1}, pd[3] = {0, 1, 1};
  real BQ[2][3];
  for (int e = 0; e < 2; ++e)
    for (int k = 0; k < 3; ++k)
      BQ[e][k] = Bm[e][0] * sym3_at(m.Q3, 0, pc[k], pd[k]) + Bm[e][1] * sym3_at(m.Q3, 1, pc[k], pd[k]);
  // A[row = cd][col = ab] = multiplicity(ab) * M_abcd.
  real A[3][3];
  const real mult[3] = {1, 2, 1};
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col) {
      const int a = pc[col], b = pd[col], c = pc[row], d = pd[row];
      const real M = sym4_at(m.T4, a, b, c, d) + sym3_at(m.T3, a, b, 0) * BQ[0][row] +
                     sym3_at(m.T3, a, b, 1) * BQ[1][row];
      A[row][col] = mult[col] * M;
    }
  const real rhs[3] = {-1, 0, -1};
  const real D = A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
                 A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
                 A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
  real scale = 0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) scale = std::fmax(scale, std::fabs(A[r][c]));
  bool ok = std::fabs(D) > rel_tol * scale * scale * scale;
  if (ok) {
    real x[3];
    for (int k = 0; k < 3; ++k) {
      real Ak[3][3];
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) Ak[r][c] = (c == k) ? rhs[r] : A[r][c];
      const real Dk = Ak[0][0] * (Ak[1][1] * Ak[2][2] - Ak[1][2] * Ak[2][1]) -
                      Ak[0][1] * (Ak[1][0] * Ak[2][2] - Ak[1][2] * Ak[2][0]) +
                      Ak[0][2] * (Ak[1][0] * Ak[2][1] - Ak[1][1] * Ak[2][0]);
      x[k] = Dk / D;
    }
    Bhat = {x[0], x[1], x[1], x[2]};
    if (check == BhatCheck::Sound) ok = laplacian_correction_is_sound(Bhat);
    if (check == BhatCheck::BoundedDiffusive) ok = laplacian_correction_is_bounded_diffusive(Bhat);
  }
  if (ok) return true;
  // Guard (docs/method.md, "The Bhat guard"): a singular or unsound system falls back to
  // Bhat = k I, with k making the operator exact for u = |x|^2/2 (H = I): k = -2 / (I : M : I).
  const real IMI = A[0][0] + A[0][2] + A[2][0] + A[2][2];  // multiplicities of xx and yy are 1
  const real k = -2 / IMI;
  Bhat = (std::isfinite(k) && k > 0 && k < kMaxLaplacianCorrection) ? k * identity2() : identity2();
  return false;
}

/// Pair weight of the Fatehi-Manzari Laplacian: since e (x) gradW = W' e (x) e,
///   Bhat : 2 w_j (e (x) gradW) = 2 w_j W' (e . Bhat . e).
template <int D>
PARTICULA_HD real fm_pair_weight(const Mat<D>& Bhat, real w_j, real dW, Vec<D> e) {
  return 2 * w_j * dW * dot(e, Bhat * e);
}

/// Fatehi-Manzari Laplacian pair term for a scalar (P.10):
///   weight * [ (u_i - u_j)/r_ij - e_ij . <grad u>_i ].
template <int D>
PARTICULA_HD real fm_laplacian_pair(real weight, real du_ij, real r, Vec<D> e, Vec<D> grad_i) {
  return weight * (du_ij / r - dot(e, grad_i));
}

/// Same for a vector field, with the gradient tensor L_ab = d_a V_b: e . L is the directional
/// derivative of each component along e.
template <int D>
PARTICULA_HD Vec<D> fm_laplacian_pair(real weight, Vec<D> dV_ij, real r, Vec<D> e, const Mat<D>& L_i) {
  return weight * (dV_ij / r - e * L_i);
}

/// Morris/Brookshaw Laplacian pair term (P.8): 2 w_j (u_i - u_j)/r_ij  e_ij . gradW_ij.
/// Not exact for quadratics next to walls; kept as the baseline.
PARTICULA_HD real morris_pair_weight(real w_j, real dW) { return 2 * w_j * dW; }

}  // namespace particula
