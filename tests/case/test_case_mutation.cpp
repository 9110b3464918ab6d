// Mutation test: hundreds of damaged variants of a valid case either load or throw CaseError;
// nothing else (no other exception, no crash, no hang).
#include <gtest/gtest.h>

#include <cstdint>
#include <regex>
#include <string>
#include <vector>

#include "particula/case/load.hpp"

using namespace particula;

namespace {

const std::string kValid = R"(name = "mutant"
description = "base case of the mutation test"

[domain]
min = [0.0, 0.0]
max = [1e-3, 2e-3]
periodic = [true, false]

[resolution]
d0 = 2.5e-5
h_over_d0 = 2.6

[fluid]
rho0 = 1000
nu = 1e-6
c = 0.1
gravity = [0, -9.81]
gravity_in_fluid = true

[time]
end = 1.0
cfl = 0.5
max_steps = 1000

[numerics]
laplacian = "morris"
wall_pressure_sweeps = 2

[initial]
seed = 7
flow = "taylor_green"
amplitude = 1e-3

[output]
interval = 0.01
snapshot_interval = 0.1

[guard]
rho_min_ratio = 0.5

[[wall]]
from = [0.0, 0.0]
to = [1e-3, 0.0]

[[wall]]
name = "lid"
from = [1e-3, 2e-3]
to = [0.0, 2e-3]
velocity = [1e-3, 0]

[[probe]]
name = "mid"
from = [5e-4, 0.0]
to = [5e-4, 2e-3]
points = 11
interval = 0.1

[collision]
stiffness = 1.5e6
range = 7.5e-5

[[body]]
name = "drop"
shape = "circle"
center = [5e-4, 1.4e-3]
radius = 2e-4
density = 1200
velocity = [0, -1e-4]

[[body]]
shape = "polygon"
vertices = [[3e-4, 3e-4], [7e-4, 3e-4], [5e-4, 7e-4]]
motion = "prescribed"
schedule = [[0, 0, 0, 0], [0.5, 1e-4, 0, 0.1]]
)";

/// A small deterministic generator (same sequence on every platform).
struct Rng {
  std::uint64_t s;
  std::uint64_t next() {  // splitmix64
    std::uint64_t z = (s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  std::size_t below(std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(next() % n); }
};

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t b = 0;
  for (std::size_t e; (e = text.find('\n', b)) != std::string::npos; b = e + 1)
    lines.push_back(text.substr(b, e - b));
  return lines;
}

std::string join(const std::vector<std::string>& lines) {
  std::string s;
  for (const auto& l : lines) s += l + "\n";
  return s;
}

std::string delete_line(const std::string& text, Rng& rng) {
  auto lines = lines_of(text);
  if (lines.empty()) return text;
  lines.erase(lines.begin() + static_cast<long>(rng.below(lines.size())));
  return join(lines);
}

std::string duplicate_line(const std::string& text, Rng& rng) {
  auto lines = lines_of(text);
  if (lines.empty()) return text;
  const std::size_t i = rng.below(lines.size());
  lines.insert(lines.begin() + static_cast<long>(i), lines[i]);
  return join(lines);
}

/// Replaces one number with a string, its negative, a huge, non-finite or overflowing value.
std::string replace_number(const std::string& text, Rng& rng) {
  static const std::regex number(R"([-+]?[0-9][0-9.eE+\-]*)");
  std::vector<std::pair<std::size_t, std::size_t>> spans;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), number); it != std::sregex_iterator(); ++it)
    spans.emplace_back(static_cast<std::size_t>(it->position()), static_cast<std::size_t>(it->length()));
  if (spans.empty()) return text;
  const auto [pos, len] = spans[rng.below(spans.size())];
  const std::string old = text.substr(pos, len);
  const std::string replacements[] = {
      "\"" + old + "\"",      "-" + old, "1e308",  "-1e308", "nan",   "inf", "-inf",
      "99999999999999999999", "0",       "1e-320", "true",   "[1, 2]"};
  std::string out = text;
  out.replace(pos, len, replacements[rng.below(std::size(replacements))]);
  return out;
}

std::string insert_bytes(const std::string& text, Rng& rng) {
  std::string bytes;
  for (std::size_t n = 1 + rng.below(8); n > 0; --n) bytes += static_cast<char>(rng.below(256));
  std::string out = text;
  out.insert(rng.below(text.size() + 1), bytes);
  return out;
}

std::string truncate(const std::string& text, Rng& rng) { return text.substr(0, rng.below(text.size() + 1)); }

/// Swaps two lines (moves keys between tables).
std::string swap_lines(const std::string& text, Rng& rng) {
  auto lines = lines_of(text);
  if (lines.empty()) return text;
  std::swap(lines[rng.below(lines.size())], lines[rng.below(lines.size())]);
  return join(lines);
}

using Mutation = std::string (*)(const std::string&, Rng&);
constexpr Mutation kMutations[] = {delete_line,  duplicate_line, replace_number,
                                   insert_bytes, truncate,       swap_lines};

}  // namespace

TEST(CaseMutation, VariantsLoadOrThrowCaseError) {
  ASSERT_NO_THROW(load_case_text(kValid, "cases/mutant.toml"));
  Rng rng{12345};
  int loaded = 0, rejected = 0;
  for (int i = 0; i < 600; ++i) {
    std::string text = kValid;
    const std::size_t rounds = 1 + rng.below(3);  // one to three mutations on top of each other
    for (std::size_t r = 0; r < rounds; ++r) text = kMutations[rng.below(std::size(kMutations))](text, rng);
    try {
      const Case c = load_case_text(text, "cases/mutant.toml");
      ++loaded;
      // Whatever loads must also survive its own round trip.
      EXPECT_EQ(resolved_case_toml(load_case_text(resolved_case_toml(c), "case.toml")),
                resolved_case_toml(c));
    } catch (const CaseError& e) {
      ++rejected;
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "multi-line message: " << e.what();
    } catch (const std::exception& e) {
      ADD_FAILURE() << "variant " << i << " threw a non-CaseError: " << e.what() << "\n" << text;
    } catch (...) {
      ADD_FAILURE() << "variant " << i << " threw a non-exception\n" << text;
    }
  }
  EXPECT_GT(loaded, 20);
  EXPECT_GT(rejected, 200);
  std::printf("mutation test: %d variants loaded, %d rejected with CaseError\n", loaded, rejected);
}

TEST(CaseMutation, OverridesWithGarbage) {
  Rng rng{777};
  const std::string keys[] = {"resolution.d0",
                              "fluid.gravity",
                              "probe.0.points",
                              "wall.1.velocity",
                              "name",
                              "numerics.laplacian",
                              "domain.periodic",
                              "x",
                              "probe.9.name",
                              "body.0.radius",
                              "body.1.vertices",
                              "body.1.schedule",
                              "body.0.shape",
                              "collision.range",
                              ""};
  const std::string values[] = {"1",
                                "-1",
                                "[1,2]",
                                "nan",
                                "\"s\"",
                                "[",
                                "1e999",
                                "true",
                                "a b",
                                "",
                                "\x01\xff",
                                "[[0,0],[1,0],[0,1]]",
                                "[[0,0,0,0],[1,1,1,1]]",
                                "[[1,2],[3]]",
                                "polygon",
                                "[[]]"};
  for (int i = 0; i < 300; ++i) {
    std::string o = keys[rng.below(std::size(keys))];
    if (rng.below(8) != 0) o += "=";
    o += values[rng.below(std::size(values))];
    try {
      load_case_text(kValid, "cases/mutant.toml", {o});
    } catch (const CaseError&) {
    } catch (...) {
      ADD_FAILURE() << "override '" << o << "' threw a non-CaseError";
    }
  }
}
