// Solid-solid repulsion (method.md section 8, P.38) generalized to any two shapes and to a
// body near a straight wall (treated as meeting its mirror image in the wall).
#pragma once

#include <vector>

#include "particula/core/types.hpp"
#include "particula/geometry/shape.hpp"
#include "particula/neighbors/domain.hpp"

namespace particula {

/// Closest approach between two solids: the surface gap (negative when they overlap) and the
/// unit direction pointing from the other solid towards this one.
struct Contact {
  real gap = 1e300;
  Vec2 normal;
};

/// P.38 for two circles of radius R at centre distance d:
///   F = k (r_s - r_q) [ (2R + eps)^2 - d^2 ]  for d <= 2R + eps.
/// Generalized with the centre distance replaced by d = gap + R_s + R_q along the contact normal
/// (R the equivalent radii), which is P.38 exactly for two circles.
PARTICULA_HD Vec2 repulsive_force(const Contact& c, real Rs, real Rq, real k, real eps) {
  if (!(c.gap <= eps) || k <= 0) return {};
  const real d = c.gap + Rs + Rq;
  const real reach = Rs + Rq + eps;
  return (k * d * (reach * reach - d * d)) * c.normal;
}

/// A placed body for contact queries: its shape, pose and surface samples (body frame).
struct PlacedBody {
  const Shape* shape = nullptr;
  const std::vector<SurfaceSample>* samples = nullptr;
  Vec2 pos;
  real angle = 0;
};

/// Contact of body a against body b (normal points from b towards a). Uses a's surface
/// samples against b's signed distance and b's samples against a's, so it resolves the gap
/// to the sampling spacing; exact for two circles.
Contact body_contact(const PlacedBody& a, const PlacedBody& b, const Domain& domain);

/// Contact of a body with a straight wall segment whose fluid side is given by `normal`
/// (normal points from the wall into the fluid, i.e. towards the body).
Contact wall_contact(const PlacedBody& a, Vec2 from, Vec2 to, Vec2 normal);

}  // namespace particula
