// The 3D scene of a box of fluid whose closed faces are fixed walls (the periodic axes have
// none): the fluid on the cell-centred lattice of spacing d0 (adjusted per axis to fit the box
// exactly), and a single layer of wall particles on each closed face at the centres of its
// cells, along the edges where two closed faces meet and at the corners where three do, with
// their normals into the fluid (edges and corners: the normalized sum of their faces'). A face may
// move along itself at a constant velocity (a belt: its particles keep their places and carry the
// velocity, exact for a plane that slides along itself, as the lid of a cavity or the moving
// plate of a Couette cell).
#pragma once

#include <vector>

#include "particula/core/types3.hpp"
#include "particula/geometry/shape3.hpp"
#include "particula/neighbors/domain.hpp"
#include "particula/solver/particles.hpp"

namespace particula {

/// A solid fixed in the box: its shape (geometry/shape3.hpp) placed at `position` (the origin of
/// its body frame) and turned by `orientation`.
struct FixedSolid3 {
  Shape3 shape;
  Vec3 position;
  Quat orientation;
};

struct BoxSpec3 {
  Vec3 lo, hi;
  bool periodic[3] = {false, false, false};
  real d0 = 0;
  real rho0 = 0, p0 = 0;
  /// The velocity of each face, in the order -x, +x, -y, +y, -z, +z; its normal component must be
  /// zero. An edge or corner moves with its faces when they all have the same velocity, else rests.
  Vec3 face_velocity[6];
  /// Solids fixed in the fluid: their surfaces sampled at about d0 (each sample a wall particle
  /// with the exact area it stands for and the shape's normal, volume d0 dA as a face's), and the
  /// fluid lattice left out where it lies within d0 / 2 of a solid or inside one (periodic images
  /// included). The fluid's masses fill the region outside the solids exactly (to the 6^3
  /// midpoints of a cut cell): a cut cell's particle holds its part outside, and a left-out
  /// cell's part goes to the nearest kept particle.
  std::vector<FixedSolid3> solids;
};

struct BoxScene3 {
  Domain3 domain;
  Particles3 particles;
  Vec3 spacing;  // the lattice spacing along each axis
};

/// The box scene of `spec`: the boundary block first (the walls; one rigid group per closed face,
/// in the order -x, +x, -y, +y, -z, +z, an edge or corner in its first face's group; then each
/// fixed solid's surface, group 6 + its index), then the fluid, each particle at rho0 and p0. Volumes: a cell
/// for the fluid, a face particle and an edge particle one cell (d0 dA, as a 2D wall particle's d0 ds), a
/// corner 1.25 cells, each chosen so that the fluid particle next to it has a nearly vanishing zeroth kernel
/// moment (M.6); areas ds: a face cell's on a face, 0 on edges and corners (the faces' particles cover the
/// surface).
BoxScene3 build_box3(const BoxSpec3& spec);

}  // namespace particula
