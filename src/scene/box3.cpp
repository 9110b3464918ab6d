#include "particula/scene/box3.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <utility>
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

/// Builds the scene of a spec in the order of its particles: walls, solids' surfaces, fluid.
class BoxBuilder {
 public:
  explicit BoxBuilder(const BoxSpec3& spec) : spec_(spec) {
    s_.domain.lo = spec.lo;
    s_.domain.hi = spec.hi;
    s_.domain.periodic_x = spec.periodic[0];
    s_.domain.periodic_y = spec.periodic[1];
    s_.domain.periodic_z = spec.periodic[2];
    const Vec3 size = spec.hi - spec.lo;
    for (int a = 0; a < 3; ++a) {
      n_[a] = static_cast<int>(std::lround(component(size, a) / spec.d0));
      if (n_[a] < 1) throw std::invalid_argument("build_box3: the box is thinner than one particle spacing");
      dx_[a] = component(size, a) / n_[a];
    }
    s_.spacing = {dx_[0], dx_[1], dx_[2]};
    cell_ = dx_[0] * dx_[1] * dx_[2];
    for (int f = 0; f < 6; ++f)
      if (component(spec.face_velocity[f], f / 2) != 0)
        throw std::invalid_argument("build_box3: a face may only move along itself");
  }

  /// Each closed face: axis a at lo or hi, the other two on the cell centres.
  void add_faces() {
    for (int a = 0; a < 3; ++a) {
      if (spec_.periodic[a]) continue;
      const int b = (a + 1) % 3, e = (a + 2) % 3;
      for (const bool far : {false, true})
        for (int j = 0; j < n_[b]; ++j)
          for (int k = 0; k < n_[e]; ++k) {
            const Vec3 x = with(with(with(Vec3{}, a, side(a, far)), b, centre(b, j)), e, centre(e, k));
            const Vec3 normal = with(Vec3{}, a, far ? -1 : 1);
            add(x, kFaceVolume * cell_, normal, dx_[b] * dx_[e], face_group(a, far), Kind::Boundary,
                spec_.face_velocity[face_group(a, far)]);
          }
    }
  }

  /// Each edge where two closed faces meet: axes b and e at lo or hi, axis a on the cell centres.
  void add_edges() {
    for (int a = 0; a < 3; ++a) {
      const int b = (a + 1) % 3, e = (a + 2) % 3;
      if (spec_.periodic[b] || spec_.periodic[e]) continue;
      for (int corner = 0; corner < 4; ++corner) {
        const bool far_b = corner & 1, far_e = corner & 2;
        const Vec3 normal = with(with(Vec3{}, b, far_b ? -1 : 1), e, far_e ? -1 : 1) / std::sqrt(2.0);
        const std::int32_t group = face_group(std::min(b, e), std::min(b, e) == b ? far_b : far_e);
        for (int i = 0; i < n_[a]; ++i) {
          const Vec3 x = with(with(with(Vec3{}, a, centre(a, i)), b, side(b, far_b)), e, side(e, far_e));
          add(x, kEdgeVolume * cell_, normal, 0, group, Kind::Boundary, shared(b, far_b, e, far_e));
        }
      }
    }
  }

  /// Each corner where three closed faces meet.
  void add_corners() {
    if (spec_.periodic[0] || spec_.periodic[1] || spec_.periodic[2]) return;
    for (int corner = 0; corner < 8; ++corner) {
      const bool far[3] = {(corner & 1) != 0, (corner & 2) != 0, (corner & 4) != 0};
      const Vec3 x{side(0, far[0]), side(1, far[1]), side(2, far[2])};
      const Vec3 normal =
          Vec3{far[0] ? -1.0 : 1.0, far[1] ? -1.0 : 1.0, far[2] ? -1.0 : 1.0} / std::sqrt(3.0);
      const Vec3 v = shared(0, far[0], 1, far[1]), w = shared(1, far[1], 2, far[2]);
      add(x, kCornerVolume * cell_, normal, 0, face_group(0, far[0]), Kind::Boundary,
          same(v, w) ? v : Vec3{});
    }
  }

  /// The fixed solids' surface samples; the boundary block ends with them.
  void add_solid_surfaces() {
    for (std::size_t k = 0; k < spec_.solids.size(); ++k) {
      const FixedSolid3& solid = spec_.solids[k];
      const Mat3 R = rotation_matrix(normalized(solid.orientation));
      for (const SurfaceSample3& smp : solid.shape.sample_surface(spec_.d0))
        add(s_.domain.wrap(solid.position + R * smp.x), kFaceVolume * smp.dA * spec_.d0, R * smp.normal,
            smp.dA, static_cast<std::int32_t>(6 + k), Kind::Boundary, {});
    }
    s_.particles.n_boundary = s_.particles.size();
  }

  /// The fluid lattice d0 / 2 clear of the solids, its masses filling the region outside them
  /// exactly, as in 2D: a cell cut by a solid surface holds its part outside (kSubcells^3
  /// midpoints), and the part of a cell whose particle is left out goes to the nearest kept
  /// particle (nearest_kept).
  void fill_fluid() {
    particle_of_.assign(static_cast<std::size_t>(n_[0]) * n_[1] * n_[2], -1);
    std::vector<real> left_over(particle_of_.size(), 0);
    for (int i = 0; i < n_[0]; ++i)
      for (int j = 0; j < n_[1]; ++j)
        for (int k = 0; k < n_[2]; ++k) {
          const Vec3 x = lattice_point(i, j, k);
          const real d = solid_distance(x), volume = outside_fraction(x, d) * cell_;
          if (d >= 0.5 * spec_.d0) {
            particle_of_[cell_index(i, j, k)] = static_cast<std::int64_t>(s_.particles.size());
            add(x, volume, {}, 0, -1, Kind::Fluid, {});
          } else {
            left_over[cell_index(i, j, k)] = volume;
          }
        }
    for (int i = 0; i < n_[0]; ++i)
      for (int j = 0; j < n_[1]; ++j)
        for (int k = 0; k < n_[2]; ++k) {
          const real volume = left_over[cell_index(i, j, k)];
          if (volume > 0) s_.particles.m[nearest_kept(i, j, k)] += spec_.rho0 * volume;
        }
    s_.particles.next_id = static_cast<std::int64_t>(s_.particles.size());
  }

  BoxScene3 take() { return std::move(s_); }

 private:
  static constexpr int kSubcells = 6;

  void add(Vec3 x, real volume, Vec3 normal, real ds, std::int32_t group, Kind kind, Vec3 v) {
    Particles3& P = s_.particles;
    P.x.push_back(x);
    P.v.push_back(v);
    P.rho.push_back(spec_.rho0);
    P.p.push_back(spec_.p0);
    P.m.push_back(spec_.rho0 * volume);
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
  }

  real centre(int a, int i) const { return component(spec_.lo, a) + (i + 0.5) * dx_[a]; }
  Vec3 lattice_point(int i, int j, int k) const { return {centre(0, i), centre(1, j), centre(2, k)}; }
  real side(int a, bool far) const { return far ? component(spec_.hi, a) : component(spec_.lo, a); }
  static std::int32_t face_group(int a, bool far) { return static_cast<std::int32_t>(2 * a + (far ? 1 : 0)); }
  static bool same(Vec3 a, Vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
  /// The common velocity of the faces (a, far_a) and (b, far_b), or rest.
  Vec3 shared(int a, bool far_a, int b, bool far_b) const {
    const Vec3 va = spec_.face_velocity[face_group(a, far_a)], vb = spec_.face_velocity[face_group(b, far_b)];
    return same(va, vb) ? va : Vec3{};
  }
  std::size_t cell_index(int i, int j, int k) const {
    return (static_cast<std::size_t>(i) * n_[1] + j) * n_[2] + k;
  }

  /// The signed distance to the nearest solid (its own, taken to the nearest periodic image of
  /// its position); infinite without solids.
  real solid_distance(Vec3 x) const {
    real d = std::numeric_limits<real>::infinity();
    for (const FixedSolid3& solid : spec_.solids) {
      const Vec3 r = s_.domain.separation(x, solid.position);
      d = std::min(d, solid.shape.signed_distance(rotate_back(normalized(solid.orientation), r)));
    }
    return d;
  }

  /// The part of the cell centred at x (at distance d from the solids) outside them.
  real outside_fraction(Vec3 x, real d) const {
    const real half_diagonal = 0.5 * std::sqrt(dx_[0] * dx_[0] + dx_[1] * dx_[1] + dx_[2] * dx_[2]);
    if (d >= half_diagonal) return 1;
    if (d <= -half_diagonal) return 0;
    int out = 0;
    for (int a = 0; a < kSubcells; ++a)
      for (int b = 0; b < kSubcells; ++b)
        for (int e = 0; e < kSubcells; ++e) {
          const Vec3 q{x.x + ((a + 0.5) / kSubcells - 0.5) * dx_[0],
                       x.y + ((b + 0.5) / kSubcells - 0.5) * dx_[1],
                       x.z + ((e + 0.5) / kSubcells - 0.5) * dx_[2]};
          out += solid_distance(q) > 0 ? 1 : 0;
        }
    return static_cast<real>(out) / (kSubcells * kSubcells * kSubcells);
  }

  /// The lattice index i + di along axis a, wrapped on a periodic axis, -1 past a closed one.
  int wrap_index(int a, int i) const {
    if (i >= 0 && i < n_[a]) return i;
    return spec_.periodic[a] ? (i + n_[a]) % n_[a] : -1;
  }

  /// The kept fluid particle nearest to cell (i, j, k) among the 5 x 5 x 5 cells round it (the
  /// first in lattice order at equal distance).
  std::size_t nearest_kept(int i, int j, int k) const {
    const Vec3 x = lattice_point(i, j, k);
    std::int64_t best = -1;
    real best_d2 = std::numeric_limits<real>::infinity();
    for (int di = -2; di <= 2; ++di)
      for (int dj = -2; dj <= 2; ++dj)
        for (int dk = -2; dk <= 2; ++dk) {
          const int ii = wrap_index(0, i + di), jj = wrap_index(1, j + dj), kk = wrap_index(2, k + dk);
          if (ii < 0 || jj < 0 || kk < 0) continue;
          const std::int64_t q = particle_of_[cell_index(ii, jj, kk)];
          if (q < 0) continue;
          const real d2 = norm2(s_.domain.separation(s_.particles.x[static_cast<std::size_t>(q)], x));
          if (d2 < best_d2) best_d2 = d2, best = q;
        }
    if (best < 0)
      throw std::invalid_argument("build_box3: fluid cut off by solids with no particle to hold it");
    return static_cast<std::size_t>(best);
  }

  const BoxSpec3& spec_;
  BoxScene3 s_;
  int n_[3] = {0, 0, 0};
  real dx_[3] = {0, 0, 0};
  real cell_ = 0;
  std::vector<std::int64_t> particle_of_;  // the fluid particle of each lattice cell, -1: left out
};

}  // namespace

BoxScene3 build_box3(const BoxSpec3& spec) {
  BoxBuilder b(spec);
  b.add_faces();  // the boundary block: the walls,
  b.add_edges();
  b.add_corners();
  b.add_solid_surfaces();  // then the solids' surfaces,
  b.fill_fluid();          // then the fluid
  return b.take();
}

}  // namespace particula
