// What a run counts as it goes: the guarded events of the passes (the run log, summary.json) and
// the wall-clock time of each phase of the step (the benchmark's breakdown).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

namespace particula {

/// Counters of guarded events (written to the run log).
struct SolverCounters {
  std::int64_t singular_B = 0;          // renormalization matrix singular -> B = I
  std::int64_t singular_Bhat = 0;       // fluid particle's Laplacian system singular -> Bhat = k I
  std::int64_t wall_pressure_kept = 0;  // P.20 denominator vanished -> previous P kept
  std::int64_t wall_pressure_extrapolated =
      0;  // P.20 ill-conditioned (sharp corner, contact wedge) -> extrapolated
  std::int64_t wall_pressure_extrapolated_far = 0;  // fluid out of P.20's reach (narrow gap) -> extrapolated
  std::int64_t normal_fallback = 0;                 // P.18 sum vanished -> analytic normal used
  std::int64_t surface_pushed = 0;     // fluid particle put back to the keep-out distance of a surface
  std::int64_t gap_squeezed = 0;       // fluid particle centred in a gap narrower than twice that
  std::int64_t isolated_left_out = 0;  // isolated fluid particle left out of P.20 (particle-steps)
  std::int64_t open_fit_fallback = 0;  // buffer particle whose mirrored fit was singular -> Shepard mean
  std::int64_t sparse_support = 0;     // fluid particle's gradient moment bounded below (particle-steps)
  std::int64_t wall_pressure_void = 0;  // surface particle with no fluid within kVoidDistance -> the void's pressure
};

/// The counters by the names summary.json and the Python module give them (one list for both).
inline std::vector<std::pair<const char*, std::int64_t>> guard_events(const SolverCounters& c) {
  return {{"singular_B", c.singular_B},
          {"singular_Bhat", c.singular_Bhat},
          {"wall_pressure_kept", c.wall_pressure_kept},
          {"wall_pressure_extrapolated", c.wall_pressure_extrapolated},
          {"wall_pressure_extrapolated_far", c.wall_pressure_extrapolated_far},
          {"normal_fallback", c.normal_fallback},
          {"surface_pushed", c.surface_pushed},
          {"gap_squeezed", c.gap_squeezed},
          {"isolated_left_out", c.isolated_left_out},
          {"open_fit_fallback", c.open_fit_fallback},
          {"sparse_support", c.sparse_support},
          {"wall_pressure_void", c.wall_pressure_void}};
}

/// Wall-clock seconds spent in each phase of the time step, summed over the steps taken (the
/// benchmark's per-phase breakdown; a handful of clock reads per step).
struct PhaseTimes {
  double neighbors = 0;      // cell binning, neighbour list, fluid reordering
  double geometry = 0;       // B, Bhat, normals, rbar, shifting direction, the fits of open boundaries
  double operators = 0;      // velocity derivatives, pressure gradient, Rhie-Chow, fluid stages
  double wall_pressure = 0;  // P.20 (or the dummy copy), and the fields of open boundaries' buffers
  double bodies = 0;         // loads, collisions, rigid motion, surface placement
  double integration = 0;    // end-of-step averages, dt, health check
  double shifting = 0;       // pressure gradient of the new state and the shift
  double total() const {
    return neighbors + geometry + operators + wall_pressure + bodies + integration + shifting;
  }
};

}  // namespace particula
