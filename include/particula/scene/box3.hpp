// The 3D scene of a box of fluid whose closed faces are fixed walls (the periodic axes have
// none): the fluid on the cell-centred lattice of spacing d0 (adjusted per axis to fit the box
// exactly), and a single layer of wall particles on each closed face at the centres of its
// cells, along the edges where two closed faces meet and at the corners where three do, with
// their normals into the fluid (edges and corners: the normalized sum of their faces').
#pragma once

#include "particula/core/types3.hpp"
#include "particula/neighbors/domain.hpp"
#include "particula/solver/particles.hpp"

namespace particula {

struct BoxSpec3 {
  Vec3 lo, hi;
  bool periodic[3] = {false, false, false};
  real d0 = 0;
  real rho0 = 0, p0 = 0;
};

struct BoxScene3 {
  Domain3 domain;
  Particles3 particles;
  Vec3 spacing;  // the lattice spacing along each axis
};

/// The box scene of `spec`: the boundary block first (the walls; one rigid group per closed face,
/// in the order -x, +x, -y, +y, -z, +z, an edge or corner in its first face's group), then the
/// fluid, each particle at rho0 and p0. Volumes: a cell for the fluid, half a cell on a face, a
/// quarter on an edge, an eighth at a corner (the parts of their cells inside the box); areas ds:
/// a face cell's on a face, 0 on edges and corners (the faces' particles cover the surface).
BoxScene3 build_box3(const BoxSpec3& spec);

}  // namespace particula
