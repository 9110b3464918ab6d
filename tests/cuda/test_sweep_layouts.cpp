// The CUDA backend runs the shared sweeps of solver/sweeps.hpp over a neighbour list that it
// builds its own way (keys sorted stably, cell starts by binary search) and stores column-major
// (ELL: neighbour q of particle i at q * stride + i), where the CPU uses the counting-sort
// binning and CSR rows. These tests run the GPU's algorithm and layout on the host, with the
// same PARTICULA_HD functions, and require bitwise the CPU's list and the CPU's results: they
// check the GPU backend's indexing on a machine without a GPU.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <vector>

#include "case_builders.hpp"
#include "particula/neighbors/neighbor_list.hpp"
#include "particula/scene/scene.hpp"
#include "particula/solver/sweeps.hpp"

namespace particula {
namespace {

template <class T>
bool same_bits(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

/// The neighbour list as the CUDA backend builds it (refresh_geometry in cuda_backend.cu):
/// keys = cell of every particle, indices stably sorted by key, cell starts by lower_bound,
/// then one visit per particle writing neighbour q at q * stride + i.
struct EllList {
  std::vector<std::uint32_t> count, j;
  std::size_t stride = 0, width = 0;
};

EllList gpu_style_list(const std::vector<Vec2>& x, const GridGeometry& grid, real h, std::size_t stride) {
  const std::size_t n = x.size();
  std::vector<std::uint32_t> cell_of(n), sorted(n);
  for (std::size_t i = 0; i < n; ++i) cell_of[i] = static_cast<std::uint32_t>(grid.cell_index(x[i]));
  std::iota(sorted.begin(), sorted.end(), 0u);
  std::stable_sort(sorted.begin(), sorted.end(), [&](std::uint32_t a, std::uint32_t b) { return cell_of[a] < cell_of[b]; });
  std::vector<std::uint32_t> keys(n);
  for (std::size_t s = 0; s < n; ++s) keys[s] = cell_of[sorted[s]];
  const std::size_t ncell = static_cast<std::size_t>(grid.cell_count());
  std::vector<std::uint32_t> cstart(ncell + 1);
  for (std::size_t c = 0; c <= ncell; ++c)
    cstart[c] = static_cast<std::uint32_t>(std::lower_bound(keys.begin(), keys.end(), c) - keys.begin());
  EllList L;
  L.stride = stride;
  L.count.resize(n);
  const real h2 = h * h;
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t k = 0;
    visit_neighbors(grid, h2, x.data(), sorted.data(), cstart.data(), cell_of[i], static_cast<std::uint32_t>(i),
                    [&](std::uint32_t, real) { ++k; });
    L.count[i] = k;
    L.width = std::max<std::size_t>(L.width, k);
  }
  L.j.assign(L.width * stride, 0xFFFFFFFFu);  // padding that would be out of range if read
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t q = i;
    visit_neighbors(grid, h2, x.data(), sorted.data(), cstart.data(), cell_of[i], static_cast<std::uint32_t>(i),
                    [&](std::uint32_t j, real) {
                      L.j[q] = j;
                      q += stride;
                    });
  }
  return L;
}

/// Per-pair and per-particle arrays of one layout.
struct Fields {
  std::vector<Vec2> grad_w;
  std::vector<real> lap_w;
  std::vector<Vec2> G, lapV, v_new, odd_even;
  std::vector<Mat2> gradV;
  std::vector<real> div_v, rc, rho, p, p_wall;
  std::vector<GeometryAt> geo;
  std::vector<WallPressureOutcome> outcome;
};

/// Runs every neighbour sweep of a step for all particles over context `c` (whose pair arrays
/// have `slots` entries), as the CPU loops and the GPU kernels do.
Fields run_sweeps(SweepContext c, std::size_t slots, const Particles& P, const std::vector<Vec2>& v,
                  const std::vector<real>& rho, const std::vector<real>& p, const StageParams& s, real d0) {
  const std::size_t n = P.size();
  Fields f;
  f.grad_w.assign(slots, Vec2{});
  f.lap_w.assign(slots, 0);
  f.geo.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    f.geo[i] = geometry_at(c, i, d0, f.grad_w.data(), f.lap_w.data());
  }
  c.grad_w = f.grad_w.data();
  c.lap_w = f.lap_w.data();
  f.gradV.resize(n);
  f.lapV.resize(n);
  f.div_v.resize(n);
  f.G.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    store_velocity_derivatives(c, i, v.data(), f.gradV.data(), f.lapV.data(), f.div_v.data());
    f.G[i] = pressure_gradient_at(c, i, p.data(), rho.data());
  }
  f.rc.resize(n);
  f.v_new = v;
  f.odd_even.assign(n, Vec2{});
  for (std::size_t i = 0; i < n; ++i)
    rhie_chow_and_momentum_at(c, i, p.data(), rho.data(), f.G.data(), f.gradV.data(), f.lapV.data(), v.data(),
                              s, f.rc.data(), f.v_new.data(), f.odd_even.data());
  f.rho = rho;
  f.p = p;
  for (std::size_t i = 0; i < n; ++i)
    derivatives_and_continuity_at(c, i, f.v_new.data(), rho.data(), f.rc.data(), s, f.gradV.data(), f.lapV.data(),
                                  f.div_v.data(), f.rho.data(), f.p.data());
  f.p_wall = f.p;
  f.outcome.assign(P.n_boundary, WallPressureOutcome::Kept);
  for (std::size_t i = 0; i < P.n_boundary; ++i)
    if (P.kind[i] == Kind::Boundary)
      f.outcome[i] = wall_pressure_at(c, i, f.p.data(), f.rho.data(), P.normal[i], P.acc[i], s.nu * f.lapV[i], s.f,
                                      wall_pressure_min_den(s.rho0, c.kernel.h), s.void_distance, s.p0, f.p_wall[i]);
  return f;
}

struct LayoutReport {
  std::size_t particles = 0, pairs = 0, extrapolated = 0, dummies = 0;
};

/// Builds the scene of `cs`, perturbs its fields with a seeded generator, and compares the CPU
/// list and sweeps with the GPU-style list and ELL sweeps, bitwise.
void compare_layouts(const Case& cs, std::uint64_t seed, LayoutReport& rep) {
  Scene sc = build_scene(cs);
  Particles& P = sc.particles;
  const std::size_t n = P.size();
  WendlandC2 kernel(sc.params.h);
  // A disordered state: positions jittered by 0.2 d0 (fluid only), velocity, density, pressure.
  SplitMix64 rng(seed);
  for (std::size_t i = P.n_boundary; i < n; ++i)
    P.x[i] = sc.domain.wrap(P.x[i] + 0.2 * sc.params.d0 * Vec2{rng.symmetric(), rng.symmetric()});
  std::vector<Vec2> v(n);
  std::vector<real> rho(n), p(n);
  for (std::size_t i = 0; i < n; ++i) {
    v[i] = 1e-3 * Vec2{rng.symmetric(), rng.symmetric()};
    rho[i] = 1000 * (1 + 0.01 * rng.symmetric());
    p[i] = 5 * rng.symmetric();
  }
  std::vector<real> vol(n);
  for (std::size_t i = 0; i < n; ++i) vol[i] = P.m[i] / rho[i];
  StageParams s;
  s.dt = 1e-5;
  s.g_dt = 1e-5;
  s.nu = 1e-5;
  s.f = {0, -9.81};
  s.rho0 = 1000;
  s.c = 1;
  s.kappa = 0.005 * s.c * kernel.h;  // the odd-even damping, on (its acceleration is compared too)
  s.void_distance = kVoidDistance * sc.params.d0;
  s.single_layer = sc.params.single_layer;

  // The CPU list (counting-sort binning, CSR).
  CellGrid grid;
  grid.setup(sc.domain, kernel.h);
  NeighborList nl;
  build_neighbor_list(P.x, sc.domain, kernel, grid, nl);
  // The GPU's list, with a padded stride so that an index computed with n instead of the
  // stride would read the padding.
  const std::size_t stride = n + 7;
  const EllList ell = gpu_style_list(P.x, grid.geometry(), kernel.h, stride);

  rep.particles = n;
  rep.pairs = nl.pair_count();
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t np = nl.start[i + 1] - nl.start[i];
    EXPECT_EQ(ell.count[i], np) << "pair count of particle " << i;
    if (ell.count[i] != np) return;
    for (std::uint32_t q = 0; q < np; ++q)
      ASSERT_EQ(ell.j[q * stride + i], nl.j[nl.start[i] + q]) << "neighbour " << q << " of particle " << i;
  }

  SweepContext base;
  base.domain = sc.domain;
  base.kernel = kernel;
  base.n = n;
  base.nb = P.n_boundary;
  base.x = P.x.data();
  base.vol = vol.data();
  base.kind = P.kind.data();
  base.group = P.group.data();
  base.fatehi_manzari = sc.params.fatehi_manzari;
  SweepContext csr = base, el = base;
  csr.start = nl.start.data();
  csr.j = nl.j.data();
  el.start = nullptr;
  el.count = ell.count.data();
  el.stride = stride;
  el.j = ell.j.data();

  const Fields a = run_sweeps(csr, nl.pair_count(), P, v, rho, p, s, sc.params.d0);
  const Fields b = run_sweeps(el, ell.j.size(), P, v, rho, p, s, sc.params.d0);
  for (std::size_t i = 0; i < n; ++i) {
    const GeometryAt &ga = a.geo[i], &gb = b.geo[i];
    ASSERT_TRUE(same_bits(ga.B, gb.B) && same_bits(ga.Bhat, gb.Bhat) && same_bits(ga.rbar, gb.rbar) &&
                same_bits(ga.normal_sum, gb.normal_sum) && same_bits(ga.shift_direction, gb.shift_direction) &&
                same_bits(ga.lap_esum, gb.lap_esum) && ga.B_ok == gb.B_ok && ga.Bhat_ok == gb.Bhat_ok &&
                ga.near.a == gb.near.a && ga.near.b == gb.near.b)
        << "geometry of particle " << i;
    for (std::uint32_t q = 0; q < ell.count[i]; ++q) {
      const std::size_t kc = nl.start[i] + q, ke = q * stride + i;
      ASSERT_TRUE(same_bits(a.grad_w[kc], b.grad_w[ke]) && same_bits(a.lap_w[kc], b.lap_w[ke]))
          << "pair weights " << q << " of particle " << i;
    }
    ASSERT_TRUE(same_bits(a.gradV[i], b.gradV[i]) && same_bits(a.lapV[i], b.lapV[i]) &&
                same_bits(a.div_v[i], b.div_v[i]) && same_bits(a.G[i], b.G[i]) &&
                same_bits(a.rc[i], b.rc[i]) && same_bits(a.v_new[i], b.v_new[i]) &&
                same_bits(a.odd_even[i], b.odd_even[i]) && same_bits(a.rho[i], b.rho[i]) &&
                same_bits(a.p[i], b.p[i]))
        << "derivatives or stages of particle " << i;
    if (i < P.n_boundary) {
      ASSERT_EQ(a.outcome[i], b.outcome[i]) << "wall pressure outcome of particle " << i;
      ASSERT_TRUE(same_bits(a.p_wall[i], b.p_wall[i])) << "wall pressure of particle " << i;
      rep.extrapolated += a.outcome[i] == WallPressureOutcome::Extrapolated ? 1 : 0;
      rep.dummies += P.kind[i] == Kind::Dummy ? 1 : 0;
    }
  }
}

TEST(SweepLayouts, GpuListAndEllSweepsMatchTheCpuAroundASharpBody) {
  // A closed box with a 72-degree triangle: walls, box corners, a moving body's surface and
  // the corners where P.20 is extrapolated.
  Case c = cases::closed_box(0.006, 0.006, 2e-4);
  BodySpec b;
  b.name = "triangle";
  b.shape = BodyShape::Polygon;
  b.vertices = {{0.002, 0.002}, {0.004, 0.002}, {0.003, 0.005}};
  b.density = 1250;
  c.bodies.push_back(b);
  LayoutReport r;
  compare_layouts(c, 7, r);
  ASSERT_FALSE(HasFatalFailure());
  EXPECT_GT(r.pairs, 15 * r.particles);
  EXPECT_GT(r.extrapolated, 0u) << "the case must take the extrapolation path of wall_pressure_at";
}

TEST(SweepLayouts, GpuListAndEllSweepsMatchTheCpuInAPeriodicChannelWithDummyWalls) {
  // Periodic in x (minimum image across the seam), the dummy-particle baseline boundary and
  // the Morris Laplacian: the other branches of the sweeps.
  Case c = cases::startup_channel(20, 1e-5, 0);
  c.boundary = BoundaryModel::Dummy;
  c.laplacian = LaplacianScheme::Morris;
  LayoutReport r;
  compare_layouts(c, 11, r);
  ASSERT_FALSE(HasFatalFailure());
  EXPECT_GT(r.dummies, 0u);
  EXPECT_GT(r.pairs, 15 * r.particles);
}

}  // namespace
}  // namespace particula
