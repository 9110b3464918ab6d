// Seeded random cases for robustness tests: `particula generate --seed N` and the
// random-case test. A seed gives a case file (TOML text) that should load: 0-12 bodies (circle,
// ellipse, convex polygon of 3-6 vertices, half_disc), free (density 500-3000 kg/m^3 or
// neutrally buoyant), fixed or prescribed, at least 2 d0 clear of each other and of the walls,
// in a closed box under gravity or in a periodic channel between sliding walls with a body
// force; 10-20 particles across the smallest body, at most about 6000 particles, default
// numerics and contact model. Same seed, same text, on every platform (SplitMix64, fixed
// formatting).
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
