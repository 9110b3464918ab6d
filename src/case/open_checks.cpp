// Checks of open boundaries ([[inlet]], [[outlet]]; docs/method.md, "Open boundaries"),
// run by run_cross_checks after the checks of walls (check_open_boundaries) and of bodies
// (check_open_bodies). An open boundary is a straight segment on a bounded edge of the domain,
// the fluid on its left walking from `from` to `to`, with `layers` rows of buffer particles
// outside the domain behind it. The buffer's fields are set from a fit over the fluid beside the
// line, and the walls that end on the line are continued through the buffer; these checks keep
// what the buffer and the fit need: an edge of their own, walls at rest that close the region
// with them, no body and no other open boundary within reach.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "body_outline.hpp"
#include "internal.hpp"
#include "particula/solver/momentum_loads.hpp"

namespace particula::case_detail {
namespace {

/// One open boundary with where it comes from in the case file.
struct Open {
  const OpenSpec* spec;
  const char* section;  // "inlet" or "outlet"
  std::size_t index;

  /// "inlet[0].from".
  std::string key(std::string_view leaf) const { return fmt::format("{}[{}].{}", section, index, leaf); }
  /// "inlet 'in' (inlet[0])".
  std::string text() const { return fmt::format("{} '{}' ({}[{}])", section, spec->name, section, index); }
};

/// The inlets, then the outlets (the order of Case::open_boundaries).
std::vector<Open> open_list(const Case& c) {
  std::vector<Open> all;
  for (std::size_t k = 0; k < c.inlets.size(); ++k) all.push_back({&c.inlets[k], "inlet", k});
  for (std::size_t k = 0; k < c.outlets.size(); ++k) all.push_back({&c.outlets[k], "outlet", k});
  return all;
}

/// The depth L_b = layers d0 of the buffer behind `o`.
real buffer_depth(const Case& c, const OpenSpec& o) { return c.open_layers(o) * c.d0; }

/// An edge line of the domain box: x = value (axis 0) or y = value (axis 1).
struct Edge {
  int axis = 0;
  real value = 0;
  bool lower = true;  // the domain.min side

  char name() const { return axis == 0 ? 'x' : 'y'; }
  /// Unit normal pointing into the domain.
  Vec2 inward() const {
    const real s = lower ? 1 : -1;
    return axis == 0 ? Vec2{s, 0} : Vec2{0, s};
  }
};

/// The edge line both ends of the segment lie on (within tol), if any.
std::optional<Edge> edge_line(const Case& c, const OpenSpec& o, real tol) {
  for (int axis = 0; axis < 2; ++axis)
    for (const bool lower : {true, false}) {
      const real v = component(lower ? c.domain_min : c.domain_max, axis);
      if (std::fabs(component(o.from, axis) - v) <= tol && std::fabs(component(o.to, axis) - v) <= tol)
        return Edge{axis, v, lower};
    }
  return std::nullopt;
}

bool is_corner(const Case& c, Vec2 p, real tol) {
  const bool at_x = std::fabs(p.x - c.domain_min.x) <= tol || std::fabs(p.x - c.domain_max.x) <= tol;
  const bool at_y = std::fabs(p.y - c.domain_min.y) <= tol || std::fabs(p.y - c.domain_max.y) <= tol;
  return at_x && at_y;
}

bool is_wall_end(const Case& c, Vec2 p, real tol) {
  return std::any_of(c.walls.begin(), c.walls.end(),
                     [&](const WallSpec& w) { return norm(w.from - p) <= tol || norm(w.to - p) <= tol; });
}

/// Length that the segment [a, b] shares with the open segment o when both lie on one line
/// (within tol), else 0.
real shared_length(const OpenSpec& o, Vec2 a, Vec2 b, real tol) {
  const Vec2 u = o.tangent();
  if (std::fabs(cross(u, a - o.from)) > tol || std::fabs(cross(u, b - o.from)) > tol) return 0;
  const real s1 = dot(u, a - o.from), s2 = dot(u, b - o.from);
  return std::max(0.0, std::min(o.width(), std::max(s1, s2)) - std::max(0.0, std::min(s1, s2)));
}

/// Distance between the segments [p1, p2] and [q1, q2]: 0 where they meet, else the least
/// distance of an end point of one to the other (the least distance of two segments that do
/// not cross is always found at an end point).
real segments_distance(Vec2 p1, Vec2 p2, Vec2 q1, Vec2 q2, real tol) {
  if (segments_meet(p1, p2, q1, q2, tol * (norm(p2 - p1) + norm(q2 - q1)), tol)) return 0;
  return std::min({segment_distance(p1, q1, q2), segment_distance(p2, q1, q2), segment_distance(q1, p1, p2),
                   segment_distance(q2, p1, p2)});
}

/// Inlets and outlets share one set of names (the schema's `unique` holds within one array):
/// their outputs are named after them.
void check_open_names(const Case& c, const LoadContext& ctx) {
  for (std::size_t j = 0; j < c.outlets.size(); ++j)
    for (std::size_t i = 0; i < c.inlets.size(); ++i)
      if (c.outlets[j].name == c.inlets[i].name)
        throw ctx.error(fmt::format("outlet[{}].name", j),
                        fmt::format("duplicate outlet name \"{}\" (already used by inlet[{}].name): inlets and "
                                    "outlets share one set of names; rename one of them",
                                    c.outlets[j].name, i));
}

/// layers is 0 (derived) or 2 to 20 (the schema's range is [0, 20]): a buffer is at least two
/// rows deep.
void check_open_layers(const Case& c, const LoadContext& ctx) {
  for (const Open& o : open_list(c)) {
    if (o.spec->layers != 1) continue;
    throw ctx.error(o.key("layers"),
                    fmt::format("{} has layers = 1, but a buffer needs at least 2 rows of particles; give 0 (the "
                                "default: ceil(h / d0) + 1 = {} rows here, deeper than h = {:.3g} d0, so that the "
                                "fluid beside the line sees a full kernel) or 2 to 20",
                                o.text(), c.open_layers(OpenSpec{}), c.h_over_d0));
  }
}

/// Where an open boundary lies: at least 4 d0 wide, on an edge of the domain that is not
/// periodic, the fluid (its left side) inside, each end a domain corner or the end of a wall.
void check_open_segments(const Case& c, const LoadContext& ctx) {
  const real tol = 1e-6 * c.d0;
  for (const Open& o : open_list(c)) {
    const OpenSpec& s = *o.spec;
    if (!(s.width() >= 4 * c.d0))
      throw ctx.error(o.key("to"),
                      fmt::format("{} is {:.6g} m wide (from {} to {}), less than 4 d0 = {:.6g} m: the buffer needs "
                                  "a few columns of particles across; make the segment at least 4 d0 long",
                                  o.text(), s.width(), vec(s.from), vec(s.to), 4 * c.d0));
    const std::optional<Edge> e = edge_line(c, s, tol);
    if (!e)
      throw ctx.error(o.key("from"),
                      fmt::format("{} from {} to {} does not lie on an edge of the domain {} .. {}: an open "
                                  "boundary lies on one of the lines x = {:.9g}, x = {:.9g}, y = {:.9g} or "
                                  "y = {:.9g} m (both ends on the same line, within 1e-6 d0)",
                                  o.text(), vec(s.from), vec(s.to), vec(c.domain_min), vec(c.domain_max),
                                  c.domain_min.x, c.domain_max.x, c.domain_min.y, c.domain_max.y));
    const int along = 1 - e->axis;  // the axis the segment runs along
    for (const auto& [leaf, p] : {std::pair{"from", s.from}, std::pair{"to", s.to}})
      if (component(p, along) < component(c.domain_min, along) - tol ||
          component(p, along) > component(c.domain_max, along) + tol)
        throw ctx.error(o.key(leaf), fmt::format("{} {} at {}, outside the domain {} .. {}", o.text(),
                                                 leaf == std::string_view("from") ? "starts" : "ends", vec(p),
                                                 vec(c.domain_min), vec(c.domain_max)));
    if (e->axis == 0 ? c.periodic_x : c.periodic_y)
      throw ctx.error(o.key("from"),
                      fmt::format("{} lies on the domain edge {} = {:.9g} m, but the domain is periodic along {}: "
                                  "the fluid wraps around there, so there is no edge to enter or leave through; "
                                  "make domain.periodic false along {} or put it on another edge",
                                  o.text(), e->name(), e->value, e->name(), e->name()));
    if (!(dot(s.inward_normal(), e->inward()) > 0))
      throw ctx.error(o.key("from"),
                      fmt::format("the fluid would be on the right of {}, outside the domain (it lies on the "
                                  "domain edge {} = {:.9g} m; the fluid lies on the left walking from `from` to "
                                  "`to`, as for walls): list it the other way round, from = {} and to = {}",
                                  o.text(), e->name(), e->value, vec(s.to), vec(s.from)));
    for (const auto& [leaf, p] : {std::pair{"from", s.from}, std::pair{"to", s.to}}) {
      if (is_corner(c, p, tol) || is_wall_end(c, p, tol)) continue;
      throw ctx.error(o.key(leaf),
                      fmt::format("{} {} at {}, which is neither a corner of the domain nor the end of a wall: "
                                  "the walls and the open boundaries enclose the fluid together; end the "
                                  "segment at a corner or where a chain of walls ends (its `from` or `to`)",
                                  o.text(), leaf == std::string_view("from") ? "starts" : "ends", vec(p)));
    }
  }
}

/// No wall runs along an open boundary (the line is open there, not a wall), and no two open
/// boundaries share a stretch.
void check_open_overlaps(const Case& c, const LoadContext& ctx) {
  const real tol = 1e-6 * c.d0;
  const std::vector<Open> all = open_list(c);
  for (const Open& o : all)
    for (std::size_t w = 0; w < c.walls.size(); ++w) {
      const WallSpec& wall = c.walls[w];
      if (wall.shape == WallShape::Arc) continue;  // a circle meets a line at points only
      const real shared = shared_length(*o.spec, wall.from, wall.to, tol);
      if (shared <= tol) continue;
      throw ctx.error(o.key("from"),
                      fmt::format("{} runs along {} for {:.6g} m: the line is either open or a wall; shorten the "
                                  "wall so that it ends where the open boundary begins",
                                  wall_text(c, w), o.text(), shared));
    }
  for (std::size_t j = 0; j < all.size(); ++j)
    for (std::size_t i = 0; i < j; ++i) {
      const real shared = shared_length(*all[i].spec, all[j].spec->from, all[j].spec->to, tol);
      if (shared <= tol) continue;
      throw ctx.error(all[j].key("from"),
                      fmt::format("{} overlaps {} for {:.6g} m: two open boundaries cannot share a stretch of "
                                  "the line; make them meet at most at an end point",
                                  all[j].text(), all[i].text(), shared));
    }
}

/// A wall ending on an open boundary is continued through the buffer behind it, which only a
/// wall at rest allows: no wall that slides or turns has an end point on an open segment.
void check_open_moving_walls(const Case& c, const LoadContext& ctx) {
  const real tol = 1e-6 * c.d0;
  for (std::size_t w = 0; w < c.walls.size(); ++w) {
    const WallSpec& wall = c.walls[w];
    const bool slides = norm(wall.velocity) != 0;
    if (!slides && wall.omega == 0) continue;
    for (const Open& o : open_list(c))
      for (const Vec2 p : {wall.from, wall.to}) {
        if (segment_distance(p, o.spec->from, o.spec->to) > tol) continue;
        const std::string motion = slides ? fmt::format("slides (velocity {})", vec(wall.velocity))
                                          : fmt::format("turns (omega {:.6g} rad/s)", wall.omega);
        throw ctx.error(wall_key(w, slides ? "velocity" : "omega"),
                        fmt::format("{} {} and has an end at {} on {}: a wall that ends on an open boundary is "
                                    "continued through the buffer behind it, which only a wall at rest allows; "
                                    "end the moving wall elsewhere or leave out its motion",
                                    wall_text(c, w), motion, vec(p), o.text()));
      }
  }
}

/// A table profile: s strictly increasing within [0, width], every u >= 0 and one > 0 (the
/// schema asks for at least 2 rows and finite numbers).
void check_inlet_tables(const Case& c, const LoadContext& ctx) {
  for (std::size_t k = 0; k < c.inlets.size(); ++k) {
    const OpenSpec& s = c.inlets[k];
    if (s.profile != InletProfile::Table) continue;
    const std::string key = fmt::format("inlet[{}].table", k);
    const std::string text = fmt::format("inlet '{}' (inlet[{}])", s.name, k);
    const real width = s.width(), slack = 1e-9 * width;
    for (std::size_t i = 0; i < s.table.size(); ++i) {
      const Vec2 row = s.table[i];
      const auto fail = [&](const std::string& why) {
        return ctx.error_at(key, ctx.item_line(key, i), fmt::format("row [{}] = {} of {}: {}", i, vec(row), text, why));
      };
      if (row.x < -slack || row.x > width + slack)
        throw fail(fmt::format("s = {:.6g} m lies outside the segment [0, {:.6g}] m (s is the distance from `from` "
                               "along the segment)",
                               row.x, width));
      if (i > 0 && !(row.x > s.table[i - 1].x))
        throw fail(fmt::format("s must increase strictly from row to row, but the row before has s = {:.6g} m",
                               s.table[i - 1].x));
      if (row.y < 0)
        throw fail(fmt::format("the speed u = {:.6g} m/s is negative: an inlet's speed points into the domain "
                               "(u >= 0); fluid leaves through an [[outlet]]",
                               row.y));
    }
    const bool flows = std::any_of(s.table.begin(), s.table.end(), [](Vec2 r) { return r.y > 0; });
    if (!flows)
      throw ctx.error(key, fmt::format("every speed u of {}'s table is 0: no fluid would enter; give at least one "
                                       "u > 0, or leave the inlet out",
                                       text));
  }
}

/// Every inlet needs an outlet (the domain's volume is fixed), at least L_b + 2 h away: the fit
/// that sets one buffer reads the fluid up to L_b + h from its line, and the fluid within h of
/// the other line feels the other buffer.
void check_open_pairs(const Case& c, const LoadContext& ctx) {
  if (!c.inlets.empty() && c.outlets.empty())
    throw ctx.error("inlet[0]",
                    fmt::format("the case has {} inlet{} but no outlet: the fluid that enters would pile up, as the "
                                "domain's volume is fixed; add an [[outlet]]",
                                c.inlets.size(), c.inlets.size() == 1 ? "" : "s"));
  const real tol = 1e-6 * c.d0;
  const std::vector<Vec2> shifts = periodic_shifts(c);
  for (std::size_t j = 0; j < c.outlets.size(); ++j)
    for (std::size_t i = 0; i < c.inlets.size(); ++i) {
      const OpenSpec &in = c.inlets[i], &out = c.outlets[j];
      real gap = std::numeric_limits<real>::infinity();
      for (const Vec2 shift : shifts)
        gap = std::min(gap, segments_distance(in.from, in.to, out.from + shift, out.to + shift, tol));
      const real depth = std::max(buffer_depth(c, in), buffer_depth(c, out));
      const real need = depth + 2 * c.h();
      if (gap >= need - tol) continue;
      throw ctx.error(
          fmt::format("outlet[{}].from", j),
          fmt::format("outlet '{}' (outlet[{}]) comes {:.6g} m from inlet '{}' (inlet[{}]), closer than L_b + 2 h = "
                      "{:.6g} m (L_b = {:.6g} m, the deeper of their buffers; h = {:.6g} m): the fluid that sets one "
                      "buffer would feel the other; move them apart",
                      out.name, j, gap, in.name, i, need, depth, c.h()));
    }
}

}  // namespace

void check_open_boundaries(const Case& c, const LoadContext& ctx) {
  if (c.inlets.empty() && c.outlets.empty()) return;
  check_open_names(c, ctx);
  check_open_layers(c, ctx);
  check_open_segments(c, ctx);
  check_open_overlaps(c, ctx);
  check_open_moving_walls(c, ctx);
  check_inlet_tables(c, ctx);
  check_open_pairs(c, ctx);
  if (c.boundary != BoundaryModel::SingleLayer)
    throw ctx.error("numerics.boundary",
                    "numerics.boundary = \"dummy\" does not support open boundaries (the buffer's walls are "
                    "continued as single-layer walls); use \"single_layer\" (the default) or leave out the "
                    "[[inlet]] and [[outlet]] tables");
}

/// Every body starts on the fluid side of each open boundary's screen, at least delta_c from it
/// (its bounding circle, also through periodic boundaries): a body nearer would start in contact
/// with the screen or behind it, where it would cut off the fluid that sets the buffer.
void check_open_bodies(const Case& c, const LoadContext& ctx) {
  if (c.inlets.empty() && c.outlets.empty()) return;
  const real tol = 1e-6 * c.d0, delta_c = c.contact_distance();
  const std::vector<Vec2> shifts = periodic_shifts(c);
  const std::vector<Open> all = open_list(c);
  for (std::size_t k = 0; k < c.bodies.size(); ++k) {
    const Outline body(c.bodies[k]);
    for (const Open& o : all) {
      const real depth = buffer_depth(c, *o.spec);
      const real screen = c.open_screen_offset(*o.spec);
      const real need = screen + delta_c;
      real gap = std::numeric_limits<real>::infinity();
      for (const Vec2 shift : shifts)
        gap = std::min(gap, segment_distance(body.center + shift, o.spec->from, o.spec->to) - body.bound);
      if (gap >= need - tol) continue;
      throw ctx.error(
          place_key(c, k),
          fmt::format("{} comes {:.3g} m from {} at t = 0 (its bounding circle, of radius {:.6g} m about {}), closer "
                      "than {:.6g} m: the boundary's screen, which holds bodies back, lies {:.6g} m inside the "
                      "line ({}), and a body starts at least the contact distance delta_c = {:.6g} m beyond it; "
                      "move the body away from the open boundary",
                      body_text(c.bodies[k]), std::max(gap, 0.0), o.text(), body.bound, vec(body.center), need,
                      screen,
                      screen > depth + c.h() + tol
                          ? fmt::format("the band of the momentum loads, {} h = {:.6g} m, must not reach the "
                                        "buffer; numerics.force = \"momentum\"",
                                        kLoadBandReach, screen)
                          : fmt::format("L_b + h: the buffer depth L_b = {} d0 = {:.6g} m and h = {:.6g} m, the "
                                        "fluid the buffer's fit reads",
                                        c.open_layers(*o.spec), depth, c.h()),
                      delta_c));
    }
  }
}

}  // namespace particula::case_detail

namespace particula {

real Case::open_screen_offset(const OpenSpec& o) const {
  const real fit_reach = open_layers(o) * d0 + h();
  const real band = force == ForceModel::Momentum ? kLoadBandReach * h() : 0.0;
  return std::max(fit_reach, band);
}

}  // namespace particula
