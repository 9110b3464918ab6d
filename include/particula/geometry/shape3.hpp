// Rigid-body shapes in 3D, in their body frame (the 3D counterpart of geometry/shape.hpp): the
// sphere, ellipsoid, cuboid and finite cylinder, and a closed triangle mesh (geometry/mesh.hpp).
// Each has its exact volume, centroid and inertia tensor (for the mesh, those of the polyhedron),
// its signed distance with the outward normal of the closest surface point, and surface samples
// at a spacing of about d0 carrying the exact area each stands for, with analytic normals (the
// mesh: its faces' normals). The body frame's origin is the volume centroid.
#pragma once

#include <memory>
#include <vector>

#include "particula/core/types3.hpp"
#include "particula/geometry/mesh.hpp"

namespace particula {

enum class Shape3Kind { Sphere, Ellipsoid, Cuboid, Cylinder, Mesh };

/// One sampled surface point in the body frame.
struct SurfaceSample3 {
  Vec3 x;       // position (body frame)
  Vec3 normal;  // outward unit normal (from the solid into the fluid)
  real dA = 0;  // surface area it represents
};

class Shape3 {
 public:
  static Shape3 sphere(real radius);
  /// Semi-axes a, b, c along the body's x, y and z.
  static Shape3 ellipsoid(real a, real b, real c);
  /// Side lengths along the body's x, y and z.
  static Shape3 cuboid(real lx, real ly, real lz);
  /// Radius and length, the axis along the body's z.
  static Shape3 cylinder(real radius, real length);
  /// A closed, consistently oriented triangle mesh (TriangleMesh checks it), moved so that its
  /// volume centroid is the origin; centroid_offset() is where the centroid was.
  static Shape3 mesh(const TriangleMesh& mesh);

  Shape3Kind kind() const { return kind_; }
  real volume() const { return volume_; }
  /// The inertia tensor per unit density about the centroid, J = int (|r|^2 I - r r^T) dV
  /// (the moment of inertia tensor is the body's density times this).
  const Mat3& inertia_per_density() const { return inertia_; }
  real surface_area() const { return area_; }
  /// Radius of the sphere with the same volume (the contact model's).
  real equivalent_radius() const;
  /// Largest distance from the centroid to the surface.
  real bounding_radius() const { return bound_; }
  /// Smallest dimension across the body, for resolution checks.
  real min_width() const { return min_width_; }
  Vec3 centroid_offset() const { return centroid_offset_; }

  /// Signed distance in the body frame (negative inside) and the outward unit normal of the
  /// closest surface point.
  void distance_and_gradient(Vec3 p, real& d, Vec3& n) const;
  real signed_distance(Vec3 p) const;
  bool contains(Vec3 p) const { return signed_distance(p) < 0; }
  /// Surface samples at a spacing of about d0 (body frame), their dA summing to the surface area.
  std::vector<SurfaceSample3> sample_surface(real d0) const;

 private:
  Shape3Kind kind_ = Shape3Kind::Sphere;
  Vec3 axes_;  // sphere: radius in x; ellipsoid: semi-axes; cuboid: half sides; cylinder: (R, R, L/2)
  std::shared_ptr<const TriangleMesh> mesh_;  // centred on its centroid
  real volume_ = 0, area_ = 0, bound_ = 0, min_width_ = 0;
  Mat3 inertia_;
  Vec3 centroid_offset_;
};

}  // namespace particula
