// Load checks of bodies on their own and against each other: keys of their shape, valid
// polygons and holes, density of free bodies, schedules, size against d0, inside the domain
// (a fixed body may stand on a wall at the domain's edge), no overlap at t = 0. Run by
// run_cross_checks (checks.cpp) in its order.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

#include "body_outline.hpp"
#include "internal.hpp"

namespace particula::case_detail {
namespace {

/// One closed loop of a polygon body as the case file gives it: the outline (`vertices`) or a
/// hole (`holes[h]`), with the words that name it and its points in messages.
struct Loop {
  const std::vector<Vec2>& v;
  std::string key;         // "body[0].vertices" or "body[0].holes"
  std::optional<std::size_t> hole;  // which hole, none for the outline

  std::string what() const { return hole ? fmt::format("polygon hole holes[{}]", *hole) : "polygon"; }
  std::string point(std::size_t i) const {
    return hole ? fmt::format("holes[{}][{}]", *hole, i) : fmt::format("vertices[{}]", i);
  }
  /// The line of point i (of the hole's entry for a hole).
  int line(const LoadContext& ctx, std::size_t i) const { return ctx.item_line(key, hole ? *hole : i); }
};

/// No two vertices of a loop closer than d0/2: every vertex is a surface particle, and the time
/// step shrinks with the closest pair of particles (two vertices 1e-8 m apart would make steps of
/// about 1e-11 s). Of all such pairs the first in (j, i) order is reported.
void check_vertex_spacing(const Case& c, const LoadContext& ctx, const Loop& loop) {
  const std::vector<Vec2>& v = loop.v;
  const std::size_t n = v.size();
  const real limit = 0.5 * c.d0;
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t p, std::size_t q) { return v[p].x < v[q].x; });
  std::optional<std::pair<std::size_t, std::size_t>> first;  // (later, earlier) vertex
  for (std::size_t p = 0; p < n; ++p)
    for (std::size_t q = p + 1; q < n && v[order[q]].x - v[order[p]].x < limit; ++q) {
      const std::size_t i = std::min(order[p], order[q]), j = std::max(order[p], order[q]);
      if (norm(v[j] - v[i]) < limit && (!first || std::pair{j, i} < *first)) first = std::pair{j, i};
    }
  if (!first) return;
  const auto [j, i] = *first;
  const real gap = norm(v[j] - v[i]);
  throw ctx.error_at(
      loop.key, loop.line(ctx, j),
      fmt::format("{} {} {} and {} {} are {:.3g} m apart, closer than d0/2 = {:.6g} m: "
                  "each vertex is a surface particle and the time step shrinks with the closest pair (about "
                  "{:.2g} times shorter here); merge the two vertices or move them at least d0/2 apart",
                  loop.what(), loop.point(i), vec(v[i]), loop.point(j), vec(v[j]), gap, limit, c.d0 / gap));
}

/// One loop: distinct consecutive vertices, not all on one line, no edge meeting another except
/// its neighbours at their shared vertex, vertices at least d0/2 apart.
void check_loop(const Case& c, const LoadContext& ctx, const Loop& loop) {
  const std::vector<Vec2>& v = loop.v;
  const std::size_t n = v.size();
  const std::string& key = loop.key;
  const real L = extent(v), len_eps = 1e-12 * L, area_eps = 1e-12 * L * L;
  if (!std::isfinite(area_eps))
    throw ctx.error(key, fmt::format("{} is absurdly large ({:.3g} m across)", loop.what(), L));
  for (std::size_t i = 0; i < n; ++i)
    if (norm(v[(i + 1) % n] - v[i]) <= len_eps)
      throw ctx.error_at(key, loop.line(ctx, (i + 1) % n),
                         fmt::format("{} has zero area or repeated points: {} and {} are the same point {}",
                                     loop.what(), loop.point(i), loop.point((i + 1) % n), vec(v[i])));
  // All on one line: no vertex off the line through vertex 0 and the vertex farthest from it.
  std::size_t far = 0;
  for (std::size_t i = 1; i < n; ++i)
    if (norm(v[i] - v[0]) > norm(v[far] - v[0])) far = i;
  bool collinear = true;
  for (std::size_t i = 0; i < n && collinear; ++i) collinear = sign(cross(v[far] - v[0], v[i] - v[0]), area_eps) == 0;
  if (collinear)
    throw ctx.error_at(key, loop.line(ctx, 0),
                       fmt::format("{} has zero area: all its vertices lie on one line", loop.what()));
  // Edges that meet: a sweep along x tests only pairs whose x ranges overlap; of all such pairs
  // the first in (i, j) order is reported.
  std::vector<std::size_t> order(n);
  std::vector<real> xlo(n), xhi(n);
  for (std::size_t i = 0; i < n; ++i) {
    order[i] = i;
    xlo[i] = std::min(v[i].x, v[(i + 1) % n].x);
    xhi[i] = std::max(v[i].x, v[(i + 1) % n].x);
  }
  std::sort(order.begin(), order.end(), [&](std::size_t p, std::size_t q) { return xlo[p] < xlo[q]; });
  std::optional<std::pair<std::size_t, std::size_t>> first;
  for (std::size_t p = 0; p < n; ++p) {
    for (std::size_t q = p + 1; q < n && xlo[order[q]] <= xhi[order[p]] + len_eps; ++q) {
      const std::size_t i = std::min(order[p], order[q]), j = std::max(order[p], order[q]);
      if ((!first || std::pair{i, j} < *first) && edges_meet(v, i, j, area_eps, len_eps)) first = std::pair{i, j};
    }
  }
  if (first) {
    const auto [i, j] = *first;
    throw ctx.error_at(key, loop.line(ctx, j),
                       fmt::format("{} intersects itself: edge {} -> {} ({} -> {}) meets edge {} -> {} ({} -> {})",
                                   loop.what(), loop.point(i), loop.point((i + 1) % n), vec(v[i]),
                                   vec(v[(i + 1) % n]), loop.point(j), loop.point((j + 1) % n), vec(v[j]),
                                   vec(v[(j + 1) % n])));
  }
  if (sign(twice_area(v), area_eps) == 0)
    throw ctx.error_at(key, loop.line(ctx, 0), fmt::format("{} has zero area", loop.what()));
  check_vertex_spacing(c, ctx, loop);
}

/// Whether p lies inside the closed polygon v (even-odd rule).
bool inside_loop(Vec2 p, const std::vector<Vec2>& v) {
  bool in = false;
  for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i++)
    if ((v[i].y > p.y) != (v[j].y > p.y) && p.x < (v[j].x - v[i].x) * (p.y - v[i].y) / (v[j].y - v[i].y) + v[i].x)
      in = !in;
  return in;
}

/// Smallest distance from a vertex of a to an edge of b or from a vertex of b to an edge of a:
/// the solid between two loops that do not meet.
real loop_gap(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  real gap = std::numeric_limits<real>::infinity();
  for (int pass = 0; pass < 2; ++pass) {
    const auto& p = pass ? b : a;
    const auto& e = pass ? a : b;
    for (const Vec2 x : p)
      for (std::size_t i = 0; i < e.size(); ++i) gap = std::min(gap, segment_distance(x, e[i], e[(i + 1) % e.size()]));
  }
  return gap;
}

/// Whether an edge of a meets an edge of b.
bool loops_meet(const std::vector<Vec2>& a, const std::vector<Vec2>& b, real area_eps, real len_eps) {
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j)
      if (segments_meet(a[i], a[(i + 1) % a.size()], b[j], b[(j + 1) % b.size()], area_eps, len_eps)) return true;
  return false;
}

/// A body needs at least this many particles across its smallest dimension.
constexpr real kMinParticlesAcross = 10;

/// Holes of polygon body[k]: each inside the outline and outside the other holes, with at least
/// kMinParticlesAcross d0 of solid between any two of the loops (the fluid on the two sides of a
/// thinner solid would see each other's surface particles through it) and as many particles
/// across the hole (the flow in it is resolved like the flow round a body).
void check_holes(const Case& c, const LoadContext& ctx, std::size_t k) {
  const BodySpec& b = c.bodies[k];
  const std::string key = body_key(k, "holes");
  const real L = extent(b.vertices), len_eps = 1e-12 * L, area_eps = 1e-12 * L * L;
  const real need = kMinParticlesAcross * c.d0 * (1 - 1e-9);
  for (std::size_t h = 0; h < b.holes.size(); ++h) {
    const std::vector<Vec2>& hole = b.holes[h];
    const int line = ctx.item_line(key, h);
    check_loop(c, ctx, Loop{hole, key, h});
    if (loops_meet(hole, b.vertices, area_eps, len_eps) || !inside_loop(hole[0], b.vertices))
      throw ctx.error_at(key, line,
                         fmt::format("polygon hole holes[{}] does not lie inside the polygon's vertices: a hole "
                                     "must be enclosed by the solid",
                                     h));
    for (std::size_t g = 0; g < h; ++g)
      if (loops_meet(hole, b.holes[g], area_eps, len_eps) || inside_loop(hole[0], b.holes[g]) ||
          inside_loop(b.holes[g][0], hole))
        throw ctx.error_at(key, line,
                           fmt::format("polygon holes holes[{}] and holes[{}] overlap: merge them into one hole", g, h));
    const auto thin = [&](real gap, const std::string& other) {
      if (gap >= need) return;
      throw ctx.error_at(key, line,
                         fmt::format("{} is too thin for d0 = {:.6g} m: the solid between polygon hole holes[{}] and "
                                     "{} is {:.3g} m, only {:.3g} particles across; it needs at least {} (the "
                                     "fluid on its two sides would see each other through it)",
                                     body_text(b), c.d0, h, other, gap, gap / c.d0, kMinParticlesAcross));
    };
    thin(loop_gap(hole, b.vertices), "the outline (vertices)");
    for (std::size_t g = 0; g < h; ++g) thin(loop_gap(hole, b.holes[g]), fmt::format("holes[{}]", g));
    const real width = polygon_width(hole);
    if (width < need)
      throw ctx.error_at(key, line,
                         fmt::format("polygon hole holes[{}] of {} is too small for d0 = {:.6g} m: it is {:.3g} m "
                                     "across, only {:.3g} particles; the fluid in it needs at least {}",
                                     h, body_text(b), c.d0, width, width / c.d0, kMinParticlesAcross));
  }
}

}  // namespace

/// Polygons: each loop valid (check_loop), holes inside the outline, apart and wide enough.
void check_polygons(const Case& c, const LoadContext& ctx) {
  for (std::size_t k = 0; k < c.bodies.size(); ++k) {
    const BodySpec& b = c.bodies[k];
    if (b.shape != BodyShape::Polygon) continue;
    check_loop(c, ctx, Loop{b.vertices, body_key(k, "vertices"), std::nullopt});
    check_holes(c, ctx, k);
  }
}

/// A free body needs a density (its mass and moment of inertia).
void check_density(const Case& c, const LoadContext& ctx) {
  for (std::size_t k = 0; k < c.bodies.size(); ++k) {
    const BodySpec& b = c.bodies[k];
    if (b.motion != BodyMotion::Free || b.density > 0) continue;
    const std::string key = body_key(k, "density");
    if (!ctx.given.contains(key))
      throw ctx.error(key,
                      "missing density: a free body needs density > 0 kg/m^3 for its mass (or give "
                      "motion = \"fixed\" or \"prescribed\")");
    throw ctx.error(key, fmt::format("a free body needs density > 0 kg/m^3 for its mass, got {}", b.density));
  }
}

/// A prescribed schedule starts at t <= 0 and its times increase strictly.
void check_schedules(const Case& c, const LoadContext& ctx) {
  for (std::size_t k = 0; k < c.bodies.size(); ++k) {
    const std::vector<MotionKnot>& s = c.bodies[k].schedule;
    const std::string key = body_key(k, "schedule");
    if (!s.empty() && s[0].t > 0)
      throw ctx.error_at(key, ctx.item_line(key, 0),
                         fmt::format("the first row must be at t <= 0 so that the motion is defined from the "
                                     "start, got t = {} s",
                                     s[0].t));
    for (std::size_t i = 1; i < s.size(); ++i)
      if (!(s[i].t > s[i - 1].t))
        throw ctx.error_at(
            key, ctx.item_line(key, i),
            fmt::format("schedule times must increase strictly: schedule[{}] at t = {} s does not "
                        "come after schedule[{}] at t = {} s",
                        i, s[i].t, i - 1, s[i - 1].t));
  }
}

/// A fixed body does not move: a velocity would be silently ignored.
void check_fixed_bodies(const Case& c, const LoadContext& ctx) {
  for (std::size_t k = 0; k < c.bodies.size(); ++k) {
    const BodySpec& b = c.bodies[k];
    if (b.motion != BodyMotion::Fixed) continue;
    if (b.velocity.x != 0 || b.velocity.y != 0)
      throw ctx.error(
          body_key(k, "velocity"),
          fmt::format("a fixed body does not move, but velocity is {} (use motion = \"prescribed\")",
                      vec(b.velocity)));
    if (b.omega != 0)
      throw ctx.error(body_key(k, "omega"),
                      fmt::format("a fixed body does not move, but omega is {} rad/s (use motion = "
                                  "\"prescribed\")",
                                  b.omega));
  }
}

void check_body_sizes(const Case& c, const LoadContext& ctx) {
  for (std::size_t k = 0; k < c.bodies.size(); ++k) {
    const BodySpec& b = c.bodies[k];
    real width = 0;
    const char* what = "";
    const char* leaf = "";
    switch (b.shape) {
      case BodyShape::Circle:
        width = 2 * b.radius, what = "diameter", leaf = "radius";
        break;
      case BodyShape::Ellipse:
        width = 2 * std::min(b.semi_axes.x, b.semi_axes.y), what = "minor axis", leaf = "semi_axes";
        break;
      case BodyShape::Polygon:
        width = polygon_width(b.vertices), what = "width", leaf = "vertices";
        break;
      case BodyShape::HalfDisc:
        width = b.radius, what = "radius", leaf = "radius";
        break;
    }
    const real across = width / c.d0;
    if (across >= kMinParticlesAcross * (1 - 1e-9)) continue;  // exactly 10 across passes despite rounding
    throw ctx.error(body_key(k, leaf),
                    fmt::format("{} is too small for d0 = {:.6g} m: its smallest dimension ({}) is {:.6g} m, "
                                "only {:.3g} particles across; it needs at least {}",
                                body_text(b), c.d0, what, width, across, kMinParticlesAcross));
  }
}

/// Bodies lie inside the domain box along non-periodic axes. A fixed body may touch a domain
/// edge or reach past it (a block on the floor, a bump sunk into it: the scene leaves out its
/// part beyond the edge; check_walls_clear_of_bodies checks how it meets a wall there) but not
/// lie wholly beyond it; of the other bodies only a half_disc may touch an edge (it is meant to
/// sit on a wall with its flat side).
void check_bodies_in_domain(const Case& c, const LoadContext& ctx) {
  const real tol = 1e-6 * c.d0;
  const bool periodic[2] = {c.periodic_x, c.periodic_y};
  for (std::size_t k = 0; k < c.bodies.size(); ++k) {
    const BodySpec& b = c.bodies[k];
    const Outline o(b);
    const bool fixed = b.motion == BodyMotion::Fixed;
    const bool may_touch = fixed || b.shape == BodyShape::HalfDisc;
    for (int axis = 0; axis < 2; ++axis) {
      if (periodic[axis]) continue;
      const char name = axis == 0 ? 'x' : 'y';
      const real lo = axis == 0 ? o.lo.x : o.lo.y, hi = axis == 0 ? o.hi.x : o.hi.y;
      const real min = axis == 0 ? c.domain_min.x : c.domain_min.y;
      const real max = axis == 0 ? c.domain_max.x : c.domain_max.y;
      if (hi <= min + tol || lo >= max - tol)
        throw ctx.error(place_key(c, k),
                        fmt::format("{} lies wholly outside the domain: it spans {} = {:.9g} .. {:.9g} m, the domain "
                                    "{:.9g} .. {:.9g} m",
                                    body_text(b), name, lo, hi, min, max));
      for (const auto& [reach, edge, below] : {std::tuple{lo, min, true}, std::tuple{hi, max, false}}) {
        const real outside = below ? edge - reach : reach - edge;  // > 0: beyond the edge
        if (outside > tol && !fixed)
          throw ctx.error(
              place_key(c, k),
              fmt::format("{} lies outside the domain: it reaches {} = {:.9g} m, beyond the domain "
                          "edge {} = {:.9g} m (only a fixed body may reach past a domain edge)",
                          body_text(b), name, reach, name, edge));
        const bool wall_there = std::any_of(c.walls.begin(), c.walls.end(), [&](const WallSpec& w) {
          const real a = axis == 0 ? w.from.x : w.from.y, b = axis == 0 ? w.to.x : w.to.y;
          return w.shape == WallShape::Segment && std::fabs(a - edge) <= tol && std::fabs(b - edge) <= tol;
        });
        if (outside > tol && !wall_there)
          throw ctx.error(place_key(c, k),
                          fmt::format("{} reaches past the domain edge {} = {:.9g} m, where no wall lies: a fixed body "
                                      "may reach past a domain edge only through a wall along it",
                                      body_text(b), name, edge));
        if (outside >= -tol && !may_touch)
          throw ctx.error(
              place_key(c, k),
              fmt::format("{} touches the domain edge {} = {:.9g} m: leave fluid between them (only a "
                          "fixed body or a half_disc may sit on a domain edge)",
                          body_text(b), name, edge));
      }
    }
  }
}

/// Bodies must not overlap at t = 0, also across periodic boundaries: bounding circles as a
/// quick reject, circles exactly, other shapes by points sampled densely on both boundaries
/// (one inside the other also counts).
void check_body_overlap(const Case& c, const LoadContext& ctx) {
  const real tol = 1e-6 * c.d0;
  const std::vector<Vec2> shifts = periodic_shifts(c);
  std::vector<Outline> outlines;
  for (const BodySpec& b : c.bodies) outlines.emplace_back(b);
  // Samples: 2000 per boundary, more for large bodies (at most 0.05 d0 apart, up to 100000).
  const auto samples = [&](const Outline& o) {
    real n = o.perimeter() / (0.05 * c.d0);
    if (!(n > 2000)) n = 2000;  // also for a non-finite perimeter
    return o.boundary(static_cast<std::size_t>(std::min(n, 100000.0)));
  };
  for (std::size_t j = 0; j < outlines.size(); ++j) {
    for (std::size_t i = 0; i <= j; ++i) {
      const Outline &A = outlines[i], &B = outlines[j];
      for (const Vec2 shift : shifts) {  // B is moved by `shift`
        const bool self = i == j;
        if (self && shift.x == 0 && shift.y == 0) continue;
        const real d = norm(B.center + shift - A.center);
        if (d >= A.bound + B.bound - tol) continue;
        bool overlap = false;
        if (A.body->shape == BodyShape::Circle && B.body->shape == BodyShape::Circle) {
          overlap = d < A.body->radius + B.body->radius - tol;
        } else {
          for (const Vec2 p : samples(A))
            if ((overlap = B.contains(p - shift, tol))) break;
          if (!overlap)
            for (const Vec2 p : samples(B))
              if ((overlap = A.contains(p + shift, tol))) break;
        }
        if (!overlap) continue;
        const bool across = shift.x != 0 || shift.y != 0;
        if (self)
          throw ctx.error(place_key(c, j), fmt::format("{} overlaps its own periodic image: it is wider than "
                                                       "the periodic domain",
                                                       body_text(*B.body)));
        throw ctx.error(place_key(c, j),
                        fmt::format("{} overlaps {} (body[{}]) at t = 0{}", body_text(*B.body),
                                    body_text(*A.body), i, across ? " across the periodic boundary" : ""));
      }
    }
  }
}

}  // namespace particula::case_detail
