// A body's outline at t = 0 in world coordinates, and the small geometry helpers the load
// checks of bodies share (checks.cpp: walls against bodies, initial contacts; body_checks.cpp:
// polygons, sizes, domain, overlaps).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "particula/case/case.hpp"
#include "particula/geometry/wall_piece.hpp"

namespace particula::case_detail {

/// "body[2].radius".
std::string body_key(std::size_t k, std::string_view leaf);
/// The key that places a body: its centre, or its vertices for a polygon.
std::string place_key(const Case& c, std::size_t k);
/// The shape's name in the case file (the choices of body[].shape follow the enumerators).
const std::string& shape_name(BodyShape s);
/// "body 'disc' (circle)".
std::string body_text(const BodySpec& b);

/// Twice the signed area of a polygon (positive when counter-clockwise), computed relative to
/// its first vertex so that far-off coordinates do not overflow.
real twice_area(const std::vector<Vec2>& v);
/// Area centroid of a polygon of non-zero area, with its holes taken out.
Vec2 centroid(const std::vector<Vec2>& v, const std::vector<std::vector<Vec2>>& holes = {});
/// Diagonal of the bounding box (the size that scales tolerances).
real extent(const std::vector<Vec2>& v);
/// Sign of x with a dead band of +-eps.
int sign(real x, real eps);
/// Whether the closed segments [p1, p2] and [q1, q2] share a point. `area_eps` is the dead band of
/// the orientation tests (an area), `len_eps` that of the collinear overlap tests.
bool segments_meet(Vec2 p1, Vec2 p2, Vec2 q1, Vec2 q2, real area_eps, real len_eps);
/// Whether edges i and j (i < j) of the closed polygon v meet other than at a vertex they share.
bool edges_meet(const std::vector<Vec2>& v, std::size_t i, std::size_t j, real area_eps, real len_eps);
/// Smallest width of a polygon: over its edges, the largest distance of a vertex from the edge
/// line, minimised (exact for convex polygons, an upper bound otherwise).
real polygon_width(const std::vector<Vec2>& v);
/// Distance from p to the segment [a, b].
real segment_distance(Vec2 p, Vec2 a, Vec2 b);
/// The shifts of the periodic images a body can meet: the 3 x 3 neighbourhood along periodic
/// axes, (0, 0) included.
std::vector<Vec2> periodic_shifts(const Case& c);

/// A body's outline at t = 0 in world coordinates.
struct Outline {
  const BodySpec* body = nullptr;
  Vec2 center;              // centre (circle, ellipse), disc centre (half_disc), area centroid (polygon)
  real cs = 1, sn = 0;      // cos and sin of the angle
  std::vector<Vec2> verts;  // polygon: rotated by the angle about the centroid
  std::vector<std::vector<Vec2>> holes;  // polygon: its holes, rotated likewise
  real bound = 0;                        // radius about `center` of a circle holding the body
  Vec2 lo, hi;                           // bounding box

  explicit Outline(const BodySpec& b);
  /// World point -> body frame (relative to `center`, unrotated).
  Vec2 local(Vec2 p) const { return rotate(p - center, cs, -sn); }
  /// Whether p lies inside the body (in its solid, not in a hole) by more than tol.
  bool contains(Vec2 p, real tol) const;
  /// Length of the boundary (holes included).
  real perimeter() const;
  /// About n points on the boundary (world coordinates; holes included), corners included.
  std::vector<Vec2> boundary(std::size_t n) const;
};

/// Gap between a body and a wall, <= 0 where they meet: exact for a circle, else the least
/// distance of the boundary samples (at most half their spacing too large).
real gap_to_wall(const Outline& o, const std::vector<Vec2>& samples, const WallPiece& w);
/// Gap between the outlines A and B (B moved by `shift`): exact for two circles, otherwise the
/// smallest distance of A's `points` boundary points to B's boundary polyline.
real outline_gap(const Outline& A, const Outline& B, Vec2 shift, std::size_t points);

}  // namespace particula::case_detail
