// Rigid-body shapes in their body frame: signed distance, exact area and polar moment,
// and surface sampling at spacing ~d0 with the exact surface length per particle.
// The body frame's origin is the area centroid; `angle` rotates body to world frame.
#pragma once

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "particula/core/types.hpp"

namespace particula {

namespace geometry_detail {
class EdgeGrid;
}

enum class ShapeKind { Circle, Ellipse, Polygon, HalfDisc };

/// One sampled surface point in the body frame.
struct SurfaceSample {
  Vec2 x;       // position (body frame)
  Vec2 normal;  // outward unit normal (from the solid into the fluid)
  real ds;      // surface length it represents
  bool corner = false;  // a vertex where two sides meet (polygon vertex, end of a half-disc's flat side)
  Vec2 sides[2];        // at a corner: the outward normals of the two sides meeting there
  real wedge = 0;       // at a convex corner (the fluid wraps round it): half the angle between
                        // the sides' normals, the corner the surface guard sees; 0 elsewhere
};

/// Half the angle between the normals n1 and n2 of the two sides at a convex corner.
inline real half_angle_between(Vec2 n1, Vec2 n2) {
  return 0.5 * std::acos(std::fmax(-1.0, std::fmin(1.0, dot(n1, n2))));
}

class Shape {
 public:
  static Shape circle(real radius);
  /// Semi-axes a (along body x) and b (along body y).
  static Shape ellipse(real a, real b);
  /// Polygon from vertices (any orientation, convex or not, not self-intersecting), with
  /// optional holes (each a polygon strictly inside it, clear of the others; any orientation).
  /// The vertices are shifted so that the area centroid is the origin; `centroid_offset()`
  /// returns where the centroid was in the given coordinates.
  static Shape polygon(std::vector<Vec2> vertices, std::vector<std::vector<Vec2>> holes = {});
  /// Half of a disc of radius R: the half with x >= 0 (flat side along the body y axis through
  /// the disc centre). The body frame origin is the centroid (4R/3pi from the flat side).
  static Shape half_disc(real radius);

  ShapeKind kind() const { return kind_; }
  real area() const { return area_; }
  /// Polar second moment of area about the centroid (moment of inertia = density * this).
  real polar_moment() const { return polar_; }
  /// Radius of the disc with the same area (used by the collision model).
  real equivalent_radius() const;
  /// Largest distance from the centroid to the surface.
  real bounding_radius() const { return bound_; }
  Vec2 centroid_offset() const { return centroid_offset_; }
  /// Smallest dimension across the body (diameter, minor axis, ...), for resolution checks.
  real min_width() const { return min_width_; }

  /// Whether p (body frame) lies inside the solid.
  bool contains(Vec2 p) const;
  /// Signed distance in the body frame: negative inside the solid.
  real signed_distance(Vec2 p) const;
  /// Outward normal of the surface point closest to p (body frame).
  Vec2 closest_normal(Vec2 p) const;
  /// Signed distance d and its gradient n (the outward unit normal of the closest surface point)
  /// in one closest-point search (body frame).
  void distance_and_gradient(Vec2 p, real& d, Vec2& n) const;
  /// Surface samples at spacing about d0 (body frame), with exact dS summing to the perimeter.
  std::vector<SurfaceSample> sample_surface(real d0) const;
  real perimeter() const;

 private:
  ShapeKind kind_ = ShapeKind::Circle;
  real a_ = 0, b_ = 0;  // radius / semi-axes
  // Polygon: the outline counter-clockwise, then each hole clockwise, so that the solid is on
  // the left of every loop (shoelace sums over all loops give the solid's area and moments).
  std::vector<std::vector<Vec2>> loops_;
  std::shared_ptr<const geometry_detail::EdgeGrid> grid_;  // polygons of many edges: nearest edge by cells
  real area_ = 0, polar_ = 0, bound_ = 0, min_width_ = 0;
  Vec2 centroid_offset_;
  Vec2 closest_point(Vec2 p) const;
  /// Polygon: signed distance (negative in the solid) and the nearest boundary point.
  real polygon_distance(Vec2 p, Vec2& q) const;
};

}  // namespace particula
