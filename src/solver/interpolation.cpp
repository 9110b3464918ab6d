#include "particula/solver/interpolation.hpp"

#include "particula/neighbors/neighbor_list.hpp"

namespace particula {

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
    real sw = 0, sp = 0;
    Vec2 sv;
    for (int c = 0; c < nc; ++c)
      for (auto s = start[cells[c]]; s < start[cells[c] + 1]; ++s) {
        const auto j = sorted[s];
        if (P.kind[j] == Kind::Dummy) continue;
        const real r = norm(domain.separation(xp, P.x[j]));
        if (r >= kernel.h) continue;
        const real ww = kernel.W(r) * P.m[j] / P.rho[j];
        sw += ww;
        sv += ww * P.v[j];
        sp += ww * P.p[j];
      }
    out[k].shepard = sw;
    if (sw > 0) {
      out[k].v = sv / sw;
      out[k].p = sp / sw;
    }
  }
  return out;
}

}  // namespace particula
