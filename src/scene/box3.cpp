#include "particula/scene/box3.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

namespace particula {

namespace {

// The volumes of wall particles in lattice cells (docs/method.md, "Three dimensions"): a face
// particle d0 dA, one cell, as a 2D wall particle's d0 ds, so that the zeroth kernel moment
// s = sum_j w_j gradW_ij of the fluid particle next to the face nearly vanishes (0.007 / d0 at
// h = 2.6 d0 on the regular lattice; half a cell gives 0.23 / d0, and a particle pushed against
// the wall would be drawn in rather than compressed); an edge particle one cell (s of the fluid
// particle at the edge 0.015 / d0), a corner particle 1.25 cells (0.004 / d0 at the corner),
// the 3D counterpart of the 2D box corner's volume factor (M.6).
constexpr real kFaceVolume = 1, kEdgeVolume = 1, kCornerVolume = 1.25;

real component(Vec3 v, int a) { return a == 0 ? v.x : (a == 1 ? v.y : v.z); }

Vec3 with(Vec3 v, int a, real value) {
  if (a == 0) v.x = value;
  if (a == 1) v.y = value;
  if (a == 2) v.z = value;
  return v;
}

}  // namespace

BoxScene3 build_box3(const BoxSpec3& spec) {
  BoxScene3 s;
  s.domain.lo = spec.lo;
  s.domain.hi = spec.hi;
  s.domain.periodic_x = spec.periodic[0];
  s.domain.periodic_y = spec.periodic[1];
  s.domain.periodic_z = spec.periodic[2];
  const Vec3 size = spec.hi - spec.lo;
  int n[3];
  real dx[3];
  for (int a = 0; a < 3; ++a) {
    n[a] = static_cast<int>(std::lround(component(size, a) / spec.d0));
    if (n[a] < 1) throw std::invalid_argument("build_box3: the box is thinner than one particle spacing");
    dx[a] = component(size, a) / n[a];
  }
  s.spacing = {dx[0], dx[1], dx[2]};
  const real cell = dx[0] * dx[1] * dx[2];
  Particles3& P = s.particles;
  const auto add = [&](Vec3 x, real volume, Vec3 normal, real ds, std::int32_t group, Kind kind, Vec3 v) {
    P.x.push_back(x);
    P.v.push_back(v);
    P.rho.push_back(spec.rho0);
    P.p.push_back(spec.p0);
    P.m.push_back(spec.rho0 * volume);
    P.kind.push_back(kind);
    P.group.push_back(group);
    P.id.push_back(static_cast<std::int64_t>(P.id.size()));
    if (kind != Kind::Boundary) return;
    P.local.push_back(x);
    P.normal_local.push_back(normal);
    P.normal.push_back(normal);
    P.ds.push_back(ds);
    P.acc.push_back({});
    P.wedge.push_back(0);
    P.source.push_back(-1);
  };
  const auto centre = [&](int a, int i) { return component(spec.lo, a) + (i + 0.5) * dx[a]; };
  const auto side = [&](int a, bool far) { return far ? component(spec.hi, a) : component(spec.lo, a); };
  const auto face_group = [&](int a, bool far) { return static_cast<std::int32_t>(2 * a + (far ? 1 : 0)); };
  for (int f = 0; f < 6; ++f)
    if (component(spec.face_velocity[f], f / 2) != 0)
      throw std::invalid_argument("build_box3: a face may only move along itself");
  // the common velocity of the faces (a, far_a) and (b, far_b), or rest
  const auto shared = [&](int a, bool far_a, int b, bool far_b) {
    const Vec3 va = spec.face_velocity[face_group(a, far_a)], vb = spec.face_velocity[face_group(b, far_b)];
    return va.x == vb.x && va.y == vb.y && va.z == vb.z ? va : Vec3{};
  };
  // faces: axis a at lo or hi, the other two on the cell centres
  for (int a = 0; a < 3; ++a) {
    if (spec.periodic[a]) continue;
    const int b = (a + 1) % 3, e = (a + 2) % 3;
    for (const bool far : {false, true})
      for (int j = 0; j < n[b]; ++j)
        for (int k = 0; k < n[e]; ++k) {
          const Vec3 x = with(with(with(Vec3{}, a, side(a, far)), b, centre(b, j)), e, centre(e, k));
          const Vec3 normal = with(Vec3{}, a, far ? -1 : 1);
          add(x, kFaceVolume * cell, normal, dx[b] * dx[e], face_group(a, far), Kind::Boundary,
              spec.face_velocity[face_group(a, far)]);
        }
  }
  // edges: axes b and e closed (at lo or hi), axis a on the cell centres
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, e = (a + 2) % 3;
    if (spec.periodic[b] || spec.periodic[e]) continue;
    for (int corner = 0; corner < 4; ++corner) {
      const bool far_b = corner & 1, far_e = corner & 2;
      const Vec3 normal = with(with(Vec3{}, b, far_b ? -1 : 1), e, far_e ? -1 : 1) / std::sqrt(2.0);
      const std::int32_t group = face_group(std::min(b, e), std::min(b, e) == b ? far_b : far_e);
      for (int i = 0; i < n[a]; ++i) {
        const Vec3 x = with(with(with(Vec3{}, a, centre(a, i)), b, side(b, far_b)), e, side(e, far_e));
        add(x, kEdgeVolume * cell, normal, 0, group, Kind::Boundary, shared(b, far_b, e, far_e));
      }
    }
  }
  // corners: all three axes closed
  if (!spec.periodic[0] && !spec.periodic[1] && !spec.periodic[2])
    for (int corner = 0; corner < 8; ++corner) {
      const bool far[3] = {(corner & 1) != 0, (corner & 2) != 0, (corner & 4) != 0};
      const Vec3 x{side(0, far[0]), side(1, far[1]), side(2, far[2])};
      const Vec3 normal =
          Vec3{far[0] ? -1.0 : 1.0, far[1] ? -1.0 : 1.0, far[2] ? -1.0 : 1.0} / std::sqrt(3.0);
      const Vec3 v = shared(0, far[0], 1, far[1]);
      const Vec3 w = shared(1, far[1], 2, far[2]);
      add(x, kCornerVolume * cell, normal, 0, face_group(0, far[0]), Kind::Boundary,
          v.x == w.x && v.y == w.y && v.z == w.z ? v : Vec3{});
    }
  // the fixed solids' surfaces
  for (std::size_t k = 0; k < spec.solids.size(); ++k) {
    const FixedSolid3& solid = spec.solids[k];
    const Quat q = normalized(solid.orientation);
    const Mat3 R = rotation_matrix(q);
    for (const SurfaceSample3& smp : solid.shape.sample_surface(spec.d0))
      add(s.domain.wrap(solid.position + R * smp.x), kFaceVolume * smp.dA * spec.d0, R * smp.normal, smp.dA,
          static_cast<std::int32_t>(6 + k), Kind::Boundary, {});
  }
  P.n_boundary = P.x.size();
  // the fluid lattice, outside the solids by d0 / 2 at least (the solids' own distance, taken to
  // the nearest periodic image of their positions)
  const auto solid_distance = [&](Vec3 x) {
    real d = std::numeric_limits<real>::infinity();
    for (const FixedSolid3& solid : spec.solids) {
      const Vec3 r = s.domain.separation(x, solid.position);
      d = std::min(d, solid.shape.signed_distance(rotate_back(normalized(solid.orientation), r)));
    }
    return d;
  };
  // The fluid's masses fill the region outside the solids exactly, as in 2D: a cell cut by a
  // solid surface holds its part outside (kSubcells^3 midpoints), and the part of a cell whose
  // particle is left out goes to the nearest kept particle among the 5 x 5 x 5 cells round it.
  constexpr int kSubcells = 6;
  const real half_diagonal = 0.5 * std::sqrt(dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]);
  const auto outside_fraction = [&](Vec3 x, real d) {
    if (d >= half_diagonal) return real(1);
    if (d <= -half_diagonal) return real(0);
    int out = 0;
    for (int a = 0; a < kSubcells; ++a)
      for (int b = 0; b < kSubcells; ++b)
        for (int e = 0; e < kSubcells; ++e) {
          const Vec3 q{x.x + ((a + 0.5) / kSubcells - 0.5) * dx[0],
                       x.y + ((b + 0.5) / kSubcells - 0.5) * dx[1],
                       x.z + ((e + 0.5) / kSubcells - 0.5) * dx[2]};
          out += solid_distance(q) > 0 ? 1 : 0;
        }
    return static_cast<real>(out) / (kSubcells * kSubcells * kSubcells);
  };
  std::vector<std::int64_t> particle_of(static_cast<std::size_t>(n[0]) * n[1] * n[2], -1);
  std::vector<real> left_over(particle_of.size(), 0);
  const auto cell_index = [&](int i, int j, int k) {
    return (static_cast<std::size_t>(i) * n[1] + j) * n[2] + k;
  };
  for (int i = 0; i < n[0]; ++i)
    for (int j = 0; j < n[1]; ++j)
      for (int k = 0; k < n[2]; ++k) {
        const Vec3 x{centre(0, i), centre(1, j), centre(2, k)};
        const real d = spec.solids.empty() ? std::numeric_limits<real>::infinity() : solid_distance(x);
        const real volume = outside_fraction(x, d) * cell;
        if (d >= 0.5 * spec.d0) {
          particle_of[cell_index(i, j, k)] = static_cast<std::int64_t>(P.size());
          add(x, volume, {}, 0, -1, Kind::Fluid, {});
        } else {
          left_over[cell_index(i, j, k)] = volume;
        }
      }
  // a left-out cell's fluid to the nearest kept particle (periodic axes wrap, closed ones end)
  const auto wrap_index = [&](int a, int i) {
    if (i >= 0 && i < n[a]) return i;
    return spec.periodic[a] ? (i + n[a]) % n[a] : -1;
  };
  for (int i = 0; i < n[0]; ++i)
    for (int j = 0; j < n[1]; ++j)
      for (int k = 0; k < n[2]; ++k) {
        const real volume = left_over[cell_index(i, j, k)];
        if (!(volume > 0)) continue;
        const Vec3 x{centre(0, i), centre(1, j), centre(2, k)};
        std::int64_t best = -1;
        real best_d2 = std::numeric_limits<real>::infinity();
        for (int di = -2; di <= 2; ++di)
          for (int dj = -2; dj <= 2; ++dj)
            for (int dk = -2; dk <= 2; ++dk) {
              const int ii = wrap_index(0, i + di), jj = wrap_index(1, j + dj), kk = wrap_index(2, k + dk);
              if (ii < 0 || jj < 0 || kk < 0) continue;
              const std::int64_t q = particle_of[cell_index(ii, jj, kk)];
              if (q < 0) continue;
              const real d2 = norm2(s.domain.separation(P.x[static_cast<std::size_t>(q)], x));
              if (d2 < best_d2) best_d2 = d2, best = q;
            }
        if (best < 0)
          throw std::invalid_argument("build_box3: fluid cut off by solids with no particle to hold it");
        P.m[static_cast<std::size_t>(best)] += spec.rho0 * volume;
      }
  P.next_id = static_cast<std::int64_t>(P.size());
  return s;
}

}  // namespace particula
