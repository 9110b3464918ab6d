// The closed box of tests/box3.hpp as a 3D solver's sweeps see it: the boundary block first (one
// rigid group of wall particles), then the fluid; its pair list (CSR), the sweep context, and the
// geometry sweep's stored weights (geometry_at, the function the backends run). Shared by the
// geometry-sweep and stage-sweep tests in 3D.
#pragma once

#include <cstdint>
#include <vector>

#include "box3.hpp"
#include "particula/neighbors/neighbor_list.hpp"
#include "particula/solver/geometry_sweep.hpp"

namespace box3 {

struct BoxSweep {
  real d0 = 0, h = 0;
  std::vector<Vec3> x, normal;
  std::vector<real> vol;
  std::vector<Kind> kind;
  std::vector<std::int32_t> group;
  std::vector<Where> where;
  std::size_t nb = 0;
  Domain3 domain;
  NeighborList list;
  SweepContextOf<3> c;
  std::vector<Vec3> grad_w;
  std::vector<real> lap_w;
  std::vector<GeometryAtOf<3>> geo;

  BoxSweep(real spacing, real support) : d0(spacing), h(support) {
    const Cloud cloud = perturbed_box(d0, h);
    for (const bool walls : {true, false})
      for (std::size_t i = 0; i < cloud.x.size(); ++i) {
        if ((cloud.where[i] == Where::Wall) != walls) continue;
        x.push_back(cloud.x[i]);
        normal.push_back(cloud.normal[i]);
        vol.push_back(cloud.w[i]);
        kind.push_back(walls ? Kind::Boundary : Kind::Fluid);
        group.push_back(walls ? 0 : -1);
        where.push_back(cloud.where[i]);
      }
    while (nb < kind.size() && kind[nb] == Kind::Boundary) ++nb;
    domain.lo = {0, 0, 0};
    domain.hi = kBoxHi;
    const Wendland<3> kernel(h);
    CellGrid3 grid;
    grid.setup(domain, h, h);
    build_neighbor_list(x, domain, kernel, grid, list);
    c.domain = domain;
    c.kernel = kernel;
    c.start = list.start.data();
    c.j = list.j.data();
    c.n = x.size();
    c.nb = nb;
    c.x = x.data();
    c.vol = vol.data();
    c.kind = kind.data();
    c.group = group.data();
    c.normal = normal.data();
    grad_w.resize(list.pair_count());
    lap_w.resize(list.pair_count());
    geo.resize(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) geo[i] = geometry_at(c, i, d0, grad_w.data(), lap_w.data());
    c.grad_w = grad_w.data();
    c.lap_w = lap_w.data();
  }
  BoxSweep(const BoxSweep&) = delete;  // c points into the members
  BoxSweep& operator=(const BoxSweep&) = delete;
};

}  // namespace box3
