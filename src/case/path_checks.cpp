// Load check of prescribed motion: a prescribed body's path, integrated from its schedule (or
// its constant velocity and omega) up to time.end, does not run into a wall, out of the domain
// or into another body that does not give way (fixed or prescribed). No contact acts on a
// prescribed body: on a path into a wall the fluid caught between is crushed and the time step
// collapses onto the trapped pair. Coming close is allowed (the film is squeezed out, as in the
// robustness case prescribed_squeeze, down to 0.1 d0); touching, to within kTouch, is not.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "body_outline.hpp"
#include "internal.hpp"
#include "particula/bodies/rigid_motion.hpp"
#include "particula/geometry/shape.hpp"

namespace particula::case_detail {
namespace {

/// The test's resolution: a gap below it is contact (the boundary is sampled at half of it).
constexpr real kTouch = 0.05;  // of d0

/// A point of the body that moves fastest moves at most this fast: |V| + |Omega| r_max over
/// the schedule (velocities are piecewise linear, so their largest values are at the knots).
real path_speed(const BodySpec& b, real bound) {
  if (b.schedule.empty()) return norm(b.velocity) + std::fabs(b.omega) * bound;
  real s = 0;
  for (const MotionKnot& k : b.schedule) s = std::max(s, norm(k.velocity) + std::fabs(k.omega) * bound);
  return s;
}

/// The point the body turns about: its area centroid (a half_disc's lies on its axis of symmetry,
/// Shape::half_disc's centroid offset from the disc's centre, as the scene places it).
Vec2 turning_point(const BodySpec& b) {
  switch (b.shape) {
    case BodyShape::Polygon:
      return centroid(b.vertices, b.holes);
    case BodyShape::HalfDisc:
      return b.center +
             rotate(Shape::half_disc(b.radius).centroid_offset(), std::cos(b.angle), std::sin(b.angle));
    default:
      return b.center;
  }
}

/// The body as it stands at time t: turned by the prescribed rotation about its centroid, which
/// the prescribed displacement carries along, and brought back into the domain along periodic
/// axes.
BodySpec moved_body(const Case& c, const BodySpec& b, real t) {
  const PrescribedState st = prescribed_state(b.schedule, b.velocity, b.omega, t);
  const Vec2 pivot0 = turning_point(b);
  Vec2 shift = st.displacement;
  const Vec2 span = c.domain_max - c.domain_min, pivot = pivot0 + shift;
  if (c.periodic_x) shift.x -= span.x * std::floor((pivot.x - c.domain_min.x) / span.x);
  if (c.periodic_y) shift.y -= span.y * std::floor((pivot.y - c.domain_min.y) / span.y);
  BodySpec m = b;
  m.angle = b.angle + st.rotation;
  const real cs = std::cos(st.rotation), sn = std::sin(st.rotation);
  m.center = pivot0 + shift + rotate(b.center - pivot0, cs, sn);  // the disc's centre turns with a half_disc
  for (Vec2& p : m.vertices) p += shift;  // a polygon's angle turns it about its centroid
  for (auto& hole : m.holes)
    for (Vec2& p : hole) p += shift;
  return m;
}

/// Gap between the outlines A and B (B moved by `shift`): exact for two circles, otherwise the
/// least distance of A's boundary points `spacing` apart (those that can be nearer than the
/// bound) to B's boundary polyline of chords `chord` long (a polygon's corners are on it, a
/// curve's chords lie within chord^2 / (8 R) of it): at most spacing / 2 too large.
real body_gap(const Outline& A, const Outline& B, Vec2 shift, real spacing, real chord) {
  if (A.body->shape == BodyShape::Circle && B.body->shape == BodyShape::Circle)
    return norm(B.center + shift - A.center) - A.body->radius - B.body->radius;
  const auto count = [](real length, real step) {
    return static_cast<std::size_t>(std::clamp(length / step, 16.0, 1e5));
  };
  std::vector<Vec2> pb = B.boundary(count(B.perimeter(), chord));
  for (Vec2& p : pb) p += shift;
  const Vec2 cb = B.center + shift;
  real gap = std::numeric_limits<real>::infinity();
  for (const Vec2 p : A.boundary(count(A.perimeter(), spacing))) {
    if (norm(p - cb) - B.bound >= gap) continue;  // no point of B is nearer than what was found
    for (std::size_t i = 0; i < pb.size(); ++i)
      gap = std::min(gap, segment_distance(p, pb[i], pb[(i + 1) % pb.size()]));
  }
  return gap;
}

/// What the path comes too close to, and where and when.
struct PathProblem {
  std::string what;  // "wall 'bottom' (wall[0])", "the domain edge y = 0 m", "body 'b' (circle) (body[2])"
  real gap = 0, t = 0;
};

/// The body's distance from everything that does not give way at time t: the first one closer
/// than `touch` (a problem), and the smallest distance found (when to look next).
struct PathLook {
  real nearest = std::numeric_limits<real>::infinity();
  std::optional<PathProblem> problem;
};

PathLook look_at(const Case& c, std::size_t k, real t, real touch, const std::vector<real>& start_gap) {
  const real tol = 1e-6 * c.d0;
  PathLook look;
  const BodySpec mk = moved_body(c, c.bodies[k], t);
  const Outline o(mk);
  std::vector<Vec2> samples;  // touch / 2 apart (at least 200), made when something is near
  const auto boundary = [&]() -> const std::vector<Vec2>& {
    if (samples.empty())
      samples = o.boundary(static_cast<std::size_t>(std::clamp(o.perimeter() / (0.5 * touch), 200.0, 2e5)));
    return samples;
  };
  const auto note = [&](real gap, real limit, const std::string& what) {
    look.nearest = std::min(look.nearest, gap);
    if (gap < limit && !look.problem) look.problem = PathProblem{what, gap, t};
  };
  // domain edges along axes that are not periodic (a wall lies along most; one that does not is
  // an edge the fluid ends at)
  const bool periodic[2] = {c.periodic_x, c.periodic_y};
  for (int axis = 0; axis < 2; ++axis) {
    if (periodic[axis]) continue;
    const char name = axis == 0 ? 'x' : 'y';
    const real lo = axis == 0 ? o.lo.x : o.lo.y, hi = axis == 0 ? o.hi.x : o.hi.y;
    const real min = axis == 0 ? c.domain_min.x : c.domain_min.y,
               max = axis == 0 ? c.domain_max.x : c.domain_max.y;
    note(lo - min, -tol, fmt::format("the domain edge {} = {:.9g} m", name, min));
    note(max - hi, -tol, fmt::format("the domain edge {} = {:.9g} m", name, max));
  }
  const std::vector<Vec2> shifts = periodic_shifts(c);
  for (std::size_t w = 0; w < c.walls.size(); ++w) {
    const WallSpec& ws = c.walls[w];
    const WallPiece at_t = ws.piece().moved(ws.pivot, ws.omega * t, {});  // a turning wall has turned
    for (const Vec2 shift : shifts) {
      const WallPiece piece = at_t.moved({}, 0, -1.0 * shift);
      const real far = piece.nearest(o.center).distance - o.bound;  // no nearer than this
      if (far >= touch) {
        look.nearest = std::min(look.nearest, far);
        continue;
      }
      note(gap_to_wall(o, boundary(), piece), touch, wall_text(c, w));
    }
  }
  for (std::size_t j = 0; j < c.bodies.size(); ++j) {
    if (j == k || c.bodies[j].motion == BodyMotion::Free) continue;
    const BodySpec mj = moved_body(c, c.bodies[j], t);
    const Outline B(mj);
    for (const Vec2 shift : shifts) {
      const real far = norm(B.center + shift - o.center) - o.bound - B.bound;
      if (far >= touch) {
        look.nearest = std::min(look.nearest, far);
        continue;
      }
      // a pair that starts closer than touch may stay about as close
      const real limit = std::min(touch, 0.5 * start_gap[j]);
      // first at d0 / 2 (its gap at most d0 / 4 too large), then at touch where that comes near
      const real coarse = body_gap(o, B, shift, 0.5 * c.d0, 0.25 * c.d0) - 0.25 * c.d0;
      if (coarse >= touch) {
        look.nearest = std::min(look.nearest, coarse);
        continue;
      }
      note(body_gap(o, B, shift, touch, 0.25 * c.d0), limit, fmt::format("{} (body[{}])", body_text(mj), j));
    }
  }
  return look;
}

}  // namespace

/// Conservative advancement along the path: from a time where the body is at least g from
/// everything, no point of it (moving at most S, S the sum of its and the fastest other's
/// speeds) comes within `touch` before (g - touch) / S later; steps of at least `touch` of
/// motion keep the count bounded (a crossing still shows as a gap below touch). Past 1e5 looks
/// (a path of more than 5000 d0 close to a wall) the rest of the path is not checked.
void check_prescribed_paths(const Case& c, const LoadContext& ctx) {
  const real touch = kTouch * c.d0;
  std::vector<real> bounds, speeds;
  real fastest_other = 0;  // turning walls and the other moving bodies
  for (const BodySpec& b : c.bodies) {
    bounds.push_back(Outline(b).bound + norm(turning_point(b) - b.center));
    speeds.push_back(b.motion == BodyMotion::Prescribed ? path_speed(b, bounds.back()) : 0);
    fastest_other = std::max(fastest_other, speeds.back());
  }
  for (const WallSpec& w : c.walls)
    if (w.omega != 0)
      fastest_other = std::max(fastest_other, std::fabs(w.omega) * w.piece().reach_from(w.pivot));
  constexpr int kMaxLooks = 100000;
  for (std::size_t k = 0; k < c.bodies.size(); ++k) {
    if (c.bodies[k].motion != BodyMotion::Prescribed || !(speeds[k] > 0) || !(c.t_end > 0)) continue;
    // the gap at t = 0 to every other body (a pair already closer than touch may keep about its gap)
    std::vector<real> start_gap(c.bodies.size(), std::numeric_limits<real>::infinity());
    const Outline o0(c.bodies[k]);
    for (std::size_t j = 0; j < c.bodies.size(); ++j) {
      if (j == k || c.bodies[j].motion == BodyMotion::Free) continue;
      const Outline B(c.bodies[j]);
      for (const Vec2 shift : periodic_shifts(c))
        if (norm(B.center + shift - o0.center) < o0.bound + B.bound + touch)
          start_gap[j] = std::min(start_gap[j], outline_gap(o0, B, shift, 2000));
    }
    const real S = speeds[k] + fastest_other, min_step = touch / S;
    real t = 0, step = min_step;
    for (int looks = 0; looks < kMaxLooks && t < c.t_end; ++looks) {
      t = std::min(c.t_end, t + step);
      const PathLook look = look_at(c, k, t, touch, start_gap);
      if (look.problem) {
        const PathProblem& p = *look.problem;
        const std::string key =
            c.bodies[k].schedule.empty() ? body_key(k, "velocity") : body_key(k, "schedule");
        throw ctx.error(
            key, fmt::format("{}, moving as prescribed, runs into {} at t = {:.6g} s (its gap {:.3g} m, "
                             "below {:g} d0): no contact acts on a prescribed body, so the fluid caught "
                             "between would be crushed; change its motion so that it stops short",
                             body_text(c.bodies[k]), p.what, p.t, p.gap, kTouch));
      }
      step = std::max(min_step, (look.nearest - touch) / S);  // nothing comes within touch before
    }
  }
}

}  // namespace particula::case_detail
