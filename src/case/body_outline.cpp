// Outlines of bodies at t = 0 and the geometry helpers of the body load checks.
#include "body_outline.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "internal.hpp"

namespace particula::case_detail {

namespace {

/// p on the segment [a, b], given that the three are collinear.
bool within(Vec2 a, Vec2 b, Vec2 p, real eps) {
  return p.x >= std::min(a.x, b.x) - eps && p.x <= std::max(a.x, b.x) + eps &&
         p.y >= std::min(a.y, b.y) - eps && p.y <= std::max(a.y, b.y) + eps;
}

/// Even-odd crossing test of p against one closed loop (toggles `in`), and the distance to the
/// loop's edges (lowers `gap`).
void test_loop(const std::vector<Vec2>& v, Vec2 p, bool& in, real& gap) {
  for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i++) {
    const Vec2 vi = v[i], vj = v[j];
    if ((vi.y > p.y) != (vj.y > p.y) && p.x < (vj.x - vi.x) * (p.y - vi.y) / (vj.y - vi.y) + vi.x) in = !in;
    gap = std::min(gap, segment_distance(p, vi, vj));
  }
}

real loop_length(const std::vector<Vec2>& v) {
  real L = 0;
  for (std::size_t i = 0; i < v.size(); ++i) L += norm(v[(i + 1) % v.size()] - v[i]);
  return L;
}

/// Points along the closed loop v, each edge cut into parts in proportion to its share of the
/// total boundary length L of n points (vertices included).
void sample_loop(const std::vector<Vec2>& v, std::size_t n, real L, std::vector<Vec2>& out) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec2 p = v[i], q = v[(i + 1) % v.size()];
    const auto parts = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(n * norm(q - p) / L)));
    for (std::size_t j = 0; j < parts; ++j)
      out.push_back(p + (static_cast<real>(j) / static_cast<real>(parts)) * (q - p));
  }
}

}  // namespace

std::string body_key(std::size_t k, std::string_view leaf) { return fmt::format("body[{}].{}", k, leaf); }

std::string place_key(const Case& c, std::size_t k) {
  return body_key(k, c.bodies[k].shape == BodyShape::Polygon ? "vertices" : "center");
}

const std::string& shape_name(BodyShape s) {
  return find_key("body[].shape")->choices.at(static_cast<std::size_t>(s));
}

std::string body_text(const BodySpec& b) {
  return fmt::format("body '{}' ({})", b.name, shape_name(b.shape));
}

real twice_area(const std::vector<Vec2>& v) {
  real a = 0;
  for (std::size_t i = 1; i + 1 < v.size(); ++i) a += cross(v[i] - v[0], v[i + 1] - v[0]);
  return a;
}

Vec2 centroid(const std::vector<Vec2>& v, const std::vector<std::vector<Vec2>>& holes) {
  // First moments of the fans of triangles from v[0] (signed), holes subtracted whatever their
  // orientation.
  const auto moment = [&](const std::vector<Vec2>& loop, real& twice) {
    Vec2 m;
    twice = 0;
    for (std::size_t i = 1; i + 1 < loop.size(); ++i) {
      const Vec2 p = loop[i] - v[0], q = loop[i + 1] - v[0], o = loop[0] - v[0];
      const real w = cross(p - o, q - o);
      twice += w;
      m += (w / 3) * (o + p + q);
    }
    return m;
  };
  real A2 = 0;
  Vec2 m = moment(v, A2);
  const real s = A2 > 0 ? 1 : -1;
  A2 *= s, m = s * m;
  for (const auto& hole : holes) {
    real a = 0;
    Vec2 mh = moment(hole, a);
    const real sh = a > 0 ? 1 : -1;
    A2 -= sh * a, m -= sh * mh;
  }
  return v[0] + m / A2;
}

real extent(const std::vector<Vec2>& v) {
  Vec2 lo = v[0], hi = v[0];
  for (const Vec2& p : v) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
  return norm(hi - lo);
}

int sign(real x, real eps) { return x > eps ? 1 : (x < -eps ? -1 : 0); }

bool segments_meet(Vec2 p1, Vec2 p2, Vec2 q1, Vec2 q2, real area_eps, real len_eps) {
  const int d1 = sign(cross(q2 - q1, p1 - q1), area_eps), d2 = sign(cross(q2 - q1, p2 - q1), area_eps);
  const int d3 = sign(cross(p2 - p1, q1 - p1), area_eps), d4 = sign(cross(p2 - p1, q2 - p1), area_eps);
  if (d1 * d2 < 0 && d3 * d4 < 0) return true;
  return (d1 == 0 && within(q1, q2, p1, len_eps)) || (d2 == 0 && within(q1, q2, p2, len_eps)) ||
         (d3 == 0 && within(p1, p2, q1, len_eps)) || (d4 == 0 && within(p1, p2, q2, len_eps));
}

bool edges_meet(const std::vector<Vec2>& v, std::size_t i, std::size_t j, real area_eps, real len_eps) {
  const std::size_t n = v.size();
  const Vec2 a = v[i], a2 = v[(i + 1) % n], q = v[j], q2 = v[(j + 1) % n];
  if (j == i + 1)  // neighbours sharing a2 == q: they meet elsewhere only by folding back
    return sign(cross(a - q, q2 - q), area_eps) == 0 && dot(a - q, q2 - q) > 0;
  if (i == 0 && j == n - 1)  // neighbours sharing a == q2
    return sign(cross(a2 - a, q - a), area_eps) == 0 && dot(a2 - a, q - a) > 0;
  return segments_meet(a, a2, q, q2, area_eps, len_eps);
}

real polygon_width(const std::vector<Vec2>& v) {
  real w = std::numeric_limits<real>::infinity();
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec2 e = v[(i + 1) % v.size()] - v[i];
    real far = 0;
    for (const Vec2& p : v) far = std::max(far, std::fabs(cross(e, p - v[i])) / norm(e));
    w = std::min(w, far);
  }
  return w;
}

real segment_distance(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const real L2 = norm2(ab);
  const real s = L2 > 0 ? std::clamp(dot(p - a, ab) / L2, 0.0, 1.0) : 0.0;
  return norm(p - (a + s * ab));
}

std::vector<Vec2> periodic_shifts(const Case& c) {
  const Vec2 span = c.domain_max - c.domain_min;
  std::vector<Vec2> shifts;
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j)
      if ((i == 0 || c.periodic_x) && (j == 0 || c.periodic_y)) shifts.push_back({i * span.x, j * span.y});
  return shifts;
}

Outline::Outline(const BodySpec& b) : body(&b), cs(std::cos(b.angle)), sn(std::sin(b.angle)) {
  const real R = b.radius, a = b.semi_axes.x, e = b.semi_axes.y;
  switch (b.shape) {
    case BodyShape::Circle:
      center = b.center, bound = R, lo = center - Vec2{R, R}, hi = center + Vec2{R, R};
      break;
    case BodyShape::Ellipse: {
      center = b.center, bound = std::max(a, e);
      const Vec2 half{std::hypot(a * cs, e * sn), std::hypot(a * sn, e * cs)};
      lo = center - half, hi = center + half;
      break;
    }
    case BodyShape::HalfDisc: {
      center = b.center, bound = R;
      // Along each axis direction d: R where the round side faces d, else the flat side's ends.
      const Vec2 u{cs, sn}, w{-sn, cs};
      const auto reach = [&](Vec2 d) { return dot(d, u) >= 0 ? R : R * std::fabs(dot(d, w)); };
      lo = center - Vec2{reach({-1, 0}), reach({0, -1})};
      hi = center + Vec2{reach({1, 0}), reach({0, 1})};
      break;
    }
    case BodyShape::Polygon: {
      center = centroid(b.vertices, b.holes);
      lo = hi = center;
      for (const Vec2& p : b.vertices) {
        verts.push_back(center + rotate(p - center, cs, sn));
        bound = std::max(bound, norm(p - center));
        lo = {std::min(lo.x, verts.back().x), std::min(lo.y, verts.back().y)};
        hi = {std::max(hi.x, verts.back().x), std::max(hi.y, verts.back().y)};
      }
      for (const auto& hole : b.holes) {
        holes.emplace_back();
        for (const Vec2& p : hole) holes.back().push_back(center + rotate(p - center, cs, sn));
      }
      break;
    }
  }
}

bool Outline::contains(Vec2 p, real tol) const {
  const BodySpec& b = *body;
  const Vec2 q = local(p);
  switch (b.shape) {
    case BodyShape::Circle:
      return norm(q) < b.radius - tol;
    case BodyShape::Ellipse: {
      const real a = b.semi_axes.x - tol, e = b.semi_axes.y - tol;
      return a > 0 && e > 0 && (q.x / a) * (q.x / a) + (q.y / e) * (q.y / e) < 1;
    }
    case BodyShape::HalfDisc:
      return q.x > tol && norm(q) < b.radius - tol;
    case BodyShape::Polygon: {
      bool in = false;  // even-odd rule over the outline and the holes
      real gap = std::numeric_limits<real>::infinity();
      test_loop(verts, p, in, gap);
      for (const auto& hole : holes) test_loop(hole, p, in, gap);
      return in && gap > tol;
    }
  }
  return false;
}

real Outline::perimeter() const {
  const BodySpec& b = *body;
  switch (b.shape) {
    case BodyShape::Circle:
      return 2 * M_PI * b.radius;
    case BodyShape::Ellipse:  // Ramanujan's approximation (only sets the sampling density)
      return M_PI * (3 * (b.semi_axes.x + b.semi_axes.y) -
                     std::sqrt((3 * b.semi_axes.x + b.semi_axes.y) * (b.semi_axes.x + 3 * b.semi_axes.y)));
    case BodyShape::HalfDisc:
      return (M_PI + 2) * b.radius;
    case BodyShape::Polygon: {
      real L = loop_length(verts);
      for (const auto& hole : holes) L += loop_length(hole);
      return L;
    }
  }
  return 0;
}

std::vector<Vec2> Outline::boundary(std::size_t n) const {
  const BodySpec& b = *body;
  std::vector<Vec2> out;
  const auto world = [&](Vec2 q) { return center + rotate(q, cs, sn); };
  switch (b.shape) {
    case BodyShape::Circle:
    case BodyShape::Ellipse: {
      const real a = b.shape == BodyShape::Circle ? b.radius : b.semi_axes.x;
      const real e = b.shape == BodyShape::Circle ? b.radius : b.semi_axes.y;
      for (std::size_t i = 0; i < n; ++i) {
        const real t = 2 * M_PI * static_cast<real>(i) / static_cast<real>(n);
        out.push_back(world({a * std::cos(t), e * std::sin(t)}));
      }
      break;
    }
    case BodyShape::HalfDisc: {
      const real R = b.radius;
      const std::size_t arc = std::max<std::size_t>(2, static_cast<std::size_t>(n * M_PI / (M_PI + 2)));
      for (std::size_t i = 0; i <= arc; ++i) {
        const real t = -0.5 * M_PI + M_PI * static_cast<real>(i) / static_cast<real>(arc);
        out.push_back(world({R * std::cos(t), R * std::sin(t)}));
      }
      const std::size_t flat = std::max<std::size_t>(2, n - arc);
      for (std::size_t i = 1; i < flat; ++i)
        out.push_back(world({0, R - 2 * R * static_cast<real>(i) / static_cast<real>(flat)}));
      break;
    }
    case BodyShape::Polygon: {
      const real L = perimeter();
      sample_loop(verts, n, L, out);
      for (const auto& hole : holes) sample_loop(hole, n, L, out);
      break;
    }
  }
  return out;
}

real gap_to_wall(const Outline& o, const std::vector<Vec2>& samples, const WallPiece& w) {
  if (o.body->shape == BodyShape::Circle) return w.nearest(o.center).distance - o.body->radius;
  if (o.contains(w.start(), 0))
    return 0;  // the wall lies inside (it would come near the boundary if it left)
  real gap = std::numeric_limits<real>::infinity();
  for (const Vec2 p : samples) gap = std::min(gap, w.nearest(p).distance);
  return gap;
}

real outline_gap(const Outline& A, const Outline& B, Vec2 shift, std::size_t points) {
  if (A.body->shape == BodyShape::Circle && B.body->shape == BodyShape::Circle)
    return norm(B.center + shift - A.center) - A.body->radius - B.body->radius;
  const std::vector<Vec2> pa = A.boundary(points), pb = B.boundary(points);
  real gap = std::numeric_limits<real>::infinity();
  for (const Vec2 p : pa)
    for (std::size_t i = 0; i < pb.size(); ++i)
      gap = std::min(gap, segment_distance(p, pb[i] + shift, pb[(i + 1) % pb.size()] + shift));
  return gap;
}

}  // namespace particula::case_detail
