// The closest pair and the particles' nearest surfaces for failure messages (solver/closest_pair.hpp).
#include "particula/solver/closest_pair.hpp"

#include <fmt/format.h>

#include <limits>

#include "particula/neighbors/neighbor_list.hpp"

namespace particula {

namespace {

/// A cell grid of side h over the particles (bounded axes get a margin of h for strays).
CellGrid binned_grid(const Particles& P, const Domain& domain, real h) {
  CellGrid grid;
  grid.setup(domain, h, h);
  grid.bin(P.x);
  return grid;
}

/// Calls consider(j, d2) for every particle j != i within h of particle i.
template <class Consider>
void visit_within(const CellGrid& grid, const Particles& P, real h, std::uint32_t i, Consider&& consider) {
  const real h2 = h * h;
  visit_candidates(grid.geometry(), P.x.data(), grid.sorted().data(), grid.cell_start().data(), grid.cell_of()[i], i,
                   [&](std::uint32_t j, real d2) {
                     if (is_neighbor(i, j, d2, h2)) consider(j, d2);
                   });
}

std::int64_t nearest_surface_in(const CellGrid& grid, const Particles& P, real h, std::uint32_t i) {
  std::int64_t best = -1;
  real best2 = std::numeric_limits<real>::infinity();
  visit_within(grid, P, h, i, [&](std::uint32_t j, real d2) {
    if (j < P.n_boundary && P.kind[j] == Kind::Boundary && P.ds[j] > 0 && d2 < best2) {
      best2 = d2;
      best = j;
    }
  });
  return best;
}

const char* kind_name(Kind k) {
  switch (k) {
    case Kind::Fluid: return "fluid particle";
    case Kind::Boundary: return "surface particle";
    case Kind::Dummy: return "dummy particle";
    case Kind::Inlet: return "inlet buffer particle";
    case Kind::Outlet: return "outlet buffer particle";
  }
  return "particle";
}

std::string group_label(const std::vector<RigidGroup>& groups, std::int32_t g) {
  if (g < 0 || static_cast<std::size_t>(g) >= groups.size()) return "a surface";
  const RigidGroup& rg = groups[static_cast<std::size_t>(g)];
  return fmt::format("{} '{}'", rg.is_wall ? "wall" : "body", rg.name);
}

}  // namespace

ClosestPair closest_pair(const Particles& P, const Domain& domain, real h) {
  ClosestPair out;
  if (P.size() < 2) return out;
  const CellGrid grid = binned_grid(P, domain, h);
  real best2 = std::numeric_limits<real>::infinity();
  for (std::uint32_t i = 0; i < P.size(); ++i)
    visit_within(grid, P, h, i, [&](std::uint32_t j, real d2) {
      if (j < i || (is_buffer(P.kind[i]) && is_buffer(P.kind[j]))) return;
      if (d2 < best2 || (d2 == best2 && i < out.i)) {
        best2 = d2;
        out = ClosestPair{true, i, j, std::sqrt(d2)};
      }
    });
  return out;
}

std::int64_t nearest_surface_particle(const Particles& P, const Domain& domain, real h, std::uint32_t i) {
  return nearest_surface_in(binned_grid(P, domain, h), P, h, i);
}

std::string describe_particle(const Particles& P, const Domain& domain, const std::vector<RigidGroup>& groups,
                              real h, real d0, std::uint32_t i) {
  std::string s = fmt::format("{} {} at ({:.6g}, {:.6g}) m", kind_name(P.kind[i]), P.id[i], P.x[i].x, P.x[i].y);
  if (i < P.n_boundary) return s + " on " + group_label(groups, P.group[i]);
  const std::int64_t near = nearest_surface_particle(P, domain, h, i);
  if (near < 0) return s + ", no surface within h";
  const auto k = static_cast<std::size_t>(near);
  return s + fmt::format(", {:.3g} d0 from {} (its surface particle at ({:.6g}, {:.6g}) m)",
                         norm(domain.separation(P.x[i], P.x[k])) / d0, group_label(groups, P.group[k]), P.x[k].x,
                         P.x[k].y);
}

}  // namespace particula
