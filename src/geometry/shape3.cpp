// 3D rigid-body shapes (geometry/shape3.hpp).
#include "particula/geometry/shape3.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <unordered_map>
#include <utility>

namespace particula {

namespace {

/// Samples along an interval: max(min_count, round(length / d0)).
int count_along(real length, real d0, int min_count = 1) {
  return std::max(min_count, static_cast<int>(std::lround(length / d0)));
}

// ---- the distance to an ellipse and an ellipsoid (Eberly, "Distance from a point to an
// ellipse, an ellipsoid, or a hyperellipsoid", 2013): the closest point from the root of a
// monotone function, found by bisection to the last bit, for semi-axes e0 >= e1 (>= e2) and a
// point in the first quadrant (octant).

real robust_length(real a, real b, real c = 0) {
  const real m = std::max({std::fabs(a), std::fabs(b), std::fabs(c)});
  if (m == 0) return 0;
  return m * std::sqrt((a / m) * (a / m) + (b / m) * (b / m) + (c / m) * (c / m));
}

template <class G>
real bisect_root(real s0, real s1, G g) {
  for (int i = 0; i < 2200; ++i) {
    const real s = 0.5 * (s0 + s1);
    if (s == s0 || s == s1) return s;
    const real v = g(s);
    if (v > 0)
      s0 = s;
    else if (v < 0)
      s1 = s;
    else
      return s;
  }
  return 0.5 * (s0 + s1);
}

/// The closest point x on the ellipse (e0 >= e1) to y (y0, y1 >= 0).
std::array<real, 2> closest_on_ellipse(real e0, real e1, real y0, real y1) {
  if (y1 > 0) {
    if (y0 > 0) {
      const real z0 = y0 / e0, z1 = y1 / e1, g = z0 * z0 + z1 * z1 - 1;
      if (g == 0) return {y0, y1};
      const real r0 = (e0 / e1) * (e0 / e1), n0 = r0 * z0;
      const real s = bisect_root(z1 - 1, g < 0 ? 0 : robust_length(n0, z1) - 1, [&](real t) {
        const real a = n0 / (t + r0), b = z1 / (t + 1);
        return a * a + b * b - 1;
      });
      return {r0 * y0 / (s + r0), y1 / (s + 1)};
    }
    return {0, e1};
  }
  const real numer0 = e0 * y0, denom0 = e0 * e0 - e1 * e1;
  if (numer0 < denom0) {
    const real xde0 = numer0 / denom0;
    return {e0 * xde0, e1 * std::sqrt(std::max(0.0, 1 - xde0 * xde0))};
  }
  return {e0, 0};
}

/// The closest point x on the ellipsoid (e0 >= e1 >= e2) to y (y >= 0 componentwise).
std::array<real, 3> closest_on_ellipsoid(real e0, real e1, real e2, real y0, real y1, real y2) {
  if (y2 > 0) {
    if (y1 > 0) {
      if (y0 > 0) {
        const real z0 = y0 / e0, z1 = y1 / e1, z2 = y2 / e2, g = z0 * z0 + z1 * z1 + z2 * z2 - 1;
        if (g == 0) return {y0, y1, y2};
        const real r0 = (e0 / e2) * (e0 / e2), r1 = (e1 / e2) * (e1 / e2), n0 = r0 * z0, n1 = r1 * z1;
        const real s = bisect_root(z2 - 1, g < 0 ? 0 : robust_length(n0, n1, z2) - 1, [&](real t) {
          const real a = n0 / (t + r0), b = n1 / (t + r1), c = z2 / (t + 1);
          return a * a + b * b + c * c - 1;
        });
        return {r0 * y0 / (s + r0), r1 * y1 / (s + r1), y2 / (s + 1)};
      }
      const auto x = closest_on_ellipse(e1, e2, y1, y2);
      return {0, x[0], x[1]};
    }
    if (y0 > 0) {
      const auto x = closest_on_ellipse(e0, e2, y0, y2);
      return {x[0], 0, x[1]};
    }
    return {0, 0, e2};
  }
  const real denom0 = e0 * e0 - e2 * e2, denom1 = e1 * e1 - e2 * e2, numer0 = e0 * y0, numer1 = e1 * y1;
  if (numer0 < denom0 && numer1 < denom1) {
    const real xde0 = numer0 / denom0, xde1 = numer1 / denom1, discr = 1 - xde0 * xde0 - xde1 * xde1;
    if (discr > 0) return {e0 * xde0, e1 * xde1, e2 * std::sqrt(discr)};
  }
  const auto x = closest_on_ellipse(e0, e1, y0, y1);
  return {x[0], x[1], 0};
}

/// The area element |x_theta x x_phi| of the ellipsoid x = (a sin t cos f, b sin t sin f, c cos t).
real ellipsoid_area_element(Vec3 e, real t, real f) {
  const real st = std::sin(t), ct = std::cos(t), sf = std::sin(f), cf = std::cos(f);
  return st * std::sqrt(e.y * e.y * e.z * e.z * st * st * cf * cf +
                        e.x * e.x * e.z * e.z * st * st * sf * sf + e.x * e.x * e.y * e.y * ct * ct);
}

/// The area of the ellipsoid's patch [t0, t1] x [f0, f1] by 8 x 8 Gauss-Legendre points (the
/// element is smooth: relative error far below round-off at cells of about d0).
real ellipsoid_patch_area(Vec3 e, real t0, real t1, real f0, real f1) {
  static constexpr real xg[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                                 -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                                 0.7966664774136267,  0.9602898564975363};
  static constexpr real wg[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                 0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                 0.2223810344533745, 0.1012285362903763};
  real s = 0;
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j)
      s += wg[i] * wg[j] *
           ellipsoid_area_element(e, 0.5 * (t0 + t1) + 0.5 * (t1 - t0) * xg[i],
                                  0.5 * (f0 + f1) + 0.5 * (f1 - f0) * xg[j]);
  return 0.25 * (t1 - t0) * (f1 - f0) * s;
}

/// The perimeter of an ellipse (Ramanujan's second approximation: for sample counts only).
real ellipse_perimeter(real a, real b) {
  const real h = (a - b) * (a - b) / ((a + b) * (a + b));
  return M_PI * (a + b) * (1 + 3 * h / (10 + std::sqrt(4 - 3 * h)));
}

std::vector<SurfaceSample3> sample_sphere(real R, real d0) {
  std::vector<SurfaceSample3> out;
  const int nt = count_along(M_PI * R, d0, 2);
  for (int k = 0; k < nt; ++k) {
    // the band between the polar angles k pi / nt and (k + 1) pi / nt: area 2 pi R (z_k - z_k+1)
    const real z0 = R * std::cos(k * M_PI / nt), z1 = R * std::cos((k + 1) * M_PI / nt);
    const real band = 2 * M_PI * R * (z0 - z1);
    const int nf = std::max(1, static_cast<int>(std::lround(band / (d0 * d0))));
    const real z = 0.5 * (z0 + z1), rho = std::sqrt(std::max(0.0, R * R - z * z));
    for (int j = 0; j < nf; ++j) {
      const real f = 2 * M_PI * (j + 0.5 * (1 + k % 2)) / nf;
      const Vec3 n{rho * std::cos(f) / R, rho * std::sin(f) / R, z / R};
      out.push_back({R * n, n, band / nf});
    }
  }
  return out;
}

std::vector<SurfaceSample3> sample_ellipsoid(Vec3 e, real d0) {
  std::vector<SurfaceSample3> out;
  const int nt = count_along(0.5 * ellipse_perimeter(std::max(e.x, e.y), e.z), d0, 2);
  for (int k = 0; k < nt; ++k) {
    const real t0 = k * M_PI / nt, t1 = (k + 1) * M_PI / nt, t = 0.5 * (t0 + t1);
    const int nf = count_along(ellipse_perimeter(e.x * std::sin(t), e.y * std::sin(t)), d0, 3);
    for (int j = 0; j < nf; ++j) {
      const real shift = 0.5 * (k % 2);
      const real f0 = 2 * M_PI * (j + shift) / nf, f1 = 2 * M_PI * (j + 1 + shift) / nf, f = 0.5 * (f0 + f1);
      const Vec3 x{e.x * std::sin(t) * std::cos(f), e.y * std::sin(t) * std::sin(f), e.z * std::cos(t)};
      const Vec3 g{x.x / (e.x * e.x), x.y / (e.y * e.y), x.z / (e.z * e.z)};
      out.push_back({x, g / norm(g), ellipsoid_patch_area(e, t0, t1, f0, f1)});
    }
  }
  return out;
}

std::vector<SurfaceSample3> sample_cuboid(Vec3 half, real d0) {
  std::vector<SurfaceSample3> out;
  const real h[3] = {half.x, half.y, half.z};
  for (int a = 0; a < 3; ++a)
    for (const real side : {-1.0, 1.0}) {
      const int u = (a + 1) % 3, v = (a + 2) % 3;
      const int nu = count_along(2 * h[u], d0), nv = count_along(2 * h[v], d0);
      const real dA = 4 * h[u] * h[v] / (nu * nv);
      for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
          real p[3], n[3] = {0, 0, 0};
          p[a] = side * h[a];
          p[u] = -h[u] + (i + 0.5) * 2 * h[u] / nu;
          p[v] = -h[v] + (j + 0.5) * 2 * h[v] / nv;
          n[a] = side;
          out.push_back({{p[0], p[1], p[2]}, {n[0], n[1], n[2]}, dA});
        }
    }
  return out;
}

std::vector<SurfaceSample3> sample_cylinder(real R, real half_length, real d0) {
  std::vector<SurfaceSample3> out;
  // the side: rings of equal cells
  const int nz = count_along(2 * half_length, d0), nf = count_along(2 * M_PI * R, d0, 3);
  const real side_dA = 2 * M_PI * R * 2 * half_length / (nz * nf);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < nf; ++j) {
      const real f = 2 * M_PI * (j + 0.5 * (1 + k % 2)) / nf;
      const Vec3 n{std::cos(f), std::sin(f), 0};
      out.push_back({{R * n.x, R * n.y, -half_length + (k + 0.5) * 2 * half_length / nz}, n, side_dA});
    }
  // the caps: annuli of width R / nr, each of equal cells at its equal-area radius
  const int nr = count_along(R, d0);
  for (const real side : {-1.0, 1.0})
    for (int k = 0; k < nr; ++k) {
      const real r0 = R * k / nr, r1 = R * (k + 1) / nr, ring = M_PI * (r1 * r1 - r0 * r0);
      const int nc = std::max(1, static_cast<int>(std::lround(ring / (d0 * d0))));
      const real r = nc == 1 ? 0 : std::sqrt(0.5 * (r0 * r0 + r1 * r1));
      for (int j = 0; j < nc; ++j) {
        const real f = 2 * M_PI * (j + 0.5 * (k % 2)) / nc;
        out.push_back({{r * std::cos(f), r * std::sin(f), side * half_length}, {0, 0, side}, ring / nc});
      }
    }
  return out;
}

/// The cell of a hash grid of spacing `cell` that holds x.
std::int64_t grid_key(Vec3 x, real cell) {
  const auto c = [&](real v) { return static_cast<std::int64_t>(std::floor(v / cell)) & 0x1fffff; };
  return (c(x.x) << 42) | (c(x.y) << 21) | c(x.z);
}

std::vector<SurfaceSample3> sample_mesh(const TriangleMesh& mesh, real d0) {
  // The faces of a mesh are of any size and shape (slivers included), so the samples are not
  // laid face by face: the surface is first covered by fine points, about 16 per d0^2 on every
  // face, each carrying the exact share A_f / n_f of its face's area (a quasi-random R2 sequence,
  // deterministic, folded into the triangle); the samples are then chosen among them greedily at
  // least 0.9 d0 apart, and every fine point's area goes to its nearest sample. The areas sum to
  // the mesh's exactly; each sample lies on a face, with that face's normal.
  struct Fine {
    Vec3 x;
    std::uint32_t face;
    real dA;
  };
  std::vector<Fine> fine;
  const real fine_area = d0 * d0 / 16;
  for (std::size_t f = 0; f < mesh.faces().size(); ++f) {
    const TriangleMesh::Triangle t = mesh.triangle(f);
    const real A = 0.5 * norm(cross(t[1] - t[0], t[2] - t[0]));
    const int n = std::max(1, static_cast<int>(std::ceil(A / fine_area)));
    for (int k = 0; k < n; ++k) {
      // R2: (k + 1/2) (1/g, 1/g^2) mod 1, g the plastic number; (u, v) folded into u + v <= 1
      real u = std::fmod(0.5 + (k + 0.5) * 0.7548776662466927, 1.0),
           v = std::fmod(0.5 + (k + 0.5) * 0.5698402909980532, 1.0);
      if (u + v > 1) {
        u = 1 - u;
        v = 1 - v;
      }
      fine.push_back({t[0] + u * (t[1] - t[0]) + v * (t[2] - t[0]), static_cast<std::uint32_t>(f), A / n});
    }
  }
  // greedy choice, in the fine points' order, on a hash grid of cell d0
  const real r_min = 0.9 * d0;
  std::unordered_map<std::int64_t, std::vector<std::size_t>> grid;  // cell -> chosen samples
  std::vector<std::size_t> chosen;
  const auto near_chosen = [&](Vec3 x, real r, auto&& visit) {
    for (int i = -1; i <= 1; ++i)
      for (int j = -1; j <= 1; ++j)
        for (int k = -1; k <= 1; ++k) {
          const auto it = grid.find(grid_key(x + Vec3{i * d0, j * d0, k * d0}, d0));
          if (it == grid.end()) continue;
          for (const std::size_t c : it->second)
            if (norm(fine[chosen[c]].x - x) < r) visit(c);
        }
  };
  for (std::size_t q = 0; q < fine.size(); ++q) {
    bool free = true;
    near_chosen(fine[q].x, r_min, [&](std::size_t) { free = false; });
    if (!free) continue;
    grid[grid_key(fine[q].x, d0)].push_back(chosen.size());
    chosen.push_back(q);
  }
  // every fine point's area to its nearest sample (one is always within r_min: it was not free)
  std::vector<SurfaceSample3> out(chosen.size());
  for (std::size_t c = 0; c < chosen.size(); ++c) {
    const TriangleMesh::Triangle t = mesh.triangle(fine[chosen[c]].face);
    const Vec3 n = cross(t[1] - t[0], t[2] - t[0]);
    out[c] = {fine[chosen[c]].x, n / norm(n), 0};
  }
  for (const Fine& p : fine) {
    std::size_t best = 0;
    real best_d = 1e300;
    near_chosen(p.x, 1.01 * r_min, [&](std::size_t c) {
      const real d = norm(fine[chosen[c]].x - p.x);
      if (d < best_d || (d == best_d && c < best)) {
        best_d = d;
        best = c;
      }
    });
    out[best].dA += p.dA;
  }
  return out;
}

}  // namespace

Shape3 Shape3::sphere(real R) {
  if (!(R > 0)) throw std::invalid_argument("sphere: the radius must be positive");
  Shape3 s;
  s.kind_ = Shape3Kind::Sphere;
  s.axes_ = {R, R, R};
  s.volume_ = 4 * M_PI * R * R * R / 3;
  s.area_ = 4 * M_PI * R * R;
  s.inertia_ = (0.4 * R * R * s.volume_) * identity3();
  s.bound_ = R;
  s.min_width_ = 2 * R;
  return s;
}

Shape3 Shape3::ellipsoid(real a, real b, real c) {
  if (!(a > 0 && b > 0 && c > 0)) throw std::invalid_argument("ellipsoid: the semi-axes must be positive");
  Shape3 s;
  s.kind_ = Shape3Kind::Ellipsoid;
  s.axes_ = {a, b, c};
  s.volume_ = 4 * M_PI * a * b * c / 3;
  s.inertia_ = (s.volume_ / 5) * diagonal({b * b + c * c, a * a + c * c, a * a + b * b});
  for (const SurfaceSample3& p : sample_ellipsoid(s.axes_, std::min({a, b, c}) / 8)) s.area_ += p.dA;
  s.bound_ = std::max({a, b, c});
  s.min_width_ = 2 * std::min({a, b, c});
  return s;
}

Shape3 Shape3::cuboid(real lx, real ly, real lz) {
  if (!(lx > 0 && ly > 0 && lz > 0)) throw std::invalid_argument("cuboid: the sides must be positive");
  Shape3 s;
  s.kind_ = Shape3Kind::Cuboid;
  s.axes_ = {0.5 * lx, 0.5 * ly, 0.5 * lz};
  s.volume_ = lx * ly * lz;
  s.area_ = 2 * (lx * ly + ly * lz + lx * lz);
  s.inertia_ = (s.volume_ / 12) * diagonal({ly * ly + lz * lz, lx * lx + lz * lz, lx * lx + ly * ly});
  s.bound_ = norm(s.axes_);
  s.min_width_ = std::min({lx, ly, lz});
  return s;
}

Shape3 Shape3::cylinder(real R, real L) {
  if (!(R > 0 && L > 0)) throw std::invalid_argument("cylinder: the radius and length must be positive");
  Shape3 s;
  s.kind_ = Shape3Kind::Cylinder;
  s.axes_ = {R, R, 0.5 * L};
  s.volume_ = M_PI * R * R * L;
  s.area_ = 2 * M_PI * R * L + 2 * M_PI * R * R;
  const real across = s.volume_ * (3 * R * R + L * L) / 12;
  s.inertia_ = diagonal({across, across, 0.5 * s.volume_ * R * R});
  s.bound_ = std::sqrt(R * R + 0.25 * L * L);
  s.min_width_ = std::min(2 * R, L);
  return s;
}

Shape3 Shape3::mesh(const TriangleMesh& mesh) {
  Shape3 s;
  s.kind_ = Shape3Kind::Mesh;
  s.centroid_offset_ = mesh.centroid();
  auto centred = std::make_shared<const TriangleMesh>(mesh.translated(-s.centroid_offset_));
  s.volume_ = centred->volume();
  s.area_ = centred->surface_area();
  const Mat3 C = centred->second_moment();  // about the centroid
  s.inertia_ = trace(C) * identity3() - C;
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (const Vec3& v : centred->vertices()) {
    s.bound_ = std::max(s.bound_, norm(v));
    lo = {std::min(lo.x, v.x), std::min(lo.y, v.y), std::min(lo.z, v.z)};
    hi = {std::max(hi.x, v.x), std::max(hi.y, v.y), std::max(hi.z, v.z)};
  }
  s.min_width_ = std::min({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  s.mesh_ = std::move(centred);
  return s;
}

real Shape3::equivalent_radius() const { return std::cbrt(3 * volume_ / (4 * M_PI)); }

void Shape3::distance_and_gradient(Vec3 p, real& d, Vec3& n) const {
  switch (kind_) {
    case Shape3Kind::Sphere: {
      const real r = norm(p);
      d = r - axes_.x;
      n = r > 0 ? p / r : Vec3{0, 0, 1};
      return;
    }
    case Shape3Kind::Ellipsoid: {
      // in the first octant with the axes sorted e0 >= e1 >= e2, then back
      const real e[3] = {axes_.x, axes_.y, axes_.z}, y[3] = {p.x, p.y, p.z};
      int order[3] = {0, 1, 2};
      std::sort(order, order + 3, [&](int i, int j) { return e[i] > e[j]; });
      const auto x = closest_on_ellipsoid(e[order[0]], e[order[1]], e[order[2]], std::fabs(y[order[0]]),
                                          std::fabs(y[order[1]]), std::fabs(y[order[2]]));
      real q[3], g[3];
      for (int k = 0; k < 3; ++k) {
        const int a = order[k];
        q[a] = std::copysign(x[k], y[a]);
        g[a] = q[a] / (e[a] * e[a]);
      }
      const real inside =
          (y[0] / e[0]) * (y[0] / e[0]) + (y[1] / e[1]) * (y[1] / e[1]) + (y[2] / e[2]) * (y[2] / e[2]);
      const real dist = norm(Vec3{y[0] - q[0], y[1] - q[1], y[2] - q[2]});
      d = inside < 1 ? -dist : dist;
      n = Vec3{g[0], g[1], g[2]} / norm(Vec3{g[0], g[1], g[2]});
      return;
    }
    case Shape3Kind::Cuboid: {
      const Vec3 q{std::fabs(p.x) - axes_.x, std::fabs(p.y) - axes_.y, std::fabs(p.z) - axes_.z};
      const Vec3 out{std::max(q.x, 0.0), std::max(q.y, 0.0), std::max(q.z, 0.0)};
      const real outside = norm(out);
      if (outside > 0) {
        d = outside;
        n = Vec3{std::copysign(out.x, p.x), std::copysign(out.y, p.y), std::copysign(out.z, p.z)} / outside;
        return;
      }
      d = std::max({q.x, q.y, q.z});  // inside: the nearest face
      n = d == q.x ? Vec3{std::copysign(1.0, p.x), 0, 0}
                   : (d == q.y ? Vec3{0, std::copysign(1.0, p.y), 0} : Vec3{0, 0, std::copysign(1.0, p.z)});
      return;
    }
    case Shape3Kind::Cylinder: {
      const real rho = std::hypot(p.x, p.y);
      const Vec3 radial = rho > 0 ? Vec3{p.x / rho, p.y / rho, 0} : Vec3{1, 0, 0};
      const Vec3 axial{0, 0, std::copysign(1.0, p.z)};
      const real qr = rho - axes_.x, qz = std::fabs(p.z) - axes_.z;
      if (qr > 0 && qz > 0) {  // beyond the rim
        d = std::hypot(qr, qz);
        n = (qr / d) * radial + (qz / d) * axial;
      } else {
        d = std::max(qr, qz);
        n = qr > qz ? radial : axial;
      }
      return;
    }
    case Shape3Kind::Mesh:
      mesh_->distance_and_gradient(p, d, n);
      return;
  }
}

real Shape3::signed_distance(Vec3 p) const {
  real d = 0;
  Vec3 n;
  distance_and_gradient(p, d, n);
  return d;
}

std::vector<SurfaceSample3> Shape3::sample_surface(real d0) const {
  switch (kind_) {
    case Shape3Kind::Sphere:
      return sample_sphere(axes_.x, d0);
    case Shape3Kind::Ellipsoid:
      return sample_ellipsoid(axes_, d0);
    case Shape3Kind::Cuboid:
      return sample_cuboid(axes_, d0);
    case Shape3Kind::Cylinder:
      return sample_cylinder(axes_.x, axes_.z, d0);
    case Shape3Kind::Mesh:
      return sample_mesh(*mesh_, d0);
  }
  return {};
}

}  // namespace particula
