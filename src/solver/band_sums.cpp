// The band's per-entry levels and loads summed per block slot on the host (a device's downloaded
// entries; the tests' reference for the CPU's fused sums).
#include <algorithm>

#include "particula/solver/momentum_loads.hpp"

namespace particula {

void sum_band_entry_levels(const std::vector<BandEntry>& band, const std::vector<std::size_t>& block_first,
                           const std::vector<Vec2>& num_den, std::vector<Vec2>& partial) {
  const std::size_t ne = band.size(), nblocks = block_first.empty() ? 0 : block_first.size() - 1;
  partial.assign(block_first.empty() ? 0 : block_first.back(), Vec2{});
#pragma omp parallel for schedule(static)
  for (std::size_t b = 0; b < nblocks; ++b)
    for (std::size_t e = b * kBandBlock; e < std::min(ne, (b + 1) * kBandBlock); ++e)
      partial[block_first[b] + band[e].slot] += num_den[e];
}

void sum_band_entry_loads(const std::vector<BandEntry>& band, const std::vector<std::size_t>& block_first,
                          const std::vector<std::uint8_t>& circle, const std::vector<Vec2>& fp,
                          const std::vector<Vec2>& fv, const std::vector<Vec2>& torque,
                          const std::vector<Vec2>& fd, std::vector<BandLoadSum>& partial) {
  const std::size_t ne = band.size(), nblocks = block_first.empty() ? 0 : block_first.size() - 1;
  partial.assign(block_first.empty() ? 0 : block_first.back(), BandLoadSum{});
#pragma omp parallel for schedule(static)
  for (std::size_t b = 0; b < nblocks; ++b)
    for (std::size_t e = b * kBandBlock; e < std::min(ne, (b + 1) * kBandBlock); ++e) {
      const BandEntry& be = band[e];
      add_band_entry_load(partial[block_first[b] + be.slot], fp[e], fv[e], torque[e], fd[e],
                          circle[static_cast<std::size_t>(be.group)] && be.in_film);
    }
}

}  // namespace particula
