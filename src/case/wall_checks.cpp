// Checks of curved and turning walls and of the region the walls enclose (the fluid fills the
// region on the left of the walls, so every chain of walls must close or end on the domain's
// edge). The checks of straight walls, joints and chains are in checks.cpp.
#include <fmt/format.h>

#include <cmath>
#include <string>
#include <vector>

#include "internal.hpp"

namespace particula::case_detail {

std::string wall_key(std::size_t k, std::string_view leaf) { return fmt::format("wall[{}].{}", k, leaf); }

std::string wall_text(const Case& c, std::size_t k) { return fmt::format("wall '{}' (wall[{}])", c.walls[k].name, k); }

namespace {

std::string point_text(Vec2 v) { return format_toml_value(Value{v}); }

bool in_domain(Vec2 p, const Case& c, real tol) {
  return p.x >= c.domain_min.x - tol && p.x <= c.domain_max.x + tol && p.y >= c.domain_min.y - tol &&
         p.y <= c.domain_max.y + tol;
}

bool on_domain_edge(Vec2 p, const Case& c, real tol) {
  return std::fabs(p.x - c.domain_min.x) <= tol || std::fabs(p.x - c.domain_max.x) <= tol ||
         std::fabs(p.y - c.domain_min.y) <= tol || std::fabs(p.y - c.domain_max.y) <= tol;
}

/// Points of a wall about `step` apart (at least 64), ends included.
std::vector<Vec2> wall_points(const WallPiece& w, real step) {
  const int n = static_cast<int>(std::min(1e5, std::max(64.0, std::ceil(w.length() / step))));
  std::vector<Vec2> pts;
  for (int i = 0; i <= n; ++i) pts.push_back(w.point_at(static_cast<real>(i) / n));
  return pts;
}

}  // namespace

void check_arc_wall(const Case& c, const LoadContext& ctx, std::size_t k) {
  const WallSpec& w = c.walls[k];
  const WallPiece arc = w.piece();
  const real sweep = w.end_angle - w.start_angle;
  if (sweep == 0) throw ctx.error(wall_key(k, "end_angle"), "arc has zero length (end_angle == start_angle)");
  if (std::fabs(sweep) > 2 * M_PI * (1 + 1e-12))
    throw ctx.error(wall_key(k, "end_angle"),
                    fmt::format("{} turns through {:.9g} rad, more than a full circle (2 pi = 6.283185307179586): "
                                "|end_angle - start_angle| may be at most 2 pi",
                                wall_text(c, k), std::fabs(sweep)));
  if (arc.length() < 0.5 * c.d0)
    throw ctx.error(wall_key(k, "end_angle"),
                    fmt::format("{} is {:.3g} m long, shorter than d0/2 = {:.6g} m; make it longer or leave it out",
                                wall_text(c, k), arc.length(), 0.5 * c.d0));
  if (w.radius < c.h())
    throw ctx.error(wall_key(k, "radius"),
                    fmt::format("{} has radius {:.3g} m, below the smoothing length h = {:.6g} m: the single wall "
                                "layer cannot resolve a bend that tight; use a larger radius or a finer d0",
                                wall_text(c, k), w.radius, c.h()));
  if (w.velocity.x != 0 || w.velocity.y != 0)
    throw ctx.error(wall_key(k, "velocity"),
                    fmt::format("{} is an arc and cannot slide (velocity {}): to move it along itself, turn it "
                                "about its centre with wall[].omega and wall[].pivot",
                                wall_text(c, k), point_text(w.velocity)));
  for (const Vec2 p : wall_points(arc, 0.5 * c.d0))
    if (!in_domain(p, c, 1e-6 * c.d0))
      throw ctx.error(wall_key(k, "center"),
                      fmt::format("{} leaves the domain {} .. {} (it passes {}): the whole arc must lie in the domain",
                                  wall_text(c, k), point_text(c.domain_min), point_text(c.domain_max),
                                  point_text(p)));
}

/// An arc that runs along another wall (the same circle twice, or an arc over a segment's
/// stretch) puts two layers of wall particles on top of each other.
void check_arc_overlap(const Case& c, const LoadContext& ctx) {
  const real tol = 1e-6 * c.d0;
  for (std::size_t j = 0; j < c.walls.size(); ++j)
    for (std::size_t i = 0; i < c.walls.size(); ++i) {
      if (i == j || (c.walls[i].shape != WallShape::Arc && c.walls[j].shape != WallShape::Arc)) continue;
      const WallPiece a = c.walls[i].piece(), b = c.walls[j].piece();
      for (int q = 0; q < 16; ++q) {
        const WallNearest n = a.nearest(b.point_at((q + 0.5) / 16));
        if (n.distance > tol || n.s <= 0 || n.s >= 1) continue;
        throw ctx.error(wall_key(std::max(i, j), "shape"),
                        fmt::format("{} runs along {}: they share a stretch, which would put two layers of wall "
                                    "particles there; remove one or make them meet only at an end point",
                                    wall_text(c, std::max(i, j)), wall_text(c, std::min(i, j))));
      }
    }
}

/// A turning wall sweeps a disc round its pivot, which must lie in the domain (its particles
/// are placed by rotation, never wrapped), and it may share end points only with walls turning
/// with it (the joint would come apart).
void check_turning_walls(const Case& c, const LoadContext& ctx) {
  const real tol = 1e-6 * c.d0;
  for (std::size_t k = 0; k < c.walls.size(); ++k) {
    const WallSpec& w = c.walls[k];
    if (w.omega == 0) continue;
    if (w.velocity.x != 0 || w.velocity.y != 0)
      throw ctx.error(wall_key(k, "velocity"),
                      fmt::format("{} both slides (velocity {}) and turns (omega {:.6g} rad/s): give one of them",
                                  wall_text(c, k), point_text(w.velocity), w.omega));
    const real reach = w.piece().reach_from(w.pivot);
    for (const Vec2 far : {w.pivot - Vec2{reach, 0}, w.pivot + Vec2{reach, 0}, w.pivot - Vec2{0, reach},
                           w.pivot + Vec2{0, reach}})
      if (!in_domain(far, c, tol))
        throw ctx.error(wall_key(k, "pivot"),
                        fmt::format("{} turns about {} and reaches {:.6g} m from it, so it sweeps beyond the domain "
                                    "{} .. {}: a turning wall must stay in the domain as it turns (an arc turning "
                                    "about its own centre: set pivot to its center)",
                                    wall_text(c, k), point_text(w.pivot), reach, point_text(c.domain_min),
                                    point_text(c.domain_max)));
    for (std::size_t o = 0; o < c.walls.size(); ++o) {
      if (o == k) continue;
      const WallSpec& v = c.walls[o];
      const bool joined = norm(v.from - w.to) <= tol || norm(v.to - w.from) <= tol || norm(v.from - w.from) <= tol ||
                          norm(v.to - w.to) <= tol;
      if (joined && (v.omega != w.omega || norm(v.pivot - w.pivot) > tol))
        throw ctx.error(wall_key(k, "omega"),
                        fmt::format("{} turns (omega {:.6g} rad/s about {}) but shares an end point with {}, which "
                                    "does not turn with it: the joint would come apart; give the walls of a chain "
                                    "the same omega and pivot",
                                    wall_text(c, k), w.omega, point_text(w.pivot), wall_text(c, o)));
    }
  }
}

/// The fluid fills the region on the left of the walls: every end of a chain of walls must be
/// joined to another wall's end (or its own, a full circle or a wall across a periodic axis) or
/// lie on the domain's edge, and not on another wall's side (a T-junction, where "the left of the
/// walls" has no meaning).
void check_region_closed(const Case& c, const LoadContext& ctx) {
  const real tol = 1e-6 * c.d0;
  const Vec2 span = c.domain_max - c.domain_min;
  for (std::size_t k = 0; k < c.walls.size(); ++k)
    for (const bool is_to : {false, true}) {
      const Vec2 p = is_to ? c.walls[k].to : c.walls[k].from;
      bool joined = false;
      for (std::size_t o = 0; o < c.walls.size() && !joined; ++o) {
        const Vec2 q = is_to ? c.walls[o].from : c.walls[o].to;  // the other's opposite end
        joined = norm(periodic_separation(c, p, q)) <= tol && (o != k || norm(p - q) <= tol ||
                                                               norm(p - q) >= 0.5 * std::min(span.x, span.y));
      }
      if (joined) continue;
      const std::string leaf = is_to ? "to" : "from", verb = is_to ? "ends" : "starts";
      for (std::size_t o = 0; o < c.walls.size(); ++o) {
        if (o == k) continue;
        const WallNearest n = c.walls[o].piece().nearest(p);
        if (n.distance <= tol && n.s > 0 && n.s < 1)
          throw ctx.error(wall_key(k, c.walls[k].shape == WallShape::Arc ? "end_angle" : leaf),
                          fmt::format("{} {} at {}, on the side of {}: split {} there into two walls so that the "
                                      "chain runs on from one end to the next (the fluid fills the region on the left "
                                      "of the walls)",
                                      wall_text(c, k), verb, point_text(p), wall_text(c, o), wall_text(c, o)));
      }
      if (on_domain_edge(p, c, tol)) continue;
      throw ctx.error(wall_key(k, c.walls[k].shape == WallShape::Arc ? "end_angle" : leaf),
                      fmt::format("{} {} at {}, inside the domain and joined to no other wall: the region the walls "
                                  "enclose is not closed (the fluid fills the region on the left of the walls); "
                                  "continue the chain to the domain's edge or close it",
                                  wall_text(c, k), verb, point_text(p)));
    }
}

/// validation.exact = "spin_up" compares with fluid spinning up in one circular container that
/// turns about its centre, with nothing else in it and no force on the fluid.
void check_spin_up(const Case& c, const LoadContext& ctx) {
  if (c.exact != ExactSolution::SpinUp) return;
  const auto fail = [&](const std::string& why) {
    throw ctx.error("validation.exact",
                    "validation.exact = \"spin_up\" needs " + why +
                        " (the exact solution is fluid at rest in a circular container that turns at a constant rate "
                        "about its centre from t = 0)");
  };
  if (c.walls.size() != 1) fail(fmt::format("exactly one wall, the container; the case has {}", c.walls.size()));
  const WallSpec& w = c.walls[0];
  if (w.shape != WallShape::Arc || !w.piece().is_full_circle() || w.end_angle < w.start_angle)
    fail("the wall to be a full circle turning counter-clockwise (end_angle = start_angle + 2 pi), fluid inside");
  if (w.omega == 0 || norm(w.pivot - w.center) > 1e-6 * c.d0)
    fail("the wall to turn (wall[].omega not 0) about its centre (wall[].pivot = wall[].center)");
  if (!c.bodies.empty()) fail("no bodies");
  if (norm(c.body_force) > 0 || (c.gravity_in_fluid && norm(c.gravity) > 0))
    fail("no body force or gravity on the fluid");
  if (c.initial_flow != InitialFlow::Rest) fail("the fluid at rest at t = 0 (initial.flow = \"rest\")");
}

}  // namespace particula::case_detail
