// Walls in the scene (internal to src/scene): their surface samples, the dummy layers of the
// baseline boundary, the corner volume factor and the region the walls enclose.
#pragma once

#include <functional>
#include <utility>
#include <vector>

#include "particula/case/case.hpp"
#include "particula/geometry/shape.hpp"
#include "particula/neighbors/domain.hpp"

namespace particula::scene_detail {

/// One sampled surface point of a wall before it is placed in the particle arrays.
struct SurfacePoint {
  Vec2 x, normal;
  real ds;
  bool corner;
  Vec2 corner_normal2;  // the other wall's normal at a corner
  Vec2 wall_normal;     // this wall's own normal there
  real wedge = 0;       // at a convex corner of the walls (the fluid wraps round it, an L-shape's
                        // inward corner): half the angle between the two normals; 0 elsewhere
};

/// Samples wall w at spacing ~d0 (a segment's points equally spaced, an arc's equally spaced
/// in angle with its analytic normals); see scene_walls.cpp.
std::vector<SurfacePoint> sample_wall(const Case& c, const Domain& dom, std::size_t w);

/// Dummy particles of the baseline boundary: `layers` rows behind each surface point along -n;
/// a corner gets the full block.
std::vector<std::pair<Vec2, std::size_t>> dummy_points(const std::vector<SurfacePoint>& surf, real d0, int layers);

/// Volume factor of a corner particle whose two walls have the fluid-side normals n1 and n2;
/// `convex`: the solid's corner is convex (fluid angle above 180 degrees).
real corner_volume_factor(Vec2 n1, Vec2 n2, bool convex = false);

/// A point where a fixed body's surface crosses a wall (scene_junctions.cpp): on both, with the
/// body's outward normal and the wall's fluid-side normal there (world frame).
struct Crossing {
  Vec2 x, body_normal, wall_normal;
};

/// The stretches [s0, s1] of `wall` (fractions along it) where holds(s) is true: walked d0/16
/// apart, each change refined by bisection (scene_junctions.cpp).
std::vector<std::pair<real, real>> wall_stretches(const WallPiece& wall, const std::function<bool(real)>& holds,
                                                  real d0);

/// The points where the surface of `shape`, placed at `pos` turned by `angle`, crosses `wall`:
/// the ends of the wall's stretches inside the body. A wall that only touches the body (a flat
/// side lying on it) is not crossed.
std::vector<Crossing> body_wall_crossings(const Shape& shape, Vec2 pos, real angle, const WallPiece& wall, real d0);

/// Whether x lies beyond the walls (outside the region they enclose) or beyond the domain's
/// edge along a non-periodic axis.
bool beyond_walls(Vec2 x, const std::vector<WallPiece>& walls, const Domain& dom);

/// x moved to its periodic image nearest the wall's middle.
Vec2 image_near(const WallPiece& w, const Domain& dom, Vec2 x);

}  // namespace particula::scene_detail
