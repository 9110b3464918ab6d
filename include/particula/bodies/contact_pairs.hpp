// Which bodies can touch: candidate pairs for the contact model from a cell list over the
// bodies, so that detection costs O(n) for n bodies at a bounded density instead of O(n^2).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "particula/core/types.hpp"
#include "particula/neighbors/domain.hpp"

namespace particula {

using BodyPair = std::pair<std::uint32_t, std::uint32_t>;

/// Every pair (i, j), i < j, of bodies whose bounding circles come within `range` of each
/// other, |x_i - x_j| <= bound_i + bound_j + range (minimum image along periodic axes, through
/// Domain::separation), sorted by (i, j). Cells are at least 2 max(bound) + range wide, so a
/// pair always lies in neighbouring cells; along a periodic axis the cells wrap, elsewhere a body
/// outside the box is binned in the nearest edge cell. `out` is overwritten.
void contact_candidates(const std::vector<Vec2>& pos, const std::vector<real>& bound, real range,
                        const Domain& domain, std::vector<BodyPair>& out);

/// The same set by testing every pair (the reference of the tests and the benchmark).
void contact_candidates_all_pairs(const std::vector<Vec2>& pos, const std::vector<real>& bound, real range,
                                  const Domain& domain, std::vector<BodyPair>& out);

}  // namespace particula
