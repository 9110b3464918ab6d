// Guard against absurd sizes: the particle count and memory of a case are estimated from its
// domain and d0 before anything is allocated, and a case beyond the limits is refused (exit 2).
#pragma once

#include "particula/case/case.hpp"

namespace particula {

/// Upper bound on the particle count of a run, whatever the machine.
inline constexpr double kMaxParticles = 2e8;

struct SizeEstimate {
  double fluid = 0, boundary = 0;
  double total() const { return fluid + boundary; }
  double bytes = 0;  // particle arrays, solver work arrays and the pair list
};

/// Estimates the particle counts and memory of `c` from its domain, walls and d0 (no allocation).
SizeEstimate estimate_size(const Case& c);

/// Throws CaseError naming `resolution.d0` and the estimated count when the case would need more
/// than kMaxParticles particles or more memory than this machine has.
void check_case_size(const Case& c);

}  // namespace particula
