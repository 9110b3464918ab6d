// The consistent SPH operators in 3D (docs/method.md sections 3-4): the pieces of
// sph/operators.hpp whose form depends on the dimension through more than the types, the inverse
// of the renormalization moment, the eigenvalues its bound and the Bhat guard read, and the
// Laplacian correction Bhat with its six unknowns. The pair functions written for any D
// (renormalization_pair, gradient_pair, fm_pair_weight, fm_laplacian_pair, ...) and the
// zeroth-order correction are those of sph/operators.hpp.
#pragma once

#include <cmath>

#include "particula/core/types3.hpp"
#include "particula/sph/operators.hpp"

namespace particula {

/// The eigenvalues of the symmetric part of a 3x3 matrix, ascending (the trigonometric solution
/// of the characteristic cubic).
PARTICULA_HD Vec3 symmetric_eigenvalues(const Mat3& m) {
  const Mat3 a = sym(m);
  const real off = a.xy * a.xy + a.xz * a.xz + a.yz * a.yz;
  const real q = trace(a) / 3;
  const real p2 = (a.xx - q) * (a.xx - q) + (a.yy - q) * (a.yy - q) + (a.zz - q) * (a.zz - q) + 2 * off;
  if (!(p2 > 0)) return {q, q, q};
  const real p = std::sqrt(p2 / 6);
  const real r0 = 0.5 * det((1 / p) * (a - q * identity3()));
  const real r = r0 < -1 ? -1 : (r0 > 1 ? 1 : r0);
  const real phi = std::acos(r) / 3;
  const real hi = q + 2 * p * std::cos(phi), lo = q + 2 * p * std::cos(phi + 2 * M_PI / 3);
  return {lo, 3 * q - hi - lo, hi};
}

/// Renormalization tensor (P.6) in 3D: B_i = -S^-1, S = sum_j w_j r_ij (x) gradW_ij. Returns false
/// (and B = I) when S is (near) singular: |det S| below rel_tol |trace S|^3.
PARTICULA_HD bool renormalization_tensor(const Mat3& S, Mat3& B, real rel_tol = 1e-6) {
  const real d = det(S), t = trace(S);
  Mat3 inv;
  if (!(std::fabs(d) > rel_tol * std::fabs(t * t * t)) || !inverse(S, inv, 0)) {
    B = identity3();
    return false;
  }
  B = -1.0 * inv;
  return true;
}

/// The bound of a sparse support's moment in 3D (see the 2D bound_sparse_moment): where the
/// symmetric part of M = -S has an eigenvalue below `floor`, M is lifted by (floor - that
/// eigenvalue) I. Returns true when it lifted.
PARTICULA_HD bool bound_sparse_moment(Mat3& S, real floor = kMinMomentEigenvalue) {
  const real lambda_min = symmetric_eigenvalues(-1.0 * S).x;
  if (!(lambda_min < floor)) return false;
  const real lift = floor - lambda_min;
  S.xx -= lift;
  S.yy -= lift;
  S.zz -= lift;
  return true;
}

/// A fully symmetric tensor of order 3 (10 components) and of order 4 (15 components) in 3D,
/// stored by the numbers of y and z indices: component (n_y, n_z) at m (m + 1) / 2 + n_z with
/// m = n_y + n_z.
struct Sym3Order3 {
  real c[10] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
};
struct Sym3Order4 {
  real c[15] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
};

/// The storage index of the component with n_y y-indices and n_z z-indices.
PARTICULA_HD int sym3_index(int ny, int nz) { return (ny + nz) * (ny + nz + 1) / 2 + nz; }
PARTICULA_HD real sym_at(const Sym3Order3& t, int a, int b, int c) {
  const int ny = (a == 1) + (b == 1) + (c == 1), nz = (a == 2) + (b == 2) + (c == 2);
  return t.c[sym3_index(ny, nz)];
}
PARTICULA_HD real sym_at(const Sym3Order4& t, int a, int b, int c, int d) {
  const int ny = (a == 1) + (b == 1) + (c == 1) + (d == 1), nz = (a == 2) + (b == 2) + (c == 2) + (d == 2);
  return t.c[sym3_index(ny, nz)];
}

/// Adds s e^(x k) (the k-fold outer product of e) to a fully symmetric tensor of order k: the
/// component (n_y, n_z) is s e_x^(k - n_y - n_z) e_y^n_y e_z^n_z.
template <int K>
PARTICULA_HD void add_symmetric_power(real* c, real s, Vec3 e) {
  real px[K + 1], py[K + 1], pz[K + 1];
  px[0] = py[0] = pz[0] = 1;
  for (int k = 1; k <= K; ++k) {
    px[k] = px[k - 1] * e.x;
    py[k] = py[k - 1] * e.y;
    pz[k] = pz[k - 1] * e.z;
  }
  for (int m = 0; m <= K; ++m)
    for (int nz = 0; nz <= m; ++nz) c[sym3_index(m - nz, nz)] += s * px[K - m] * py[m - nz] * pz[nz];
}

/// The moment sums that define Bhat_i in 3D (as LaplacianMoments in 2D).
struct LaplacianMoments3 {
  Sym3Order4 T4;
  Sym3Order3 T3;
  Sym3Order3 Q3;
};

/// Adds neighbour j to the moments. `dW` = W'(r_ij), `e` = e_ij.
PARTICULA_HD void laplacian_moments_pair(LaplacianMoments3& m, real w_j, real r, real dW, Vec3 e) {
  const real s = w_j * dW;
  add_symmetric_power<4>(m.T4.c, s * r, e);
  add_symmetric_power<3>(m.T3.c, s, e);
  add_symmetric_power<3>(m.Q3.c, s * r * r, e);
}

/// The Bhat guards of sph/operators.hpp in 3D: sound (symmetric positive definite, largest
/// eigenvalue below kMaxLaplacianCorrection) for boundary particles, bounded and diffusive on
/// average (trace > 0, every eigenvalue below it in magnitude) for fluid particles.
PARTICULA_HD bool laplacian_correction_is_sound(const Mat3& Bh) {
  const Vec3 l = symmetric_eigenvalues(Bh);
  return l.x > 0 && l.z < kMaxLaplacianCorrection;
}
PARTICULA_HD bool laplacian_correction_is_bounded_diffusive(const Mat3& Bh) {
  const Vec3 l = symmetric_eigenvalues(Bh);
  return trace(Bh) > 0 && std::fabs(l.x) < kMaxLaplacianCorrection &&
         std::fabs(l.z) < kMaxLaplacianCorrection;
}

/// Solves Bhat : M = -I for the symmetric Bhat (P.11) in 3D, with
///   M_abcd = T4_abcd + sum_ef T3_abe B_ef Q3_fcd,
/// a 6x6 system in (Bhat_xx, Bhat_xy, Bhat_xz, Bhat_yy, Bhat_yz, Bhat_zz), solved by Gaussian
/// elimination with partial pivoting. Singular (|det| below rel_tol times the sixth power of the
/// largest entry) or failing `check`: Bhat = k I with k = -3 / (I : M : I), which makes the
/// operator exact for |x|^2 / 2, or I; returns false.
PARTICULA_HD bool laplacian_correction_tensor(const LaplacianMoments3& m, const Mat3& B, Mat3& Bhat,
                                              BhatCheck check = BhatCheck::None, real rel_tol = 1e-9) {
  const real Bm[3][3] = {{B.xx, B.xy, B.xz}, {B.yx, B.yy, B.yz}, {B.zx, B.zy, B.zz}};
  const int pa[6] = {0, 0, 0, 1, 1, 2}, pb[6] = {0, 1, 2, 1, 2, 2};
  const real mult[6] = {1, 2, 2, 1, 2, 1};
  // BQ_ecd = sum_f B_ef Q3_fcd for the symmetric pairs cd
  real BQ[3][6];
  for (int e = 0; e < 3; ++e)
    for (int k = 0; k < 6; ++k) {
      BQ[e][k] = 0;
      for (int f = 0; f < 3; ++f) BQ[e][k] += Bm[e][f] * sym_at(m.Q3, f, pa[k], pb[k]);
    }
  // A[row = cd][col = ab] = multiplicity(ab) M_abcd; the right-hand side -I : (cd)
  real A[6][7];
  real scale = 0;
  for (int row = 0; row < 6; ++row) {
    for (int col = 0; col < 6; ++col) {
      const int a = pa[col], b = pb[col], c = pa[row], d = pb[row];
      real M = sym_at(m.T4, a, b, c, d);
      for (int e = 0; e < 3; ++e) M += sym_at(m.T3, a, b, e) * BQ[e][row];
      A[row][col] = mult[col] * M;
      scale = std::fmax(scale, std::fabs(A[row][col]));
    }
    A[row][6] = pa[row] == pb[row] ? -1 : 0;
  }
  // I : M : I from the diagonal rows and columns, before the elimination overwrites them
  const int diag[3] = {0, 3, 5};
  real IMI = 0;
  for (const int r : diag)
    for (const int c : diag) IMI += A[r][c];
  real det_abs = 1;
  bool ok = scale > 0;
  for (int k = 0; k < 6 && ok; ++k) {
    int piv = k;
    for (int r = k + 1; r < 6; ++r)
      if (std::fabs(A[r][k]) > std::fabs(A[piv][k])) piv = r;
    if (piv != k)
      for (int c = 0; c < 7; ++c) {
        const real t = A[k][c];
        A[k][c] = A[piv][c];
        A[piv][c] = t;
      }
    det_abs *= std::fabs(A[k][k]) / scale;
    if (!(A[k][k] != 0)) {
      ok = false;
      break;
    }
    for (int r = k + 1; r < 6; ++r) {
      const real f = A[r][k] / A[k][k];
      for (int c = k; c < 7; ++c) A[r][c] -= f * A[k][c];
    }
  }
  ok = ok && det_abs > rel_tol;
  if (ok) {
    real x[6];
    for (int k = 5; k >= 0; --k) {
      real s = A[k][6];
      for (int c = k + 1; c < 6; ++c) s -= A[k][c] * x[c];
      x[k] = s / A[k][k];
    }
    Bhat = {x[0], x[1], x[2], x[1], x[3], x[4], x[2], x[4], x[5]};
    if (check == BhatCheck::Sound) ok = laplacian_correction_is_sound(Bhat);
    if (check == BhatCheck::BoundedDiffusive) ok = laplacian_correction_is_bounded_diffusive(Bhat);
  }
  if (ok) return true;
  const real k = -3 / IMI;  // -D / (I : M : I): exact for tr H = D
  Bhat = (std::isfinite(k) && k > 0 && k < kMaxLaplacianCorrection) ? k * identity3() : identity3();
  return false;
}

}  // namespace particula
