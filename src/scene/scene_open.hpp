// Open boundaries in the scene (internal to src/scene): zones, buffer particles, wall
// extensions through the buffer (scene_open.cpp).
#pragma once

#include <vector>

#include "particula/boundary/open_boundary.hpp"
#include "particula/case/case.hpp"
#include "particula/scene/scene.hpp"

namespace particula::scene_detail {

/// The zone of each open boundary of the case (inlets, then outlets), on the fluid lattice of
/// spacing dx x dy.
std::vector<OpenZone> open_zones(const Case& c, real dx, real dy);

/// A buffer particle's position and zone.
struct BufferPoint {
  Vec2 x;
  std::size_t zone = 0;
};

/// The buffer particles at t = 0: behind each zone's line, the columns of the fluid lattice
/// continued outwards by the zone's layers.
std::vector<BufferPoint> buffer_points(const Case& c, const std::vector<OpenZone>& zones, real dx, real dy);

/// How many points of spacing ds a straight wall continues beyond its end (`at_end`) or its
/// start through the buffer of an open boundary it meets there, leaving the domain through it
/// (0 when it meets none): without them the buffer beside the wall would see no wall, and the
/// fluid at the corner a hole in its kernel support.
int wall_extension_points(const Case& c, const WallSpec& w, bool at_end, real ds);

/// Appends the buffer particles (kinds Inlet, Outlet) after the fluid, sets the ids and next_id,
/// and the zones in the physics parameters.
void append_buffers(const Case& c, Scene& sc);

}  // namespace particula::scene_detail
