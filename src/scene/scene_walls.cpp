// Walls in the scene: surface samples (segments and arcs), dummy layers, corner volumes, and
// the region the walls enclose (the fluid fills the left side of the walls).
#include "scene_walls.hpp"

#include "scene_open.hpp"

#include <cmath>
#include <limits>

namespace particula::scene_detail {

namespace {

bool same_point(const Domain& d, Vec2 a, Vec2 b, real tol) { return norm(d.separation(a, b)) < tol; }

}  // namespace

/// x moved to its periodic image nearest the wall's middle (an arc's centre), so that a wall
/// spanning a periodic side is found from either end.
Vec2 image_near(const WallPiece& w, const Domain& dom, Vec2 x) {
  return w.middle() + dom.separation(x, w.middle());
}

/// Samples wall w at spacing ~d0: points at fractions k/n of its length for k = 0..n-1, plus
/// the end point unless another wall starts there (closed chains) or it is the start itself (a
/// full circle) or its periodic image. A point shared with the previous wall gets the mean of
/// the two walls' normals there; it is a corner where those differ (a smooth joint, such as an
/// arc meeting the segment along its tangent, is not one).
std::vector<SurfacePoint> sample_wall(const Case& c, const Domain& dom, std::size_t w) {
  const WallSpec& ws = c.walls[w];
  const WallPiece piece = ws.piece();
  const real len = piece.length();
  const int n = std::max(piece.is_arc() ? 8 : 1, static_cast<int>(std::lround(len / c.d0)));
  const real ds = len / n;
  const real tol = 1e-6 * c.d0;
  std::vector<SurfacePoint> pts;
  for (int k = 0; k <= n; ++k) {
    const real s = static_cast<real>(k) / n;
    const Vec2 x = piece.point_at(s);
    const Vec2 nrm = piece.normal_at(s);
    SurfacePoint sp{x, nrm, ds, false, {}, nrm};
    if (k == n) {
      if (same_point(dom, x, piece.start(), tol)) break;
      bool starts_other = false;
      for (std::size_t o = 0; o < c.walls.size(); ++o)
        if (o != w && same_point(dom, x, c.walls[o].from, tol)) starts_other = true;
      if (starts_other) break;
    }
    if (k == 0) {
      for (std::size_t o = 0; o < c.walls.size(); ++o)
        if (o != w && same_point(dom, x, c.walls[o].to, tol)) {
          const Vec2 n2 = c.walls[o].piece().normal_at(1);
          const Vec2 mean = nrm + n2;
          if (norm(mean) > 1e-12 && dot(nrm, n2) < 1 - 1e-9) {
            sp.normal = mean / norm(mean);
            sp.corner = true;
            sp.corner_normal2 = n2;
            // convex when this wall leaves the corner away from the other wall's fluid side
            if (dot(piece.tangent_at(0), n2) < 0) sp.wedge = half_angle_between(nrm, n2);
          }
        }
    }
    pts.push_back(sp);
  }
  // A wall that leaves the domain through an open boundary continues through its buffer.
  const int before = wall_extension_points(c, ws, false, ds), after = wall_extension_points(c, ws, true, ds);
  std::vector<SurfacePoint> ext;
  for (int k = -before; k < 0; ++k) {
    const real s = static_cast<real>(k) / n;
    ext.push_back({piece.point_at(s), piece.normal_at(0), ds, false, {}, piece.normal_at(0)});
  }
  ext.insert(ext.end(), pts.begin(), pts.end());
  for (int k = n + 1; k <= n + after; ++k) {
    const real s = static_cast<real>(k) / n;
    ext.push_back({piece.point_at(s), piece.normal_at(1), ds, false, {}, piece.normal_at(1)});
  }
  return ext;
}

/// Dummy particles of the baseline boundary (docs/method.md section 6, last paragraph): `layers`
/// rows behind each surface point along -n; a corner gets the full block spanned by the two
/// walls' normals.
std::vector<std::pair<Vec2, std::size_t>> dummy_points(const std::vector<SurfacePoint>& surf, real d0, int layers) {
  std::vector<std::pair<Vec2, std::size_t>> out;
  for (std::size_t s = 0; s < surf.size(); ++s) {
    const auto& sp = surf[s];
    if (sp.corner) {
      const Vec2 n1 = sp.wall_normal;
      for (int a = 0; a <= layers; ++a)
        for (int b = 0; b <= layers; ++b)
          if (a != 0 || b != 0) out.push_back({sp.x - (a * d0) * n1 - (b * d0) * sp.corner_normal2, s});
    } else {
      for (int k = 1; k <= layers; ++k) out.push_back({sp.x - (k * d0) * sp.normal, s});
    }
  }
  return out;
}

/// Volume factor of a corner particle. A single layer stands for the solid behind it. With
/// the volume d0 ds of a flat-wall particle the zeroth kernel moment s_i = sum_j w_j gradW_ij
/// of the fluid next to a straight wall nearly vanishes (|s| = 0.02/d0 for h = 2.6 d0), so a
/// fluid particle pushed against the wall is compressed rather than sucked in (with the
/// difference form of the renormalized gradient a particle whose s points away from the wall
/// gets lower pressure as it approaches and is pulled further in). At a corner where the
/// fluid angle is 90 degrees the same moment at the corner fluid particle is 0.22/d0 with a
/// unit factor and 0.03/d0 with a factor 2 (computed on the regular lattice): we scale the
/// corner volume linearly in the solid wedge angle, 1 for a flat wall and 2 for a right-angled
/// corner (docs/method.md section 6, M.6). Without it a loaded box corner blows up. A convex
/// corner of the solid (the inward corner of an L-shape: less solid behind it than behind a flat
/// wall) keeps the flat wall's 1.
real corner_volume_factor(Vec2 n1, Vec2 n2, bool convex) {
  const real turn = std::acos(std::fmax(-1.0, std::fmin(1.0, dot(n1, n2))));
  const real fluid_angle = convex ? M_PI + turn : M_PI - turn;
  const real solid_angle = 2 * M_PI - fluid_angle;
  return std::fmax(1.0, 2 * solid_angle / M_PI - 1);
}

}  // namespace particula::scene_detail

namespace particula {

using scene_detail::image_near;

/// The distance to the nearest wall point, with the sign of its side. Where that point is an end
/// point shared by two walls, x lies in the cone between the two end normals, and the sign of
/// (x - p).(n1 + n2) is the side of the chain there (in 2D the pseudo-normal of a vertex decides
/// inside and outside).
real signed_wall_distance(const std::vector<WallPiece>& walls, const Domain& dom, Vec2 x) {
  if (walls.empty()) return std::numeric_limits<real>::infinity();
  real best = std::numeric_limits<real>::infinity();
  for (const WallPiece& w : walls) best = std::min(best, w.nearest(image_near(w, dom, x)).distance);
  const real tie = best * (1 + 1e-9) + 1e-300;
  Vec2 normal_sum, from_point;
  for (const WallPiece& w : walls) {
    const Vec2 xi = image_near(w, dom, x);
    const WallNearest n = w.nearest(xi);
    if (n.distance > tie) continue;
    if (w.is_full_circle() || (n.s > 0 && n.s < 1)) return n.side >= 0 ? best : -best;
    normal_sum += n.normal;
    from_point = xi - n.point;
  }
  return dot(from_point, normal_sum) >= 0 ? best : -best;
}

bool in_fluid_region(const std::vector<WallPiece>& walls, const Domain& dom, Vec2 x) {
  return signed_wall_distance(walls, dom, x) >= 0;
}

std::vector<WallPiece> walls_at(const Case& c, real t) {
  std::vector<WallPiece> walls;
  for (const WallSpec& w : c.walls)
    walls.push_back(w.omega != 0 ? w.piece().moved(w.pivot, w.omega * t, Vec2{}) : w.piece());
  return walls;
}

}  // namespace particula
