// Seeded random cases for robustness tests: `particula generate --seed N`, the random-case test
// and `particula validate --group random`. A seed gives a case file (TOML text) that should load:
// a container (closed box, L- or T-shape, hopper, 5-8-gon, arc-bottomed U, a periodic channel
// between sliding walls with a body force, or a channel from a parabolic inlet to an outlet),
// 0-12 bodies (circle, ellipse, convex polygon of 3-6 vertices, half_disc; free from 0.1 to 3 times
// the fluid's density or neutrally buoyant, fixed, or prescribed; fixed and prescribed ones half
// of the time 1-3 d0 from a wall, the rest at least 2 d0 clear of each other and of the walls),
// Re = U s / nu from 0.1 to 100; 10-20 particles across the smallest body, at most about 5000
// particles, default numerics and contact model, and an end time of at most 2000 of the case's
// own steps. Same seed, same text, on every platform (SplitMix64, fixed formatting).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace particula {

/// The case file text of seed `seed` (its header comment names the seed and what was drawn).
std::string random_case_toml(std::uint64_t seed);

/// `particula generate --seed N [--out FILE]`: writes the case of seed N to FILE (standard
/// output when empty). Exit 0, or 2 when FILE cannot be written.
int generate_command(std::uint64_t seed, const std::filesystem::path& out);

}  // namespace particula
