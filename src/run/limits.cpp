#include "particula/run/limits.hpp"

#include <fmt/format.h>
#include <omp.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>

#include "particula/case/error.hpp"

namespace particula {

namespace {
/// Physical memory of this machine in bytes (0 when unknown).
double physical_memory() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? static_cast<double>(pages) * static_cast<double>(page) : 0.0;
}
}  // namespace

SizeEstimate estimate_size(const Case& c) {
  SizeEstimate e;
  const double lx = c.domain_max.x - c.domain_min.x, ly = c.domain_max.y - c.domain_min.y;
  // Computed in floating point, so absurd inputs give huge (or inf/nan) counts, never overflow.
  e.fluid = std::max(1.0, std::round(lx / c.d0)) * std::max(1.0, std::round(ly / c.d0));
  const double layers = c.boundary == BoundaryModel::Dummy ? 1 + std::ceil(c.h_over_d0) : 1;
  for (const auto& w : c.walls) e.boundary += (norm(w.to - w.from) / c.d0 + 1) * layers;
  // Per particle: ~30 doubles of state and work arrays, plus 36 bytes per neighbour pair
  // (pi (h/d0)^2 neighbours within the kernel support).
  const double neighbours = M_PI * c.h_over_d0 * c.h_over_d0;
  for (const auto& p : c.probes) e.probe_points += static_cast<double>(probe_point_count(p));
  e.probe_bytes = e.probe_points * kBytesPerProbePoint;
  e.bytes = e.total() * (30 * 8 + 36 * neighbours) + e.probe_bytes;
  return e;
}

void check_case_size(const Case& c) {
  const SizeEstimate e = estimate_size(c);
  const double ram = physical_memory();
  const bool too_many = !(e.total() <= kMaxParticles);
  const bool too_big = ram > 0 && !(e.bytes <= ram);
  if (!too_many && !too_big) return;
  const std::string limit =
      too_many ? fmt::format("more than the {:.3g} particles particula accepts", kMaxParticles)
               : fmt::format("about {:.3g} GiB, more than this machine's {:.3g} GiB of memory", e.bytes / 1073741824.0,
                             ram / 1073741824.0);
  throw CaseError(c.source.string(), 0, "resolution.d0",
                  fmt::format("d0 = {:.6g} m gives about {:.3g} particles ({}); increase resolution.d0", c.d0,
                              e.total(), limit));
}

namespace {
/// Whether OMP_NUM_THREADS, when set, starts with a count in [1, kMaxThreads] (a list such as
/// "8,2" sets nested levels, which particula does not use). The OpenMP runtime itself only warns
/// about a value it cannot parse and takes all cores.
bool env_threads_valid(const std::string& text) {
  const std::string first = text.substr(0, text.find(','));
  const auto b = first.find_first_not_of(" \t"), e = first.find_last_not_of(" \t");
  if (b == std::string::npos) return text.empty();
  const std::string digits = first.substr(b, e - b + 1);
  if (digits.size() > 4 || digits.find_first_not_of("0123456789") != std::string::npos) return false;
  const int n = std::stoi(digits);
  return n >= 1 && n <= kMaxThreads;
}
}  // namespace

std::string default_threads_problem() {
  // omp_get_max_threads() is the team size the runtime would start (OMP_NUM_THREADS, all cores,
  // or what omp_set_num_threads set); the variable is checked as written too.
  const char* env = std::getenv("OMP_NUM_THREADS");
  const int team = omp_get_max_threads();
  if (team >= 1 && team <= kMaxThreads && (env == nullptr || env_threads_valid(env))) return {};
  return fmt::format(
      "OMP_NUM_THREADS={}: not a thread count particula runs (1 .. {}, the most the OpenMP runtime starts "
      "safely); set OMP_NUM_THREADS within it, unset it (all cores) or choose the count with --threads "
      "(Python: threads=)",
      env != nullptr ? std::string(env) : std::to_string(team), kMaxThreads);
}

}  // namespace particula
