// Seeded random cases: the generator's promises (same seed, same text; what it draws
// stays in its documented ranges) and, slow and left out under sanitizers, a batch of random
// cases run for a few hundred steps each: a refusal at load is allowed and counted, a numerical
// failure (exit 3 of `particula run`) or a time step below 1e-3 of the case's own fails the test with
// its seed, message and time. `particula validate --group random` runs 200 seeds to their end.
#include <gtest/gtest.h>


#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "particula/case/error.hpp"
#include "particula/case/load.hpp"
#include "particula/scene/scene.hpp"
#include "particula/solver/solver.hpp"
#include "particula/validation/random_case.hpp"

using namespace particula;

namespace {

/// Seeds of the batch: the first 24 (each new failure gets a reproducible name:
/// `particula generate --seed N --out case.toml && particula run case.toml`).
constexpr std::uint64_t kSeeds = 32;

/// Steps each accepted case runs (a few hundred: enough for bodies to start moving, the
/// pressure waves of the start to cross the box and the first contacts to happen).
constexpr int kSteps = 300;

}  // namespace

TEST(RandomCaseGenerator, SameSeedSameText) {
  EXPECT_EQ(random_case_toml(5), random_case_toml(5));
  EXPECT_NE(random_case_toml(5), random_case_toml(6));
  EXPECT_EQ(random_case_toml(5).rfind("# Random case of seed 5 ", 0), 0u);
}

TEST(RandomCaseGenerator, DrawsStayInTheirRangesAndCoverEveryContainer) {
  int with_bodies = 0, light = 0, heavy = 0;
  std::map<std::string, int> containers;
  for (std::uint64_t seed = 1; seed <= 80; ++seed) {
    SCOPED_TRACE(seed);
    const std::string text = random_case_toml(seed);
    const std::string first = text.substr(0, text.find('\n'));
    containers[first.substr(first.find("placed, ") + 8)]++;
    Case c;
    try {
      c = load_case_text(text, "random.toml");
    } catch (const CaseError& e) {
      ADD_FAILURE() << "refused at load: " << e.what();  // the generator means to make valid cases
      continue;
    }
    EXPECT_LE(c.bodies.size(), 12u);
    EXPECT_GE(c.d0, 5e-5 * (1 - 1e-9));
    EXPECT_LE(c.d0, 2e-4 * (1 + 1e-9));
    const Vec2 span = c.domain_max - c.domain_min;
    EXPECT_LE(span.x * span.y / (c.d0 * c.d0), 6400) << "a small case";
    const real dt = 0.25 * std::min(c.d0 / c.c, c.d0 * c.d0 / c.nu);
    EXPECT_LE(c.t_end / dt, 2000 * (1 + 1e-6)) << "a short case";
    if (c.bodies.empty()) continue;
    ++with_bodies;
    double smallest = 1e300;
    for (const auto& b : c.bodies) {
      smallest = std::min(smallest, body_shape(b).min_width());
      if (b.motion == BodyMotion::Free) {
        EXPECT_TRUE(b.density >= 100 * (1 - 1e-6) && b.density <= 3000 * (1 + 1e-6)) << b.density;
        light += b.density < 300;
        heavy += b.density > 2000;
      }
    }
    EXPECT_GE(smallest / c.d0, 10 * (1 - 1e-6));
    EXPECT_LE(smallest / c.d0, 32 * (1 + 1e-6)) << "the first body drawn is 10-20 d0, the others up to 1.6 times that";
  }
  EXPECT_GT(with_bodies, 40);
  EXPECT_GT(light, 3) << "free bodies down to 0.1 rho0";
  EXPECT_GT(heavy, 3);
  EXPECT_EQ(containers.size(), 8u) << "every kind of container";
  for (const auto& [kind, count] : containers) {
    std::printf("%s: %d\n", kind.c_str(), count);
    EXPECT_GE(count, 3) << kind;
  }
}

namespace {

struct Outcome {
  bool refused = false;
  std::string refusal;
  std::optional<Failure> failure;
  double time = 0;
  std::int64_t step = 0;
  std::size_t particles = 0, bodies = 0;
  double dt_ratio = 1e300;  // the smallest step over the case's own
};

Outcome run_seed(std::uint64_t seed) {
  Outcome o;
  Case c;
  try {
    c = load_case_text(random_case_toml(seed), "random_" + std::to_string(seed) + ".toml");
  } catch (const CaseError& e) {
    o.refused = true;
    o.refusal = e.what();
    return o;
  }
  Scene s = build_scene(c);
  o.particles = s.particles.size();
  o.bodies = c.bodies.size();
  Solver solver(s.params, s.domain, s.particles, s.groups);
  for (int k = 0; k < kSteps && solver.time() < c.t_end; ++k) {
    o.failure = solver.step(c.t_end - solver.time());
    if (o.failure) break;
    o.dt_ratio = std::min(o.dt_ratio, solver.last_dt() / solver.case_dt());
  }
  o.time = solver.time();
  o.step = solver.step_count();
  return o;
}

}  // namespace

TEST(RandomCases, RunWithoutNumericalFailure) {
  int refused = 0, finished = 0;
  std::vector<std::string> failures;
  for (std::uint64_t seed = 1; seed <= kSeeds; ++seed) {
    Outcome o = run_seed(seed);
    if (o.refused) {
      ++refused;
      std::printf("seed %llu: refused at load: %s\n", static_cast<unsigned long long>(seed), o.refusal.c_str());
      continue;
    }
    std::printf("seed %llu: %zu particles, %zu bodies: %s after %lld steps at t = %.6g s, smallest dt / case's %.3g\n",
                static_cast<unsigned long long>(seed), o.particles, o.bodies, o.failure ? "FAILED" : "ok",
                static_cast<long long>(o.step), o.time, o.dt_ratio);
    if (!o.failure && o.dt_ratio < kTimeStepDrop)
      o.failure = Failure{"the time step fell below 1e-3 of the case's", -1, {}};
    if (!o.failure) {
      ++finished;
      continue;
    }
    failures.push_back(std::to_string(seed) + ": " + o.failure->what + " at t = " + std::to_string(o.time) +
                       " s, step " + std::to_string(o.step));
  }
  std::printf("random cases: %llu generated, %d refused at load, %d finished %d steps, %zu failed\n",
              static_cast<unsigned long long>(kSeeds), refused, finished, kSteps, failures.size());
  for (const auto& f : failures) ADD_FAILURE() << "seed " << f;
}
