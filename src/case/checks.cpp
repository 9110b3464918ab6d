// Consistency checks between keys, run after every key passed its own type and range check.
// To add one, write a function below and append it to kChecks.
#include <fmt/format.h>

#include <cmath>

#include "internal.hpp"

namespace particula::case_detail {
namespace {

std::string vec(Vec2 v) { return format_toml_value(Value{v}); }

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

/// Walls: non-zero length, endpoints in the domain, velocity along the wall.
void check_walls(const Case& c, const LoadContext& ctx) {
  const real tol = c.d0 * 1e-6;
  for (std::size_t k = 0; k < c.walls.size(); ++k) {
    const WallSpec& w = c.walls[k];
    const std::string key = fmt::format("wall[{}].", k);
    for (const auto& [end, p] : {std::pair{"from", w.from}, std::pair{"to", w.to}})
      if (!inside(p, c, tol))
        throw ctx.error(key + end, fmt::format("wall end point {} lies outside the domain {} .. {}", vec(p),
                                               vec(c.domain_min), vec(c.domain_max)));
    const Vec2 t = w.to - w.from;
    if (norm(t) == 0) throw ctx.error(key + "to", "wall has zero length (to == from)");
    if (std::fabs(cross(w.velocity, t)) > 1e-9 * norm(w.velocity) * norm(t))
      throw ctx.error(key + "velocity",
                      fmt::format("wall velocity must be tangential (parallel to to - from = {}), "
                                  "got {}",
                                  vec(t), vec(w.velocity)));
  }
}

using CrossCheck = void (*)(const Case&, const LoadContext&);

/// Run in this order (later checks may rely on earlier ones, e.g. walls on a valid domain).
constexpr CrossCheck kChecks[] = {check_domain, check_periodic_width, check_walls};

}  // namespace

void run_cross_checks(const Case& c, const LoadContext& ctx) {
  for (const CrossCheck check : kChecks) check(c, ctx);
}

}  // namespace particula::case_detail
