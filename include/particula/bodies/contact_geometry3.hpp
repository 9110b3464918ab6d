// The geometry of contacts in 3D (the 3D counterpart of body_contact and wall_contact of
// bodies/collision.hpp): the closest approach of two placed bodies, or of a body and a plane wall,
// with the point where the contact force acts. Exact for two spheres and for a sphere and a plane;
// other shapes resolve the gap to their surface sampling (each one's samples against the other's
// signed distance), the conservative fallback: the gap found is never smaller than the true one by
// more than the chord error of the sampling.
#pragma once

#include <vector>

#include "particula/bodies/collision.hpp"
#include "particula/geometry/shape3.hpp"
#include "particula/neighbors/domain.hpp"

namespace particula {

/// A placed body for contact queries: its shape, surface samples (body frame) and pose.
struct PlacedBody3 {
  const Shape3* shape = nullptr;
  const std::vector<SurfaceSample3>* samples = nullptr;
  Vec3 pos;
  Quat q;
};

/// A plane wall: a point on it and its unit normal into the fluid.
struct WallPlane {
  Vec3 point;
  Vec3 normal;
};

/// Contact of body a against body b (normal from b towards a).
ContactOf<3> body_contact(const PlacedBody3& a, const PlacedBody3& b, const Domain3& domain);

/// Contact of a body with a plane wall (normal: the wall's, towards the body).
ContactOf<3> wall_contact(const PlacedBody3& a, const WallPlane& wall);

}  // namespace particula
