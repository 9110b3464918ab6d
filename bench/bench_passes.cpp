// Google Benchmark micro-benchmarks of the neighbour search and of each pass of a time step,
// on the falling-cylinder case (paper 7.2). The resolution is the benchmark argument in
// particles across the cylinder diameter (25 -> d0 = 1e-4 m, about 1.2e5 particles).
// Items processed = particles, so the reported rate is particles (or particle-steps) per second.
// Contact detection (BM_ContactCandidates*) runs on n random bodies instead; items = bodies.
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <string>

#include "particula/bodies/contact_pairs.hpp"
#include "particula/case/load.hpp"
#include "particula/neighbors/neighbor_list.hpp"
#include "particula/scene/scene.hpp"
#include "particula/solver/solver.hpp"
#include "particula/solver/sweeps.hpp"

namespace {

using namespace particula;

/// One solver per resolution, built once and advanced a few steps so that the fields are
/// those of a running simulation (a moving body, a non-trivial pressure).
Solver& solver_for(int across) {
  static std::unique_ptr<Solver> s;
  static int built = -1;
  if (built != across) {
    const std::string d0 = std::to_string(2.5e-3 / across);
    Case c = load_case(std::string(PARTICULA_SOURCE_DIR) + "/cases/falling_cylinder.toml", {"resolution.d0=" + d0});
    Scene scene = build_scene(c);
    s = std::make_unique<Solver>(scene.params, scene.domain, std::move(scene.particles), scene.groups);
    for (int k = 0; k < 3; ++k) s->step();
    built = across;
  }
  return *s;
}

void set_items(benchmark::State& state, const Solver& s) {
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(s.particles().size()));
  state.counters["particles"] = static_cast<double>(s.particles().size());
}

void BM_NeighborList(benchmark::State& state) {
  Solver& s = solver_for(static_cast<int>(state.range(0)));
  CellGrid grid;
  grid.setup(s.domain(), s.params().h);
  NeighborList nl;
  for (auto _ : state) {
    build_neighbor_list(s.particles().x, s.domain(), s.kernel(), grid, nl);
    benchmark::DoNotOptimize(nl.j.data());
  }
  set_items(state, s);
  state.counters["pairs/particle"] = static_cast<double>(nl.pair_count()) / static_cast<double>(s.particles().size());
}

void BM_Geometry(benchmark::State& state) {  // neighbour list + B, Bhat, normals, shifting direction
  Solver& s = solver_for(static_cast<int>(state.range(0)));
  for (auto _ : state) s.refresh_geometry();
  set_items(state, s);
}

void BM_VelocityDerivatives(benchmark::State& state) {
  Solver& s = solver_for(static_cast<int>(state.range(0)));
  const auto v = s.particles().v;
  for (auto _ : state) s.host().compute_velocity_derivatives(v);
  set_items(state, s);
}

void BM_PressureGradient(benchmark::State& state) {
  Solver& s = solver_for(static_cast<int>(state.range(0)));
  const auto p = s.particles().p;
  const auto rho = s.particles().rho;
  for (auto _ : state) s.host().compute_pressure_gradient(p, rho);
  set_items(state, s);
}

void BM_RhieChow(benchmark::State& state) {
  Solver& s = solver_for(static_cast<int>(state.range(0)));
  const SweepContext c = s.host().sweep_context();
  const auto& P = s.particles();
  const Vec2* G = s.host().grad_p_over_rho().data();
  std::vector<real> rc(P.size());
  for (auto _ : state) {
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < P.size(); ++i) rc[i] = rhie_chow_at(c, i, P.p.data(), P.rho.data(), G);
    benchmark::DoNotOptimize(rc.data());
  }
  set_items(state, s);
}

void BM_WallPressure(benchmark::State& state) {  // items = boundary particles
  Solver& s = solver_for(static_cast<int>(state.range(0)));
  const SweepContext c = s.host().sweep_context();
  const auto& P = s.particles();
  std::vector<real> out(P.n_boundary);
  const real min_den = wall_pressure_min_den(1000, c.kernel.h);
  const real void_distance = kVoidDistance * s.params().d0;
  for (auto _ : state) {
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < P.n_boundary; ++i)
      wall_pressure_at(c, i, P.p.data(), P.rho.data(), P.normal[i], P.acc[i], Vec2{}, Vec2{}, min_den, void_distance, 0, out[i]);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(P.n_boundary));
}

void BM_Step(benchmark::State& state) {
  Solver& s = solver_for(static_cast<int>(state.range(0)));
  for (auto _ : state) s.step();
  set_items(state, s);
}

/// n discs (R = 1 mm, bounding radii 0.5-1 mm) at random in a periodic box holding them at an
/// area fraction of about 30 % (seeded: the same configuration every run).
struct BodyCloud {
  std::vector<Vec2> pos;
  std::vector<real> bound;
  Domain domain;
};

BodyCloud body_cloud(int n) {
  BodyCloud c;
  const real side = std::sqrt(n * M_PI * 1e-6 / 0.3);
  c.domain = Domain{{0, 0}, {side, side}, true, true};
  SplitMix64 rng(7);
  for (int i = 0; i < n; ++i) {
    c.pos.push_back({0.5 * side * (rng.symmetric() + 1), 0.5 * side * (rng.symmetric() + 1)});
    c.bound.push_back(1e-3 * (0.75 + 0.25 * rng.symmetric()));
  }
  return c;
}

/// Contact candidates of one step: the cell list over the bodies (what the solver uses).
void BM_ContactCandidates(benchmark::State& state) {
  const BodyCloud c = body_cloud(static_cast<int>(state.range(0)));
  std::vector<BodyPair> pairs;
  for (auto _ : state) {
    contact_candidates(c.pos, c.bound, 1e-4, c.domain, pairs);
    benchmark::DoNotOptimize(pairs.data());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.counters["pairs"] = static_cast<double>(pairs.size());
}

/// The same by testing all pairs (the quadratic search the cell list replaces).
void BM_ContactCandidatesAllPairs(benchmark::State& state) {
  const BodyCloud c = body_cloud(static_cast<int>(state.range(0)));
  std::vector<BodyPair> pairs;
  for (auto _ : state) {
    contact_candidates_all_pairs(c.pos, c.bound, 1e-4, c.domain, pairs);
    benchmark::DoNotOptimize(pairs.data());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.counters["pairs"] = static_cast<double>(pairs.size());
}

// 10 and 25 particles across the cylinder: d0 = 2.5e-4 (about 2e4 particles) and 1e-4 (1.2e5).
BENCHMARK(BM_NeighborList)->Arg(10)->Arg(25)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Geometry)->Arg(10)->Arg(25)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_VelocityDerivatives)->Arg(10)->Arg(25)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_PressureGradient)->Arg(10)->Arg(25)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_RhieChow)->Arg(10)->Arg(25)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_WallPressure)->Arg(10)->Arg(25)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Step)->Arg(10)->Arg(25)->Unit(benchmark::kMillisecond)->UseRealTime();
// contact detection at 1000 (and 30) bodies
BENCHMARK(BM_ContactCandidates)->Arg(30)->Arg(1000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ContactCandidatesAllPairs)->Arg(30)->Arg(1000)->Unit(benchmark::kMicrosecond);

}  // namespace
