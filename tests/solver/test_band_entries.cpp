// The CPU backend's evaluation of the load band's entries (Backend::set_load_band, band_levels,
// band_loads; numerics.force = "momentum"): every entry as the PARTICULA_HD functions of
// solver/momentum_loads.hpp give it from the host's particles and fields of the stage, with the
// backend's own arrays (the constants' pointers are ignored), whatever the entries' order.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "case_builders.hpp"
#include "particula/case/case.hpp"
#include "particula/scene/scene.hpp"
#include "particula/solver/momentum_loads.hpp"
#include "particula/solver/solver.hpp"

using namespace particula;

namespace {

/// A free cylinder settling in a closed box of fluid under gravity (the fluid moving, the
/// odd-even damping on).
Case settling_cylinder() {
  const real L = 4e-3;
  Case c = cases::closed_box(L, L, 1.25e-4);
  c.name = "settling";
  c.nu = 1e-4;
  c.gravity = {0, -9.81};
  c.gravity_in_fluid = true;
  c.force = ForceModel::Momentum;
  c.odd_even_damping = 0.01;
  BodySpec b = cases::circle_body("cylinder", {L / 2, L / 2}, 0.8e-3);
  b.density = 1500;
  c.bodies = {b};
  return c;
}

/// Up to three entries per fluid particle, of random groups and weights, with the particle's
/// random area (0: its volume), each particle's entries consecutive, in two passes over the fluid (a
/// particle's entries of the two passes apart, in different blocks).
std::vector<BandEntry> random_band(const Particles& P, std::size_t groups) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<real> u(-1, 1);
  std::vector<real> area(P.size());  // a particle's, as a band build gives all its entries
  for (real& a : area) a = rng() % 3 == 0 ? 0 : 4e-8 * (1 + 0.2 * u(rng));
  std::vector<BandEntry> band;
  const auto add = [&](std::size_t i, int count) {
    for (int k = 0; k < count; ++k) {
      BandEntry e;
      e.particle = static_cast<std::uint32_t>(i);
      e.group = static_cast<std::int32_t>(rng() % groups);
      e.phi = 0.5 * (1 + u(rng));
      e.grad_phi = Vec2{u(rng), u(rng)} * 1e3;
      e.area = area[i];
      e.in_film = rng() % 5 == 0;
      band.push_back(e);
    }
  };
  for (int pass = 0; pass < 2; ++pass)
    for (std::size_t i = P.n_boundary; i < P.size(); ++i) add(i, 1 + static_cast<int>(rng() % 3));
  return band;
}

/// Equal to round-off: the backend and this test compile the same PARTICULA_HD functions in two
/// translation units, and a build that fuses multiply-adds (-march=native) may fuse them
/// differently, so the last bits may differ (bitwise with -DPARTICULA_NATIVE=OFF).
constexpr real kRoundOff = 1e-12;
bool close(real a, real b) { return std::abs(a - b) <= kRoundOff * (std::abs(a) + std::abs(b)) + 1e-300; }
bool same(Vec2 a, Vec2 b) {
  const real scale = kRoundOff * (norm(a) + norm(b)) + 1e-300;
  return std::abs(a.x - b.x) <= scale && std::abs(a.y - b.y) <= scale;
}

/// Each block's slots as LoadBand numbers them (the groups in the order they first appear in the
/// block); returns where each block's slots start, and `slot_group` the group of each slot.
std::vector<std::int32_t> slot_group;
std::vector<std::size_t> assign_slots(std::vector<BandEntry>& band, std::size_t groups) {
  std::vector<std::size_t> first{0};
  slot_group.clear();
  for (std::size_t e0 = 0; e0 < band.size(); e0 += kBandBlock) {
    std::vector<std::int32_t> slot_of(groups, -1);
    for (std::size_t e = e0; e < std::min(band.size(), e0 + kBandBlock); ++e) {
      std::int32_t& slot = slot_of[static_cast<std::size_t>(band[e].group)];
      if (slot < 0) {
        slot = static_cast<std::int32_t>(slot_group.size() - first.back());
        slot_group.push_back(band[e].group);
      }
      band[e].slot = static_cast<std::uint16_t>(slot);
    }
    first.push_back(slot_group.size());
  }
  return first;
}

/// The host's particles and fields of the stage as the per-entry functions read them.
LoadArrays host_arrays(const Solver& s, const LoadArrays& scalars) {
  const Particles& P = s.particles();
  LoadArrays a = scalars;
  a.x = P.x.data();
  a.m = P.m.data();
  a.rho = P.rho.data();
  a.p = P.p.data();
  a.grad_v = s.host().grad_v().data();
  a.lap_v = s.host().lap_v().data();
  a.odd_even = s.host().odd_even();
  a.grad_p_over_rho = s.host().grad_p_over_rho().data();
  return a;
}

}  // namespace

TEST(BandEntries, TheCpuBackendEvaluatesEveryEntryAsTheSharedFunctions) {
  const Scene sc = build_scene(settling_cylinder());
  Solver s(sc.params, sc.domain, sc.particles, sc.groups);
  for (int k = 0; k < 3; ++k) ASSERT_FALSE(s.step().has_value());
  ASSERT_NE(s.host().odd_even(), nullptr);
  const std::size_t ng = s.groups().size();
  const std::vector<BandEntry> band = random_band(s.particles(), ng);
  ASSERT_GT(band.size(), 2 * kBandBlock) << "entries in several blocks";

  // the constants only: the backend adds its own arrays
  LoadArrays scalars;
  scalars.domain = s.domain();
  scalars.mu = sc.params.nu * sc.params.rho0;
  scalars.nu = sc.params.nu;
  scalars.rho0 = sc.params.rho0;
  scalars.c2 = sc.params.c * sc.params.c;
  scalars.p0 = sc.params.p0;
  scalars.g_h = sc.params.gravity;
  scalars.x_ref = s.domain().lo;
  std::vector<Vec2> group_pos;
  std::vector<real> group_level;
  for (const RigidGroup& g : s.groups()) {
    group_pos.push_back(g.pos);
    group_level.push_back(sc.params.rho0 * scalars.c2 * (1 + 1e-3 * static_cast<real>(group_level.size())));
  }
  LoadArrays ref = host_arrays(s, scalars);
  ref.group_pos = group_pos.data();
  ref.group_level = group_level.data();

  CpuBackend& host = s.host();
  host.set_load_band(band);
  std::vector<Vec2> num_den, fp, fv, torque, fd;
  host.band_levels(scalars, num_den);
  host.band_loads(scalars, group_pos, group_level, fp, fv, torque, fd);
  ASSERT_EQ(num_den.size(), band.size());
  ASSERT_EQ(fd.size(), band.size());
  std::size_t damped = 0;
  for (std::size_t e = 0; e < band.size(); ++e) {
    real num, den;
    band_entry_level(ref, band[e], num, den);
    EXPECT_TRUE(close(num_den[e].x, num)) << e << ": " << num_den[e].x << " against " << num;
    EXPECT_TRUE(close(num_den[e].y, den)) << e << ": " << num_den[e].y << " against " << den;
    Vec2 efp, efv, et, efd;
    band_entry_load(ref, band[e], efp, efv, et, efd);
    EXPECT_TRUE(same(fp[e], efp) && same(fv[e], efv) && same(torque[e], et) && same(fd[e], efd))
        << "entry " << e;
    damped += norm2(efd) > 0;
  }
  EXPECT_GT(damped, band.size() / 2) << "the damping's share read from the stage's accelerations";

  // the loads summed per block slot: the CPU adds each entry as it evaluates it, the host sum
  // adds the per-entry loads, both in the entries' order within each block
  std::vector<BandEntry> slotted = band;
  const std::vector<std::size_t> block_first = assign_slots(slotted, ng);
  ASSERT_GT(block_first.size(), 3u);
  std::vector<std::uint8_t> circle(ng);
  for (std::size_t k = 0; k < ng; ++k) circle[k] = k % 2;
  host.set_load_band(slotted);
  std::vector<BandLoadSum> fused, summed;
  host.band_load_sums(scalars, group_pos, group_level, circle, block_first, fused);
  host.band_loads(scalars, group_pos, group_level, fp, fv, torque, fd);
  sum_band_entry_loads(slotted, block_first, circle, fp, fv, torque, fd, summed);
  std::vector<BandLoadSum> expected(block_first.back()), plain(block_first.back());
  std::vector<real> magnitude(block_first.back());
  for (std::size_t e = 0; e < slotted.size(); ++e) {
    const BandEntry& be = slotted[e];
    const std::size_t q = block_first[e / kBandBlock] + be.slot;
    ASSERT_EQ(slot_group[q], be.group);
    add_band_entry_load(expected[q], fp[e], fv[e], torque[e], fd[e],
                        circle[static_cast<std::size_t>(be.group)] && be.in_film);
    add_band_entry_load(plain[q], fp[e], fv[e], torque[e], fd[e], false);
    magnitude[q] += norm(fp[e]) + norm(fv[e]) + norm(fd[e]) + std::abs(torque[e].x) + std::abs(torque[e].y);
  }
  ASSERT_EQ(fused.size(), expected.size());
  ASSERT_EQ(summed.size(), expected.size());
  std::size_t film_torques = 0;
  for (std::size_t q = 0; q < expected.size(); ++q) {
    const real tol = kRoundOff * magnitude[q] + 1e-300;
    const BandLoadSum& a = fused[q];
    const BandLoadSum& b = expected[q];
    EXPECT_TRUE(norm(a.fp - b.fp) <= tol && norm(a.fv - b.fv) <= tol && norm(a.fd - b.fd) <= tol &&
                std::abs(a.torque - b.torque) <= tol)
        << "slot " << q;
    // additions only: the host sum is the expected one bit for bit
    const auto bits = [](Vec2 u, Vec2 v) { return u.x == v.x && u.y == v.y; };
    EXPECT_TRUE(bits(summed[q].fp, b.fp) && bits(summed[q].fv, b.fv) && bits(summed[q].fd, b.fd) &&
                summed[q].torque == b.torque)
        << "slot " << q;
    film_torques += plain[q].torque != b.torque;
  }
  EXPECT_GT(film_torques, 0u) << "a circle's entries in a film leave out their pressure torque";

  // the levels summed per block slot likewise
  std::vector<Vec2> fused_levels, summed_levels;
  host.band_level_sums(scalars, block_first, fused_levels);
  host.band_levels(scalars, num_den);
  sum_band_entry_levels(slotted, block_first, num_den, summed_levels);
  std::vector<Vec2> expected_levels(block_first.back()), level_magnitude(block_first.back());
  for (std::size_t e = 0; e < slotted.size(); ++e) {
    const std::size_t q = block_first[e / kBandBlock] + slotted[e].slot;
    expected_levels[q] += num_den[e];
    level_magnitude[q] += Vec2{std::abs(num_den[e].x), std::abs(num_den[e].y)};
  }
  ASSERT_EQ(fused_levels.size(), expected_levels.size());
  ASSERT_EQ(summed_levels.size(), expected_levels.size());
  for (std::size_t q = 0; q < expected_levels.size(); ++q) {
    EXPECT_LE(std::abs(fused_levels[q].x - expected_levels[q].x), kRoundOff * level_magnitude[q].x + 1e-300)
        << q;
    EXPECT_LE(std::abs(fused_levels[q].y - expected_levels[q].y), kRoundOff * level_magnitude[q].y + 1e-300)
        << q;
    EXPECT_TRUE(summed_levels[q].x == expected_levels[q].x && summed_levels[q].y == expected_levels[q].y)
        << q;
  }

  // a later band replaces the entries
  const std::vector<BandEntry> fewer(band.begin() + 5, band.begin() + 20);
  host.set_load_band(fewer);
  host.band_levels(scalars, num_den);
  ASSERT_EQ(num_den.size(), fewer.size());
  for (std::size_t e = 0; e < fewer.size(); ++e) {
    real num, den;
    band_entry_level(ref, fewer[e], num, den);
    EXPECT_TRUE(close(num_den[e].x, num)) << e << ": " << num_den[e].x << " against " << num;
    EXPECT_TRUE(close(num_den[e].y, den)) << e << ": " << num_den[e].y << " against " << den;
  }
}
