#include "particula/geometry/shape.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "edge_grid.hpp"

namespace particula {

namespace {

Vec2 unit(Vec2 v) {
  const real n = norm(v);
  return n > 0 ? v / n : Vec2{1, 0};
}

/// Closest point to p on segment [a, b].
Vec2 closest_on_segment(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const real L2 = norm2(ab);
  const real s = L2 > 0 ? std::clamp(dot(p - a, ab) / L2, 0.0, 1.0) : 0.0;
  return a + s * ab;
}

/// Even-odd point-in-polygon test.
bool inside_polygon(Vec2 p, const std::vector<Vec2>& v) {
  bool in = false;
  for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i++) {
    if ((v[i].y > p.y) != (v[j].y > p.y) && p.x < (v[j].x - v[i].x) * (p.y - v[i].y) / (v[j].y - v[i].y) + v[i].x)
      in = !in;
  }
  return in;
}

/// Ellipse point at parameter t and its outward normal.
Vec2 ellipse_point(real a, real b, real t) { return {a * std::cos(t), b * std::sin(t)}; }
Vec2 ellipse_normal(real a, real b, Vec2 x) { return unit({x.x / (a * a), x.y / (b * b)}); }

/// Samples a polyline loop (closed polygon) at spacing ~d0: vertices included, normals of
/// vertices = mean of the adjacent edge normals, dS exact (sums to the perimeter).
std::vector<SurfaceSample> sample_loop(const std::vector<Vec2>& v, real d0) {
  const std::size_t n = v.size();
  std::vector<real> spacing(n);
  std::vector<int> parts(n);
  std::vector<Vec2> nrm(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 e = v[(i + 1) % n] - v[i];
    parts[i] = std::max(1, static_cast<int>(std::lround(norm(e) / d0)));
    spacing[i] = norm(e) / parts[i];
    const Vec2 t = unit(e);
    nrm[i] = {t.y, -t.x};  // outward for a counter-clockwise loop
  }
  std::vector<SurfaceSample> out;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t prev = (i + n - 1) % n;
    // the solid is on the left of the loop: a left turn at v[i] is a convex corner
    const bool convex = cross(v[i] - v[prev], v[(i + 1) % n] - v[i]) > 0;
    out.push_back({v[i], unit(nrm[i] + nrm[prev]), 0.5 * (spacing[i] + spacing[prev]), true, {nrm[prev], nrm[i]},
                   convex ? half_angle_between(nrm[prev], nrm[i]) : real(0)});
    for (int k = 1; k < parts[i]; ++k)
      out.push_back({v[i] + (static_cast<real>(k) / parts[i]) * (v[(i + 1) % n] - v[i]), nrm[i], spacing[i], false, {}});
  }
  return out;
}

}  // namespace

Shape Shape::circle(real radius) {
  if (!(radius > 0)) throw std::invalid_argument("circle radius must be positive");
  Shape s;
  s.kind_ = ShapeKind::Circle;
  s.a_ = s.b_ = radius;
  s.area_ = M_PI * radius * radius;
  s.polar_ = 0.5 * M_PI * std::pow(radius, 4);
  s.bound_ = radius;
  s.min_width_ = 2 * radius;
  return s;
}

Shape Shape::ellipse(real a, real b) {
  if (!(a > 0 && b > 0)) throw std::invalid_argument("ellipse semi-axes must be positive");
  Shape s;
  s.kind_ = ShapeKind::Ellipse;
  s.a_ = a;
  s.b_ = b;
  s.area_ = M_PI * a * b;
  s.polar_ = 0.25 * M_PI * a * b * (a * a + b * b);
  s.bound_ = std::max(a, b);
  s.min_width_ = 2 * std::min(a, b);
  return s;
}

namespace {

/// Polygons of at least this many edges find their nearest edge through a grid of cells.
constexpr std::size_t kGridEdges = 16;

/// Twice the signed area of a closed loop (positive when counter-clockwise).
real twice_signed_area(const std::vector<Vec2>& v) {
  real a = 0;
  for (std::size_t i = 0; i < v.size(); ++i) a += cross(v[i], v[(i + 1) % v.size()]);
  return a;
}

/// Smallest distance between a vertex of one loop and an edge of another: the thinnest solid
/// between a hole and the outline or between two holes.
real closest_loops(const std::vector<std::vector<Vec2>>& loops) {
  real d2 = 1e300;
  for (std::size_t a = 0; a < loops.size(); ++a)
    for (std::size_t b = 0; b < loops.size(); ++b) {
      if (a == b) continue;
      const auto& e = loops[b];
      for (const Vec2& p : loops[a])
        for (std::size_t i = 0; i < e.size(); ++i) d2 = std::min(d2, norm2(p - closest_on_segment(p, e[i], e[(i + 1) % e.size()])));
    }
  return std::sqrt(d2);
}

}  // namespace

Shape Shape::polygon(std::vector<Vec2> v, std::vector<std::vector<Vec2>> holes) {
  if (v.size() < 3) throw std::invalid_argument("a polygon needs at least 3 vertices");
  // The solid lies on the left of every loop: the outline counter-clockwise, holes clockwise.
  std::vector<std::vector<Vec2>> loops{std::move(v)};
  for (auto& hole : holes) {
    if (hole.size() < 3) throw std::invalid_argument("a polygon hole needs at least 3 vertices");
    loops.push_back(std::move(hole));
  }
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const real a = twice_signed_area(loops[l]);
    if (!(std::fabs(a) > 0)) throw std::invalid_argument("polygon has zero area");
    if ((l == 0) != (a > 0)) std::reverse(loops[l].begin(), loops[l].end());
  }
  // Area and centroid: shoelace sums over all loops (a clockwise hole subtracts its share).
  real A2 = 0;
  Vec2 c;
  for (const auto& loop : loops)
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Vec2 p = loop[i], q = loop[(i + 1) % loop.size()];
      const real w = cross(p, q);
      A2 += w;
      c += (w / 3) * (p + q);
    }
  if (!(A2 > 0)) throw std::invalid_argument("polygon holes cover its whole area");
  c = c / A2;
  Shape s;
  s.kind_ = ShapeKind::Polygon;
  s.centroid_offset_ = c;
  // Polar moment about the (new) origin = the centroid: shoelace formula over all loops.
  real J = 0;
  for (auto& loop : loops) {
    for (auto& p : loop) p = p - c;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Vec2 p = loop[i], q = loop[(i + 1) % loop.size()];
      J += cross(p, q) * (p.x * p.x + p.x * q.x + q.x * q.x + p.y * p.y + p.y * q.y + q.y * q.y);
    }
  }
  s.area_ = 0.5 * A2;
  s.polar_ = J / 12;
  const std::vector<Vec2>& outline = loops[0];
  for (const auto& p : outline) s.bound_ = std::max(s.bound_, norm(p));
  // Smallest width: minimum over edges of the largest distance of any vertex from the edge line
  // (exact for convex polygons, an upper bound for non-convex ones), and the thinnest solid
  // between loops.
  real w = 1e300;
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const Vec2 t = unit(outline[(i + 1) % outline.size()] - outline[i]);
    real far = 0;
    for (const auto& p : outline) far = std::max(far, std::fabs(cross(t, p - outline[i])));
    w = std::min(w, far);
  }
  s.min_width_ = std::min(w, closest_loops(loops));
  s.loops_ = std::move(loops);
  std::size_t edges = 0;
  for (const auto& loop : s.loops_) edges += loop.size();
  if (edges >= kGridEdges) s.grid_ = std::make_shared<const geometry_detail::EdgeGrid>(s.loops_);
  return s;
}

Shape Shape::half_disc(real radius) {
  if (!(radius > 0)) throw std::invalid_argument("half-disc radius must be positive");
  Shape s;
  s.kind_ = ShapeKind::HalfDisc;
  s.a_ = s.b_ = radius;
  const real xc = 4 * radius / (3 * M_PI);  // centroid distance from the flat side
  s.centroid_offset_ = {xc, 0};
  s.area_ = 0.5 * M_PI * radius * radius;
  s.polar_ = 0.25 * M_PI * std::pow(radius, 4) - s.area_ * xc * xc;
  s.bound_ = std::hypot(xc, radius);
  s.min_width_ = radius;
  return s;
}

real Shape::equivalent_radius() const { return std::sqrt(area_ / M_PI); }

real Shape::perimeter() const {
  switch (kind_) {
    case ShapeKind::Circle: return 2 * M_PI * a_;
    case ShapeKind::HalfDisc: return (M_PI + 2) * a_;
    case ShapeKind::Ellipse: {
      const int n = 20000;
      real L = 0;
      for (int k = 0; k < n; ++k)
        L += norm(ellipse_point(a_, b_, 2 * M_PI * (k + 1) / n) - ellipse_point(a_, b_, 2 * M_PI * k / n));
      return L;
    }
    case ShapeKind::Polygon: {
      real L = 0;
      for (const auto& loop : loops_)
        for (std::size_t i = 0; i < loop.size(); ++i) L += norm(loop[(i + 1) % loop.size()] - loop[i]);
      return L;
    }
  }
  return 0;
}

Vec2 Shape::closest_point(Vec2 p) const {
  switch (kind_) {
    case ShapeKind::Circle: return a_ * unit(p);
    case ShapeKind::Ellipse: {
      // Newton iteration on the parameter t of the closest point (x - p) . x'(t) = 0.
      real t = std::atan2(p.y * a_, p.x * b_);
      for (int it = 0; it < 40; ++it) {
        const real c = std::cos(t), s = std::sin(t);
        const Vec2 x{a_ * c, b_ * s}, d1{-a_ * s, b_ * c}, d2{-a_ * c, -b_ * s};
        const real f = dot(x - p, d1), df = dot(d1, d1) + dot(x - p, d2);
        if (!(std::fabs(df) > 0)) break;
        const real step = f / df;
        t -= std::clamp(step, -0.5, 0.5);
        if (std::fabs(step) < 1e-14) break;
      }
      return ellipse_point(a_, b_, t);
    }
    case ShapeKind::Polygon: {
      if (grid_) return grid_->nearest(p).point;
      Vec2 best = loops_[0][0];
      real bd = 1e300;
      for (const auto& loop : loops_)
        for (std::size_t i = 0; i < loop.size(); ++i) {
          const Vec2 q = closest_on_segment(p, loop[i], loop[(i + 1) % loop.size()]);
          if (norm2(q - p) < bd) {
            bd = norm2(q - p);
            best = q;
          }
        }
      return best;
    }
    case ShapeKind::HalfDisc: {
      const Vec2 d{-centroid_offset_.x, 0};  // disc centre
      const Vec2 r = p - d;
      const Vec2 on_arc = r.x >= 0 ? d + a_ * unit(r) : d + Vec2{0, r.y >= 0 ? a_ : -a_};
      const Vec2 on_flat = closest_on_segment(p, d + Vec2{0, -a_}, d + Vec2{0, a_});
      return norm2(on_arc - p) < norm2(on_flat - p) ? on_arc : on_flat;
    }
  }
  return p;
}

bool Shape::contains(Vec2 p) const {
  switch (kind_) {
    case ShapeKind::Circle: return norm(p) < a_;
    case ShapeKind::Ellipse: return (p.x * p.x) / (a_ * a_) + (p.y * p.y) / (b_ * b_) < 1;
    case ShapeKind::Polygon: {  // even-odd rule over all loops: a point in a hole is outside
      bool in = false;
      for (const auto& loop : loops_) in = in != inside_polygon(p, loop);
      return in;
    }
    case ShapeKind::HalfDisc: {
      const Vec2 r = p - Vec2{-centroid_offset_.x, 0};
      return r.x > 0 && norm(r) < a_;
    }
  }
  return false;
}

real Shape::polygon_distance(Vec2 p, Vec2& q) const {
  if (grid_) {
    const geometry_detail::PolygonNearest n = grid_->nearest(p);
    q = n.point;
    return n.inside ? -n.distance : n.distance;
  }
  q = closest_point(p);
  const real d = norm(p - q);
  return contains(p) ? -d : d;
}

real Shape::signed_distance(Vec2 p) const {
  if (kind_ == ShapeKind::Circle) return norm(p) - a_;
  if (kind_ == ShapeKind::Polygon) {
    Vec2 q;
    return polygon_distance(p, q);
  }
  const real d = norm(p - closest_point(p));
  return contains(p) ? -d : d;
}

Vec2 Shape::closest_normal(Vec2 p) const {
  const Vec2 q = closest_point(p);
  switch (kind_) {
    case ShapeKind::Circle: return unit(p);
    case ShapeKind::Ellipse: return ellipse_normal(a_, b_, q);
    default: {
      const real sd = signed_distance(p);
      if (std::fabs(sd) > 1e-12 * bound_) return unit(sd > 0 ? p - q : q - p);
      return unit(p);  // on the surface: fall back to the radial direction
    }
  }
}

void Shape::distance_and_gradient(Vec2 p, real& d, Vec2& n) const {
  if (kind_ == ShapeKind::Circle) {
    d = norm(p) - a_;
    n = unit(p);
    return;
  }
  Vec2 q;
  real sd = 0;
  if (kind_ == ShapeKind::Polygon) {
    sd = polygon_distance(p, q);
  } else {
    q = closest_point(p);
    sd = contains(p) ? -norm(p - q) : norm(p - q);
  }
  const bool inside = sd < 0;
  const real dist = std::fabs(sd);
  d = sd;
  if (kind_ == ShapeKind::Ellipse) n = ellipse_normal(a_, b_, q);
  else if (dist > 1e-12 * bound_) n = unit(inside ? q - p : p - q);
  else n = unit(p);  // on the surface: the radial direction
}

std::vector<SurfaceSample> Shape::sample_surface(real d0) const {
  std::vector<SurfaceSample> out;
  switch (kind_) {
    case ShapeKind::Circle: {
      const int n = std::max(8, static_cast<int>(std::lround(2 * M_PI * a_ / d0)));
      for (int k = 0; k < n; ++k) {
        const real t = 2 * M_PI * k / n;
        const Vec2 e{std::cos(t), std::sin(t)};
        out.push_back({a_ * e, e, 2 * M_PI * a_ / n, false, {}});
      }
      break;
    }
    case ShapeKind::Ellipse: {
      // Equal arc-length spacing from a fine cumulative-length table.
      const int fine = 20000;
      std::vector<real> cum(fine + 1, 0);
      for (int k = 0; k < fine; ++k)
        cum[k + 1] = cum[k] + norm(ellipse_point(a_, b_, 2 * M_PI * (k + 1) / fine) -
                                   ellipse_point(a_, b_, 2 * M_PI * k / fine));
      const real L = cum[fine];
      const int n = std::max(8, static_cast<int>(std::lround(L / d0)));
      int k = 0;
      for (int i = 0; i < n; ++i) {
        const real target = L * i / n;
        while (k < fine && cum[k + 1] < target) ++k;
        const real f = cum[k + 1] > cum[k] ? (target - cum[k]) / (cum[k + 1] - cum[k]) : 0;
        const real t = 2 * M_PI * (k + f) / fine;
        const Vec2 x = ellipse_point(a_, b_, t);
        out.push_back({x, ellipse_normal(a_, b_, x), L / n, false, {}});
      }
      break;
    }
    case ShapeKind::Polygon:  // the outline, then each hole (its normals point into the hole)
      for (const auto& loop : loops_) {
        const auto part = sample_loop(loop, d0);
        out.insert(out.end(), part.begin(), part.end());
      }
      break;
    case ShapeKind::HalfDisc: {
      const Vec2 d{-centroid_offset_.x, 0};
      const int na = std::max(4, static_cast<int>(std::lround(M_PI * a_ / d0)));
      const int nf = std::max(2, static_cast<int>(std::lround(2 * a_ / d0)));
      const real sa = M_PI * a_ / na, sf = 2 * a_ / nf;
      for (int k = 0; k <= na; ++k) {  // arc from -90 to +90 degrees, both corners included
        const real t = -0.5 * M_PI + M_PI * k / na;
        const Vec2 e{std::cos(t), std::sin(t)};
        if (k == 0 || k == na)
          out.push_back({d + a_ * e, unit(e + Vec2{-1, 0}), 0.5 * (sa + sf), true, {e, Vec2{-1, 0}},
                         half_angle_between(e, Vec2{-1, 0})});
        else
          out.push_back({d + a_ * e, e, sa, false, {}});
      }
      for (int k = 1; k < nf; ++k)  // flat side from top to bottom
        out.push_back({d + Vec2{0, a_ - sf * k}, {-1, 0}, sf, false, {}});
      break;
    }
  }
  return out;
}

}  // namespace particula
