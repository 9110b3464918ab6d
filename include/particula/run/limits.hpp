// Guard against absurd sizes: the particle count and memory of a case are estimated from its
// domain and d0 before anything is allocated, and a case beyond the limits is refused (exit 2);
// likewise a thread count beyond what the OpenMP runtime can start.
#pragma once

#include <string>

#include "particula/case/case.hpp"

namespace particula {

/// Upper bound on the particle count of a run, whatever the machine.
inline constexpr double kMaxParticles = 2e8;

struct SizeEstimate {
  double fluid = 0, boundary = 0;
  double total() const { return fluid + boundary; }
  double bytes = 0;  // particle arrays, solver work arrays, the pair list and the probes
  double probe_points = 0, probe_bytes = 0;  // all probes together (included in `bytes`)
};

/// Memory per probe point: its position, the interpolated sample and the row written.
inline constexpr double kBytesPerProbePoint = 16 + 32 + 8 * 7;

/// Estimates the particle counts and memory of `c` from its domain, walls, d0 and probes (no
/// allocation).
SizeEstimate estimate_size(const Case& c);

/// The most OpenMP threads a run uses (--threads, Python's threads=, OMP_NUM_THREADS). The OpenMP
/// runtime (libgomp) puts per-thread start data on the calling thread's stack when it starts a team:
/// about 100000 threads overflow an 8 MiB stack (SIGSEGV) and 10^9 exhaust memory (an abort), before
/// particula's code runs. 4096 threads need about 0.5 MiB of that stack.
inline constexpr int kMaxThreads = 4096;

/// Empty when OpenMP's default team size (OMP_NUM_THREADS, else the cores) is within
/// [1, kMaxThreads]; otherwise the reason, naming OMP_NUM_THREADS and its value.
std::string default_threads_problem();

/// Throws CaseError naming `resolution.d0` and the estimated count when the case would need more
/// than kMaxParticles particles or more memory than this machine has.
void check_case_size(const Case& c);

}  // namespace particula
