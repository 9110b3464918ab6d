// Consistency checks between keys, run after every key passed its own type and range check.
// To add one, write a function below and append it to kChecks.
// Walls: on a domain edge with the fluid inside, not on a periodic boundary, no two on one
// stretch, joined head to tail (no gaps below d0/2, at most two per point), sliding only along a
// periodic axis, clear of bodies.
// Keys used by their shape or motion only; walls against bodies; no free body starting in
// contact. Bodies on their own and against each other: body_checks.cpp; curved and turning
// walls: wall_checks.cpp; scales, probes and time steps: cost_checks.cpp; inlets and outlets:
// open_checks.cpp.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

#include "body_outline.hpp"
#include "internal.hpp"

namespace particula::case_detail {
namespace {

/// domain.max must exceed domain.min in both components.
void check_domain(const Case& c, const LoadContext& ctx) {
  if (c.domain_max.x > c.domain_min.x && c.domain_max.y > c.domain_min.y) return;
  throw ctx.error("domain.max",
                  fmt::format("domain.max {} must be greater than domain.min {} in both components",
                              vec(c.domain_max), vec(c.domain_min)));
}

/// Along a periodic axis the domain must hold at least 3 h (else particles see their own images).
void check_periodic_width(const Case& c, const LoadContext& ctx) {
  const real widths[2] = {c.domain_max.x - c.domain_min.x, c.domain_max.y - c.domain_min.y};
  const bool periodic[2] = {c.periodic_x, c.periodic_y};
  for (int a = 0; a < 2; ++a) {
    if (!periodic[a] || widths[a] >= 3 * c.h()) continue;
    throw ctx.error("domain.periodic",
                    fmt::format("periodic along {} needs the domain to be at least 3 h = {:.6g} m wide "
                                "(h = h_over_d0 * d0 = {:.6g} m), but it is {:.6g} m wide",
                                a == 0 ? 'x' : 'y', 3 * c.h(), c.h(), widths[a]));
  }
}

/// True if p lies in the domain box, up to `tol`.
bool inside(Vec2 p, const Case& c, real tol) {
  return p.x >= c.domain_min.x - tol && p.x <= c.domain_max.x + tol && p.y >= c.domain_min.y - tol &&
         p.y <= c.domain_max.y + tol;
}

/// Walls: non-zero length, endpoints in the domain (an arc: all of it), velocity along the wall.
void check_walls(const Case& c, const LoadContext& ctx) {
  const real tol = c.d0 * 1e-6;
  for (std::size_t k = 0; k < c.walls.size(); ++k) {
    const WallSpec& w = c.walls[k];
    const std::string key = fmt::format("wall[{}].", k);
    if (w.shape == WallShape::Arc) {
      check_arc_wall(c, ctx, k);
      continue;
    }
    for (const auto& [end, p] : {std::pair{"from", w.from}, std::pair{"to", w.to}})
      if (!inside(p, c, tol))
        throw ctx.error(key + end, fmt::format("wall end point {} lies outside the domain {} .. {}", vec(p),
                                               vec(c.domain_min), vec(c.domain_max)));
    const Vec2 t = w.to - w.from;
    if (norm(t) == 0) throw ctx.error(key + "to", "wall has zero length (to == from)");
    if (norm(t) < 0.5 * c.d0)
      throw ctx.error(
          key + "to",
          fmt::format("wall '{}' is {:.3g} m long, shorter than d0/2 = {:.6g} m: its two end particles "
                      "would be that close (the time step shrinks with the closest pair); make it at "
                      "least d0/2 long or leave it out",
                      w.name, norm(t), 0.5 * c.d0));
    if (std::fabs(cross(w.velocity, t)) > 1e-9 * norm(w.velocity) * norm(t))
      throw ctx.error(key + "velocity",
                      fmt::format("wall velocity must be tangential (parallel to to - from = {}), "
                                  "got {}",
                                  vec(t), vec(w.velocity)));
  }
}

// ---------------------------------------------------------------------------------------------
// Bodies.

/// Members used only for some choices (body[].radius for circles and half-discs) must not be
/// given for others.
void check_unused_keys(const Case& c, const LoadContext& ctx) {
  for (const SectionSpec& sec : case_sections()) {
    if (!sec.array) continue;
    for (std::size_t i = 0; i < sec.size(c); ++i) {
      for (const KeySpec& s : case_schema()) {
        if (s.section() != sec.name || s.used_for(c, i)) continue;
        const std::string key = concrete_key(s.key, i);
        if (!ctx.given.contains(key)) continue;
        const KeySpec& decider = *find_key(s.used_when->key);
        throw ctx.error(key, fmt::format("not used by {} '{}' (only by {} {})", decider.leaf(),
                                         std::get<std::string>(*decider.bind.get(c, i)), decider.leaf(),
                                         fmt::join(s.used_when->values, ", ")));
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Walls among themselves and against bodies. The fluid lies on the left of a wall walking from
// `from` to `to` (its normal is the left normal); the scene joins two walls into a corner where
// one's `to` is the other's `from`, and leaves out wall particles within d0/2 of a body. A case
// that breaks these rules loads but fails at the first step (NaN), so it is stopped here.

Vec2 unit(Vec2 v) { return v / norm(v); }

/// Normal on the fluid side of a wall.
Vec2 left_normal(const WallSpec& w) {
  const Vec2 t = unit(w.to - w.from);
  return {-t.y, t.x};
}

/// b - a, to the nearest periodic image along periodic axes (as Domain::separation, which the
/// scene uses to decide whether two wall ends are one point).
Vec2 separation(const Case& c, Vec2 a, Vec2 b) { return periodic_separation(c, b, a); }

/// An edge line of the domain box: x = value (axis 0) or y = value (axis 1).
struct DomainEdge {
  int axis = 0;
  real value = 0;
  bool lower = true;  // domain.min side

  char name() const { return axis == 0 ? 'x' : 'y'; }
  /// Unit normal pointing into the domain.
  Vec2 inward() const {
    const real s = lower ? 1 : -1;
    return axis == 0 ? Vec2{s, 0} : Vec2{0, s};
  }
};

/// The domain edge a wall lies on (both ends on its line, within tol), if any.
std::optional<DomainEdge> edge_of(const Case& c, const WallSpec& w, real tol) {
  if (w.shape == WallShape::Arc) return std::nullopt;
  for (int axis = 0; axis < 2; ++axis)
    for (const bool lower : {true, false}) {
      const real v = component(lower ? c.domain_min : c.domain_max, axis);
      if (std::fabs(component(w.from, axis) - v) <= tol && std::fabs(component(w.to, axis) - v) <= tol)
        return DomainEdge{axis, v, lower};
    }
  return std::nullopt;
}

bool periodic_along(const Case& c, int axis) { return axis == 0 ? c.periodic_x : c.periodic_y; }

/// A wall may not lie on the boundary of a periodic axis: the fluid wraps around there, so the
/// fluid beyond the boundary (its periodic image) would stand on the wall's right side.
void check_walls_off_periodic_edges(const Case& c, const LoadContext& ctx) {
  for (std::size_t k = 0; k < c.walls.size(); ++k) {
    const std::optional<DomainEdge> e = edge_of(c, c.walls[k], 1e-6 * c.d0);
    if (!e || !periodic_along(c, e->axis)) continue;
    throw ctx.error(
        wall_key(k, "from"),
        fmt::format("{} lies on the domain edge {} = {:.9g} m, but the domain is periodic along {}: "
                    "the fluid wraps around that edge and would be on both sides of the wall; "
                    "remove the wall or make domain.periodic false along {}",
                    wall_text(c, k), e->name(), e->value, e->name(), e->name()));
  }
}

/// A wall on an edge of the domain box must have the fluid (its left side) inside the box.
void check_wall_orientation(const Case& c, const LoadContext& ctx) {
  for (std::size_t k = 0; k < c.walls.size(); ++k) {
    const std::optional<DomainEdge> e = edge_of(c, c.walls[k], 1e-6 * c.d0);
    if (!e || dot(left_normal(c.walls[k]), e->inward()) > 0) continue;
    throw ctx.error(
        wall_key(k, "from"),
        fmt::format("the fluid would be on the right of {} (it lies on the domain edge {} = {:.9g} "
                    "m; the fluid lies on the left walking from `from` to `to`): swap from and to",
                    wall_text(c, k), e->name(), e->value));
  }
}

/// Two walls on one line sharing a stretch (a duplicated wall, or a wall repeated in parts) put
/// two layers of wall particles on top of each other.
void check_wall_overlap(const Case& c, const LoadContext& ctx) {
  const real tol = 1e-6 * c.d0;
  for (std::size_t j = 0; j < c.walls.size(); ++j) {
    for (std::size_t i = 0; i < j; ++i) {
      const WallSpec &a = c.walls[i], &b = c.walls[j];
      if (a.shape == WallShape::Arc || b.shape == WallShape::Arc) continue;  // check_arc_overlap
      const Vec2 u = unit(a.to - a.from);
      if (std::fabs(cross(u, b.from - a.from)) > tol || std::fabs(cross(u, b.to - a.from)) > tol) continue;
      const real s1 = dot(u, b.from - a.from), s2 = dot(u, b.to - a.from);
      const real shared = std::min(norm(a.to - a.from), std::max(s1, s2)) - std::max(0.0, std::min(s1, s2));
      if (shared <= tol) continue;  // collinear, meeting at most at an end point
      const bool same = norm(b.from - a.from) <= tol && norm(b.to - a.to) <= tol;
      const bool reversed = norm(b.from - a.to) <= tol && norm(b.to - a.from) <= tol;
      const std::string what = same ? "duplicates" : reversed ? "duplicates (reversed)" : "overlaps";
      throw ctx.error(
          wall_key(j, "from"),
          fmt::format("{} {} {}: they share {:.6g} m of the same line, which would put two layers "
                      "of wall particles there; remove one or make them meet only at an end point",
                      wall_text(c, j), what, wall_text(c, i), shared));
    }
  }
}

/// One end point of a wall.
struct WallEnd {
  std::size_t wall;
  bool is_to;  // `to`, else `from`

  Vec2 at(const Case& c) const { return is_to ? c.walls[wall].to : c.walls[wall].from; }
  const char* leaf() const { return is_to ? "to" : "from"; }
  const char* verb() const { return is_to ? "ends" : "starts"; }
};

/// Distance between two wall ends as the scene sees it (through periodic boundaries), or
/// infinity for the two ends of one wall unless they face each other across a periodic
/// boundary (a wall's own length is not a gap).
real end_gap(const Case& c, WallEnd p, WallEnd q) {
  const Vec2 direct = q.at(c) - p.at(c), wrapped = separation(c, p.at(c), q.at(c));
  if (p.wall == q.wall && norm(direct) - norm(wrapped) <= 1e-6 * c.d0)
    return std::numeric_limits<real>::infinity();
  return norm(wrapped);
}

/// All wall ends, in case order (from, then to).
std::vector<WallEnd> wall_ends(const Case& c) {
  std::vector<WallEnd> ends;
  for (std::size_t k = 0; k < c.walls.size(); ++k) ends.insert(ends.end(), {{k, false}, {k, true}});
  return ends;
}

/// Ends closer than d0/2 must be one point: the scene joins only equal points, so a chain meant
/// to be closed that is not has a hole the size of the gap (and two corners that overlap).
void check_wall_gaps(const Case& c, const LoadContext& ctx) {
  const std::vector<WallEnd> ends = wall_ends(c);
  for (std::size_t q = 0; q < ends.size(); ++q)
    for (std::size_t p = 0; p < q; ++p) {
      const real gap = end_gap(c, ends[p], ends[q]);
      if (gap <= 1e-6 * c.d0 || gap >= 0.5 * c.d0) continue;
      const WallEnd &a = ends[p], &b = ends[q];
      throw ctx.error(wall_key(b.wall, b.leaf()),
                      fmt::format("{} {} at {}, a gap of {:.3g} m from where {} {} ({}): end points closer "
                                  "than d0/2 = {:.6g} m must be the same point to join the walls; make them "
                                  "equal, or at least d0/2 apart",
                                  wall_text(c, b.wall), b.verb(), vec(b.at(c)), gap, wall_text(c, a.wall),
                                  a.verb(), vec(a.at(c)), 0.5 * c.d0));
    }
}

/// At most two walls meet at a point: the scene makes one corner of two walls.
void check_wall_joints(const Case& c, const LoadContext& ctx) {
  const std::vector<WallEnd> ends = wall_ends(c);
  for (std::size_t q = 0; q < ends.size(); ++q) {
    std::vector<std::string> names;  // the walls whose ends meet at ends[q], up to q
    for (std::size_t p = 0; p <= q; ++p)
      if (p == q || end_gap(c, ends[p], ends[q]) <= 1e-6 * c.d0) names.push_back(wall_text(c, ends[p].wall));
    if (names.size() <= 2) continue;
    throw ctx.error(wall_key(ends[q].wall, ends[q].leaf()),
                    fmt::format("{} wall ends meet at {}: {}; at most two walls may share an end point (one "
                                "ending where the other starts)",
                                names.size(), vec(ends[q].at(c)), fmt::join(names, ", ")));
  }
}

/// Two walls joined at an end point must run head to tail (one's `to` is the other's `from`):
/// two that both start or both end there have the fluid on opposite sides of the chain.
void check_wall_chains(const Case& c, const LoadContext& ctx) {
  const std::vector<WallEnd> ends = wall_ends(c);
  const real tol = 1e-6 * c.d0;
  for (std::size_t q = 0; q < ends.size(); ++q)
    for (std::size_t p = 0; p < q; ++p) {
      const WallEnd &a = ends[p], &b = ends[q];
      if (a.is_to != b.is_to || end_gap(c, a, b) > tol) continue;
      // The one to turn round: not a wall on a domain edge (those are oriented already).
      const std::size_t turn = edge_of(c, c.walls[b.wall], tol) ? a.wall : b.wall;
      throw ctx.error(
          wall_key(b.wall, b.leaf()),
          fmt::format("{} and {} both {} at {}: they have opposite orientations (the fluid lies on "
                      "the left walking from `from` to `to`), so the fluid would be on different "
                      "sides of the chain; swap from and to of {} so that one ends where the other "
                      "starts",
                      wall_text(c, b.wall), wall_text(c, a.wall), b.is_to ? "end" : "start", vec(b.at(c)),
                      wall_text(c, turn)));
    }
}

/// A sliding wall (non-zero velocity) translates along itself: it must run along a periodic axis,
/// where its particles wrap around, and share no end point with another wall (the joint would
/// come apart). In a closed box its particles would run into the next wall after d0/|v| and the
/// time step collapse (a lid-driven cavity cannot be made this way).
void check_sliding_walls(const Case& c, const LoadContext& ctx) {
  const real tol = 1e-6 * c.d0;
  const std::vector<WallEnd> ends = wall_ends(c);
  for (std::size_t k = 0; k < c.walls.size(); ++k) {
    const WallSpec& w = c.walls[k];
    if (norm(w.velocity) == 0) continue;
    const Vec2 t = w.to - w.from;
    const bool along_x = std::fabs(t.y) <= tol, along_y = std::fabs(t.x) <= tol;
    if (!(along_x && c.periodic_x) && !(along_y && c.periodic_y))
      throw ctx.error(
          wall_key(k, "velocity"),
          fmt::format(
              "{} slides (velocity {}), but it does not run along a periodic axis of the domain: a sliding "
              "wall moves along itself, so its particles would run into the next wall or out of the domain "
              "after d0/|v| = {:.3g} s; sliding walls are for channels periodic along the wall "
              "(domain.periodic), e.g. Couette flow",
              wall_text(c, k), vec(w.velocity), c.d0 / norm(w.velocity)));
    for (const WallEnd& e : ends) {
      if (e.wall != k) continue;
      for (const WallEnd& o : ends)
        if (o.wall != k && end_gap(c, e, o) <= tol)
          throw ctx.error(
              wall_key(k, "velocity"),
              fmt::format("{} slides (velocity {}) but {} where {} {}: the joint would come apart as "
                          "it slides; a sliding wall must not share an end point with another wall",
                          wall_text(c, k), vec(w.velocity), e.verb(), wall_text(c, o.wall), o.verb()));
    }
  }
}

/// A flat side of a body: from p to q, with its outward normal.
struct FlatSide {
  Vec2 p, q, out;
};

/// The flat sides of a body at t = 0 (a half_disc's, a polygon's edges); none for round shapes.
std::vector<FlatSide> flat_sides(const Outline& o) {
  const BodySpec& b = *o.body;
  std::vector<FlatSide> sides;
  const auto world = [&](Vec2 q) { return o.center + rotate(q, o.cs, o.sn); };
  if (b.shape == BodyShape::HalfDisc)
    sides.push_back({world({0, -b.radius}), world({0, b.radius}), rotate({-1, 0}, o.cs, o.sn)});
  if (b.shape == BodyShape::Polygon) {
    const real turn = twice_area(o.verts) > 0 ? 1 : -1;  // outward = right of each edge if counter-clockwise
    for (std::size_t i = 0; i < o.verts.size(); ++i) {
      const Vec2 p = o.verts[i], q = o.verts[(i + 1) % o.verts.size()], e = unit(q - p);
      sides.push_back({p, q, turn * Vec2{e.y, -e.x}});
    }
  }
  return sides;
}

/// Whether a fixed body stands on the wall [a, b] the way the scene builds it (place_on_walls
/// leaves out the body's samples that face into a wall within d0/2, and makes the corners where
/// its free side meets the wall into junctions): a flat side lies on the wall's line facing into
/// the wall and shares a stretch with it, and no part of the body reaches past that line where
/// the wall is. `samples` are points on the body's boundary.
bool stands_on(const Outline& o, const std::vector<Vec2>& samples, const WallPiece& w, real tol) {
  if (o.body->motion != BodyMotion::Fixed || w.is_arc()) return false;
  const Vec2 a = w.start(), b = w.end();
  const Vec2 u = unit(b - a), n{-u.y, u.x};
  const real L = norm(b - a);
  constexpr real antiparallel = -0.999;  // as place_on_walls
  const auto on_wall = [&](const FlatSide& s) {
    const real s1 = dot(u, s.p - a), s2 = dot(u, s.q - a);
    return std::fabs(dot(n, s.p - a)) <= tol && std::fabs(dot(n, s.q - a)) <= tol &&
           dot(s.out, n) < antiparallel &&
           std::min(L, std::max(s1, s2)) - std::max(0.0, std::min(s1, s2)) > tol;
  };
  const std::vector<FlatSide> sides = flat_sides(o);
  if (std::none_of(sides.begin(), sides.end(), on_wall)) return false;
  return std::none_of(samples.begin(), samples.end(), [&](Vec2 p) {
    const real along = dot(u, p - a);
    return dot(n, p - a) < -tol && along > tol && along < L - tol;
  });
}

/// Whether a wall runs through the inside of a body (deeper than tol), tested at points `step`
/// apart.
bool cuts_through(const Outline& o, const WallPiece& w, real step, real tol) {
  const real n = std::min(1e6, std::ceil(w.length() / step));
  for (real i = 0; i <= n; ++i)
    if (o.contains(w.point_at(i / n), tol)) return true;
  return false;
}

/// Smallest angle between a fixed body's surface and a wall where they cross.
constexpr real kMinCrossingAngle = M_PI / 6;

/// How deep p lies inside the body (0 outside), to 1e-6 of `reach`, looked for up to `reach`.
real depth_inside(const Outline& o, Vec2 p, real reach) {
  if (!o.contains(p, 0)) return 0;
  real lo = 0, hi = reach;
  for (int it = 0; it < 20; ++it) {
    const real m = 0.5 * (lo + hi);
    (o.contains(p, m) ? lo : hi) = m;
  }
  return lo;
}

/// A fixed body crossed by wall w (a block sunk into the floor, a bump, a body cut by the
/// domain's edge; the scene leaves out its part beyond the wall and makes each crossing a
/// junction corner): it must meet the wall at kMinCrossingAngle or more, or the fluid in the
/// wedge between them is thinner than d0 over several d0 (a body barely crossing, or touching
/// tangentially). The angle comes from how fast the wall goes into the body past the crossing.
void check_crossing_angles(const Case& c, const LoadContext& ctx, std::size_t k, const Outline& o,
                           std::size_t w) {
  const WallPiece piece = c.walls[w].piece();
  std::size_t crossings = 0;
  const real step = 0.05 * c.d0, delta = 0.25 * c.d0;
  const real n = std::min(1e6, std::ceil(piece.length() / step));
  bool was_inside = o.contains(piece.point_at(0), 0);
  for (real i = 1; i <= n; ++i) {
    const bool inside = o.contains(piece.point_at(i / n), 0);
    if (inside == was_inside) continue;
    real a = (i - 1) / n, b = i / n;  // refine the crossing
    for (int it = 0; it < 40; ++it) {
      const real m = 0.5 * (a + b);
      (o.contains(piece.point_at(m), 0) == was_inside ? a : b) = m;
    }
    was_inside = inside;
    ++crossings;
    const Vec2 x = piece.point_at(0.5 * (a + b));
    const Vec2 into =
        (inside ? 1.0 : -1.0) * piece.tangent_at(0.5 * (a + b));  // along the wall into the body
    const real sine = std::min(1.0, depth_inside(o, x + delta * into, delta) / delta);
    const real angle = std::asin(sine);
    if (angle >= kMinCrossingAngle * (1 - 1e-6)) continue;
    throw ctx.error(
        place_key(c, k),
        fmt::format("{} meets {} at {:.3g} degrees at [{:.6g}, {:.6g}] at t = 0, less than {:.0f}: the fluid "
                    "in the wedge "
                    "between them would be thinner than d0 over several d0; sink the body deeper into "
                    "the wall, or move it at least d0/2 clear of it",
                    body_text(c.bodies[k]), wall_text(c, w), angle * 180 / M_PI, x.x, x.y,
                    kMinCrossingAngle * 180 / M_PI));
  }
  if (crossings == 0)
    throw ctx.error(place_key(c, k),
                    fmt::format("{} lies inside {} at t = 0: a wall may cross a fixed body, not hide "
                                "in it; leave the wall out or move it",
                                wall_text(c, w), body_text(c.bodies[k])));
}

/// A wall that crosses a body or passes within d0/2 of it at t = 0, also across periodic
/// boundaries, breaks the scene: the wall particles within d0/2 of the body are left out (a
/// hole in the wall) and a body crossing the wall has fluid inside it. Only a fixed body may
/// stand on a wall, with a flat side (stands_on), or cross it (check_crossing_angles).
void check_walls_clear_of_bodies(const Case& c, const LoadContext& ctx) {
  const real tol = 1e-6 * c.d0, reach = 0.5 * c.d0 * (1 - 1e-9);  // as the scene's near_body
  const std::vector<Vec2> shifts = periodic_shifts(c);  // of the body; the wall is moved the other way
  for (std::size_t k = 0; k < c.bodies.size(); ++k) {
    const Outline o(c.bodies[k]);
    std::vector<Vec2> samples;  // 0.01 d0 apart (at least 2000, at most 200000), made when needed
    for (std::size_t w = 0; w < c.walls.size(); ++w)
      for (const Vec2 shift : shifts) {
        const WallPiece piece = c.walls[w].piece().moved({}, 0, -1.0 * shift);
        if (piece.nearest(o.center).distance >= o.bound + reach) continue;
        if (samples.empty()) {
          const real n = o.perimeter() / (0.01 * c.d0);
          samples = o.boundary(static_cast<std::size_t>(n > 2000 ? std::min(n, 2e5) : 2000));  // NaN: 2000
        }
        const real gap = gap_to_wall(o, samples, piece);
        const bool across = shift.x != 0 || shift.y != 0;
        if (gap >= reach || (!across && stands_on(o, samples, piece, tol))) continue;
        const std::string where = across ? " across the periodic boundary" : "";
        const bool fixed = c.bodies[k].motion == BodyMotion::Fixed;
        const bool at_rest = c.walls[w].omega == 0 && norm(c.walls[w].velocity) == 0;
        if (cuts_through(o, piece, 0.05 * c.d0, tol) && fixed && !across && at_rest) {
          check_crossing_angles(c, ctx, k, o, w);
          continue;
        }
        if (cuts_through(o, piece, 0.05 * c.d0, tol))
          throw ctx.error(
              place_key(c, k),
              fmt::format("{} cuts through {} at t = 0{}: move the body clear of the wall (only a "
                          "fixed body may stand on a wall, with a flat side on it, or cross a wall at rest)",
                          wall_text(c, w), body_text(c.bodies[k]), where));
        const std::string near = gap <= tol ? "touches" : fmt::format("passes {:.3g} m from", gap);
        throw ctx.error(
            place_key(c, k),
            fmt::format("{} {} {} at t = 0{}, closer than d0/2 = {:.6g} m (the wall particles there would be "
                        "left out): move the body at least d0/2 from the wall (only a fixed body may stand "
                        "on a wall, with a flat side on it, or cross a wall at rest)",
                        wall_text(c, w), near, body_text(c.bodies[k]), where, 0.5 * c.d0));
      }
  }
}

/// Gap between an outline and a wall segment: exact for a circle, otherwise from its boundary points.
real wall_gap(const Outline& A, const WallSpec& w, std::size_t points) {
  const WallPiece piece = w.piece();
  if (A.body->shape == BodyShape::Circle) return piece.nearest(A.center).distance - A.body->radius;
  real gap = std::numeric_limits<real>::infinity();
  for (const Vec2 p : A.boundary(points)) gap = std::min(gap, piece.nearest(p).distance);
  return gap;
}

/// A free body must not start in contact: at t = 0 its gap to every wall and to every other body
/// must be at least the contact distance delta_c (collision.range, or its model's default); the
/// paper's force meets a wall as the body's mirror image, so there half of it. A body that starts
/// inside the contact distance is pushed off by the full contact force in the first step.
void check_initial_contacts(const Case& c, const LoadContext& ctx) {
  if (!c.contacts_active()) return;
  const bool paper = c.collision_model == ContactModel::Paper;
  const real delta_c = c.contact_distance();
  const std::string model = paper ? "paper" : "spring_dashpot";
  const std::string source =
      c.collision_range > 0
          ? "collision.range"
          : fmt::format("{} d0, the default for collision.model \"{}\"", paper ? 3 : 0.5, model);
  const auto fail = [&](std::size_t k, const std::string& other, real gap, real limit, const char* note) {
    throw ctx.error(
        place_key(c, k),
        fmt::format("{} starts in contact with {}: its gap at t = 0 is {:.3g} m, below {:.3g} m{} (the "
                    "contact distance delta_c = {:.3g} m: {}); move it away or set a smaller "
                    "collision.range",
                    body_text(c.bodies[k]), other, gap, limit, note, delta_c, source));
  };
  constexpr std::size_t kPoints = 2000;
  const real tol = 1e-6 * c.d0;  // a gap of exactly delta_c, up to round-off, is not yet a contact
  const std::vector<Vec2> shifts = periodic_shifts(c);
  std::vector<Outline> outlines;
  for (const BodySpec& b : c.bodies) outlines.emplace_back(b);
  const auto is_free = [&](std::size_t k) { return c.bodies[k].motion == BodyMotion::Free; };
  for (std::size_t k = 0; k < c.bodies.size(); ++k) {
    if (!is_free(k)) continue;
    const Outline& A = outlines[k];
    const real wall_limit = paper ? 0.5 * delta_c : delta_c;
    for (std::size_t w = 0; w < c.walls.size(); ++w) {
      const real gap = wall_gap(A, c.walls[w], kPoints);
      if (gap < wall_limit - tol)
        fail(k, fmt::format("wall '{}' (wall[{}])", c.walls[w].name, w), gap, wall_limit,
             paper ? ", half the contact distance (P.38 meets a wall as the body's mirror image)" : "");
    }
    for (std::size_t j = 0; j < c.bodies.size(); ++j) {
      if (j == k || (is_free(j) && j < k)) continue;  // a pair of free bodies once
      const Outline& B = outlines[j];
      for (const Vec2 shift : shifts) {
        if (norm(B.center + shift - A.center) >= A.bound + B.bound + delta_c) continue;
        const real gap = outline_gap(A, B, shift, kPoints);
        if (gap < delta_c - tol)
          fail(k, fmt::format("{} (body[{}])", body_text(*B.body), j), gap, delta_c, "");
      }
    }
  }
}

using CrossCheck = void (*)(const Case&, const LoadContext&);

/// Run in this order (later checks may rely on earlier ones, e.g. walls on a valid domain, the
/// geometric body checks on valid polygons).
constexpr CrossCheck kChecks[] = {check_domain,
                                  check_magnitudes,
                                  check_periodic_width,
                                  check_walls,
                                  check_walls_off_periodic_edges,
                                  check_wall_orientation,
                                  check_wall_overlap,
                                  check_wall_gaps,
                                  check_wall_joints,
                                  check_wall_chains,
                                  check_sliding_walls,
                                  check_arc_overlap,
                                  check_turning_walls,
                                  check_region_closed,
                                  check_wall_regions,
                                  check_spin_up,
                                  check_unused_keys,
                                  check_open_boundaries,
                                  check_polygons,
                                  check_density,
                                  check_schedules,
                                  check_fixed_bodies,
                                  check_body_sizes,
                                  check_bodies_in_domain,
                                  check_body_overlap,
                                  check_walls_clear_of_bodies,
                                  check_initial_contacts,
                                  check_open_bodies,
                                  check_probes,
                                  check_references,
                                  check_mach,
                                  check_time_steps,
                                  check_prescribed_paths};

}  // namespace

void run_cross_checks(const Case& c, const LoadContext& ctx) {
  for (const CrossCheck check : kChecks) check(c, ctx);
}

}  // namespace particula::case_detail
