#include "particula/run/limits.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cmath>

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

}  // namespace particula
