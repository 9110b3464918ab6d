#include "particula/solver/interpolation.hpp"

#include <cmath>

#include "particula/neighbors/neighbor_list.hpp"

namespace particula {

namespace {

constexpr int kMaxBasis = 6;
constexpr int kMaxRhs = 3;

/// The monomials of the quadratic (n = 6) or linear (n = 3) basis at offset d.
void basis(Vec2 d, int n, real* p) {
  p[0] = 1;
  p[1] = d.x;
  p[2] = d.y;
  if (n == 6) {
    p[3] = d.x * d.x;
    p[4] = d.x * d.y;
    p[5] = d.y * d.y;
  }
}

}  // namespace

bool mls_fit(int order, const std::vector<Vec2>& dx, const std::vector<real>& w, const std::vector<real>& f,
             int nrhs, real* value) {
  const int n = order == 2 ? 6 : 3;
  // Moment matrix M = sum_j w_j p_j p_j^T and right-hand sides b = sum_j w_j p_j f_j.
  real M[kMaxBasis][kMaxBasis] = {}, b[kMaxBasis][kMaxRhs] = {};
  real p[kMaxBasis];
  for (std::size_t j = 0; j < dx.size(); ++j) {
    basis(dx[j], n, p);
    for (int r = 0; r < n; ++r) {
      for (int c = 0; c <= r; ++c) M[r][c] += w[j] * p[r] * p[c];
      for (int k = 0; k < nrhs; ++k) b[r][k] += w[j] * p[r] * f[j * nrhs + k];
    }
  }
  // Cholesky M = L L^T (lower triangle in place); a pivot that loses all but 1e-6 of its
  // diagonal entry means the points leave a direction of the basis undetermined.
  for (int c = 0; c < n; ++c) {
    real d = M[c][c];
    for (int k = 0; k < c; ++k) d -= M[c][k] * M[c][k];
    if (!(d > 1e-6 * M[c][c]) || !(M[c][c] > 0)) return false;
    M[c][c] = std::sqrt(d);
    for (int r = c + 1; r < n; ++r) {
      real s = M[r][c];
      for (int k = 0; k < c; ++k) s -= M[r][k] * M[c][k];
      M[r][c] = s / M[c][c];
    }
  }
  // a = M^-1 b by forward (L y = b) and back (L^T a = y) substitution; only a_0 is wanted.
  for (int k = 0; k < nrhs; ++k) {
    real y[kMaxBasis];
    for (int r = 0; r < n; ++r) {
      real s = b[r][k];
      for (int c = 0; c < r; ++c) s -= M[r][c] * y[c];
      y[r] = s / M[r][r];
    }
    for (int r = n - 1; r >= 0; --r) {
      real s = y[r];
      for (int c = r + 1; c < n; ++c) s -= M[c][r] * y[c];
      y[r] = s / M[r][r];
    }
    value[k] = y[0];
  }
  return true;
}

std::vector<PointSample> interpolate_at(const Particles& P, const Domain& domain, const WendlandC2& kernel,
                                        const std::vector<Vec2>& points) {
  CellGrid grid;
  grid.setup(domain, kernel.h);
  grid.bin(P.x);
  const auto& sorted = grid.sorted();
  const auto& start = grid.cell_start();
  std::vector<PointSample> out(points.size());
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Vec2 xp = domain.wrap(points[k]);
    int cells[9];
    const int nc = grid.neighbor_cells(grid.cell_index(xp), cells);
    // The data points around xp, in a fixed order (cells, then the cell-sorted particles).
    std::vector<Vec2> dx;
    std::vector<real> w, f;
    real sw = 0, sf[kMaxRhs] = {};
    for (int c = 0; c < nc; ++c)
      for (auto s = start[cells[c]]; s < start[cells[c] + 1]; ++s) {
        const auto j = sorted[s];
        if (P.kind[j] == Kind::Dummy) continue;  // behind a surface: the surface particles carry the wall
        const Vec2 d = domain.separation(P.x[j], xp);
        const real r = norm(d);
        if (r >= kernel.h) continue;
        const real ww = kernel.W(r) * P.m[j] / P.rho[j];
        const real fj[kMaxRhs] = {P.v[j].x, P.v[j].y, P.p[j]};
        dx.push_back(d * kernel.inv_h);
        w.push_back(ww);
        f.insert(f.end(), fj, fj + kMaxRhs);
        sw += ww;
        for (int q = 0; q < kMaxRhs; ++q) sf[q] += ww * fj[q];
      }
    PointSample& o = out[k];
    o.shepard = sw;
    if (!(sw > 0)) continue;
    real value[kMaxRhs];
    if (mls_fit(2, dx, w, f, kMaxRhs, value)) {
      o.order = 2;
    } else if (mls_fit(1, dx, w, f, kMaxRhs, value)) {
      o.order = 1;
    } else {
      for (int q = 0; q < kMaxRhs; ++q) value[q] = sf[q] / sw;
      o.order = 0;
    }
    o.v = {value[0], value[1]};
    o.p = value[2];
  }
  return out;
}

}  // namespace particula
