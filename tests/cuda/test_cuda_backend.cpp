// The CUDA backend against the CPU path. On a machine without a GPU (or a build
// without CUDA) the comparisons skip with the reason, and the refusal path is checked instead.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "particula/case/load.hpp"
#include "particula/scene/scene.hpp"
#include "particula/solver/backend.hpp"
#include "particula/solver/solver.hpp"

namespace particula {
namespace {

Case load(const std::string& name, const std::vector<std::string>& overrides) {
  return load_case(std::string(PARTICULA_SOURCE_DIR) + "/cases/" + name + ".toml", overrides);
}

struct Difference {
  double body_velocity = 0;  // max over bodies of |V_gpu - V_cpu| / |V_cpu|, and the same for Omega
  double fluid_velocity = 0;  // max over particles of |v_gpu - v_cpu| / max |v_cpu|
  double damping = 0;         // max over solids of |fd_gpu - fd_cpu| / max |fd_cpu| (the damping's sink)
  std::int64_t created = 0;   // particles the CPU run created at its open boundaries
};

/// Runs `steps` steps of the case on the CPU and on the GPU, in double precision, and compares.
Difference compare(const Case& c, int steps) {
  Scene a = build_scene(c), b = build_scene(c);
  b.params.cuda = true;
  Solver cpu(a.params, a.domain, std::move(a.particles), a.groups);
  Solver gpu(b.params, b.domain, std::move(b.particles), b.groups);
  for (int s = 0; s < steps; ++s) {
    EXPECT_FALSE(cpu.step().has_value()) << "cpu step " << s;
    EXPECT_FALSE(gpu.step().has_value()) << "gpu step " << s;
  }
  // dt depends on the largest speed, which differs in the last bits (the body loads are summed
  // in another order on the GPU), so the times agree to round-off, not bitwise.
  EXPECT_NEAR(cpu.time(), gpu.time(), 1e-12 * cpu.time());
  Difference d;
  double fd_max = 0;
  for (const RigidGroup& g : cpu.groups()) fd_max = std::max(fd_max, norm(g.force_damping));
  for (std::size_t k = 0; k < cpu.groups().size(); ++k) {
    const RigidGroup& gc = cpu.groups()[k];
    const RigidGroup& gg = gpu.groups()[k];
    if (fd_max > 0) d.damping = std::max(d.damping, norm(gg.force_damping - gc.force_damping) / fd_max);
    if (gc.is_wall) continue;
    if (norm(gc.vel) > 0) d.body_velocity = std::max(d.body_velocity, norm(gg.vel - gc.vel) / norm(gc.vel));
    if (gc.omega != 0) d.body_velocity = std::max(d.body_velocity, std::fabs(gg.omega - gc.omega) / std::fabs(gc.omega));
  }
  const Particles& pc = cpu.particles();
  const Particles& pg = gpu.particles();
  // By id: open boundaries create and delete particles, so ids run past the count; both
  // backends must hold the same particles.
  EXPECT_EQ(pc.size(), pg.size());
  std::map<std::int64_t, Vec2> vg;
  for (std::size_t i = 0; i < pg.size(); ++i) vg[pg.id[i]] = pg.v[i];
  double vmax = 0;
  for (std::size_t i = 0; i < pc.size(); ++i) vmax = std::max(vmax, norm(pc.v[i]));
  for (std::size_t i = 0; i < pc.size(); ++i) {
    const auto it = vg.find(pc.id[i]);
    if (it == vg.end()) {
      ADD_FAILURE() << "particle id " << pc.id[i] << " is on the CPU only";
      d.fluid_velocity = 1;
      continue;
    }
    d.fluid_velocity = std::max(d.fluid_velocity, norm(it->second - pc.v[i]) / vmax);
  }
  for (std::size_t z = 0; z < cpu.open_flux().size(); ++z) {
    const OpenFlux& fc = cpu.open_flux()[z];
    const OpenFlux& fg = gpu.open_flux()[z];
    d.created += fc.created;
    EXPECT_EQ(fc.created, fg.created) << "open boundary " << z;
    EXPECT_EQ(fc.deleted, fg.deleted) << "open boundary " << z;
    EXPECT_NEAR(fc.mass, fg.mass, 1e-12 * std::max(std::fabs(fc.mass), 1e-30)) << "open boundary " << z;
  }
  return d;
}

bool have_gpu(std::string& why) { return cuda_backend_available(&why); }

/// A case, its overrides and how many steps to compare.
struct CaseRun {
  const char* name;
  std::vector<std::string> overrides;
  int steps;
};

/// Runs each case on the CPU and the GPU and requires body and fluid velocities to agree to 1e-9,
/// and the damping's sink next to the solids to 1e-6; with `creates`, also that the CPU run created particles at its
/// open boundaries.
void expect_cases_agree(const std::vector<CaseRun>& cases, bool creates) {
  for (const CaseRun& k : cases) {
    const Difference d = compare(load(k.name, k.overrides), k.steps);
    std::printf(
        "%s, %d steps: %lld particles created, body velocity rel. difference %.3g, fluid velocity %.3g, "
        "damping's sink %.3g\n",
        k.name, k.steps, static_cast<long long>(d.created), d.body_velocity, d.fluid_velocity, d.damping);
    if (creates) {
      EXPECT_GT(d.created, 0) << k.name << ": the transfer must have run";
    }
    EXPECT_LT(d.body_velocity, 1e-9) << k.name;
    EXPECT_LT(d.fluid_velocity, 1e-9) << k.name;
    // a difference of two Laplacians, small beside the loads: round-off differences of the
    // velocities weigh more in it (not yet run on a device: 1e-6 catches a sink left out or stale)
    EXPECT_LT(d.damping, 1e-6) << k.name;
  }
}

TEST(CudaBackend, FallingCylinderAgreesWithCpuAfter100Steps) {
  std::string why;
  if (!have_gpu(why)) GTEST_SKIP() << "no CUDA backend here: " << why;
  expect_cases_agree({{"falling_cylinder", {"resolution.d0=2.5e-4"}, 100}}, false);
}

TEST(CudaBackend, CollidingBodiesPeriodicShearAndDummyWallsAgreeWithCpu) {
  std::string why;
  if (!have_gpu(why)) GTEST_SKIP() << "no CUDA backend here: " << why;
  expect_cases_agree({{"dkt", {"resolution.d0=2e-4"}, 60},
                      {"two_cylinders_shear", {}, 60},
                      {"falling_cylinder", {"resolution.d0=2.5e-4", "numerics.boundary=dummy"}, 60},
                      {"couette", {}, 60}},
                     false);
}

TEST(CudaBackend, OpenBoundariesAgreeWithCpu) {
  // The open-boundary passes run on the host between the device's passes (fits, buffer fields,
  // transfer): the same particles must be created and deleted, with the same fields. Steps
  // enough for each to create particles (on the CPU: 4, 56 and 44).
  std::string why;
  if (!have_gpu(why)) GTEST_SKIP() << "no CUDA backend here: " << why;
  expect_cases_agree({{"poiseuille_open", {"resolution.d0=1e-4", "inlet.0.ramp_time=0"}, 400},
                      {"dfg_2d1", {"resolution.d0=0.01", "inlet.0.ramp_time=0.01"}, 150},
                      {"particle_channel", {"outlet.0.bodies=removed", "inlet.0.ramp_time=0"}, 400}},
                     true);
}

TEST(CudaBackend, WithoutAGpuTheBackendIsRefusedWithAReason) {
  std::string why;
  if (have_gpu(why)) GTEST_SKIP() << "a GPU is present";
  EXPECT_FALSE(why.empty());
  const Case c = load("couette", {});
  Scene s = build_scene(c);
  s.params.cuda = true;
  EXPECT_THROW(Solver(s.params, s.domain, std::move(s.particles), s.groups), std::runtime_error);
  // The command line refuses it before writing anything: exit code 2.
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "particula_cuda_refused";
  std::filesystem::remove_all(dir);
  const std::string cmd = std::string(PARTICULA_BINARY) + " run " + PARTICULA_SOURCE_DIR +
                          "/cases/couette.toml --quiet --backend cuda --out " + dir.string() + " > /dev/null 2>&1";
  const int rc = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(rc));
  EXPECT_EQ(WEXITSTATUS(rc), 2);
  EXPECT_FALSE(std::filesystem::exists(dir));
}

}  // namespace
}  // namespace particula
