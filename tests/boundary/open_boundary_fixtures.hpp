// Shared by the open-boundary tests (test_open_boundary.cpp, test_open_bodies.cpp): the shipped
// open channel at a coarse level, a solver built from a case, and a run, a shorter run and its
// resumption through the command line, for the bitwise resume checks.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "cli_process.hpp"
#include "particula/case/load.hpp"
#include "particula/io/vtk.hpp"
#include "particula/scene/scene.hpp"
#include "particula/solver/solver.hpp"

namespace open_test {

inline const std::filesystem::path kChannel =
    std::filesystem::path(PARTICULA_SOURCE_DIR) / "cases" / "poiseuille_open.toml";

/// The shipped open channel at 10 particles across (d0 = 1e-4 m), with `extra` overrides.
inline particula::Case channel(std::vector<std::string> extra = {}) {
  std::vector<std::string> o{"resolution.d0=1e-4"};
  o.insert(o.end(), extra.begin(), extra.end());
  return particula::load_case(kChannel, o);
}

/// A fast start: a uniform inflow of 1 cm/s from t = 0 (Mach 0.05), so that columns of the
/// inlet buffer enter the fluid and fluid reaches the outlet's buffer within a few hundred steps.
inline particula::Case fast_channel() {
  particula::Case c = channel();
  c.inlets.at(0).profile = particula::InletProfile::Uniform;
  c.inlets.at(0).velocity = 1e-2;
  c.inlets.at(0).ramp_time = 0;
  return c;
}

inline particula::Solver make_solver(const particula::Case& c) {
  particula::Scene sc = particula::build_scene(c);
  return particula::Solver(sc.params, sc.domain, std::move(sc.particles), std::move(sc.groups));
}

/// The exit codes and output of `particula run FILE` to `whole_end` in DIR/whole and to
/// `half_end` in DIR/half, and of `particula resume DIR/half` to `whole_end` (`common`: the
/// options of both runs). The resumed run's outputs must match the whole run's bitwise.
struct ResumeRuns {
  cli_test::Ended whole, half, resumed;
};
inline ResumeRuns whole_half_resumed(const std::filesystem::path& file, const std::filesystem::path& dir,
                                     const std::vector<std::string>& common, const std::string& whole_end,
                                     const std::string& half_end) {
  auto run = [&](const std::filesystem::path& out, const std::string& end) {
    std::vector<std::string> a{"run", file.string(), "--out", out.string(), "--set", "time.end=" + end};
    a.insert(a.end(), common.begin(), common.end());
    return cli_test::cli(a);
  };
  ResumeRuns r;
  r.whole = run(dir / "whole", whole_end);
  r.half = run(dir / "half", half_end);
  r.resumed = cli_test::cli({"resume", (dir / "half").string(), "--set", "time.end=" + whole_end, "--threads",
                             "1", "--quiet", "--no-plots"});
  return r;
}

/// Expects DIR/whole and DIR/half (resumed) to hold the same `files`, particles.pvd and
/// snapshots, byte for byte; returns the number of snapshots.
inline std::size_t expect_same_outputs(const std::filesystem::path& dir,
                                       const std::vector<std::string>& files) {
  for (const std::string& f : files) {
    const std::string a = cli_test::read_text(dir / "whole" / f), b = cli_test::read_text(dir / "half" / f);
    EXPECT_FALSE(a.empty()) << f;
    EXPECT_TRUE(a == b) << f << " differs after the resume";
  }
  EXPECT_TRUE(cli_test::read_text(dir / "whole" / "particles.pvd") ==
              cli_test::read_text(dir / "half" / "particles.pvd"));
  const auto index = particula::io::PvdIndex::read(dir / "whole" / "particles.pvd");
  for (const auto& e : index.entries())
    EXPECT_TRUE(cli_test::read_text(dir / "whole" / e.file) == cli_test::read_text(dir / "half" / e.file))
        << e.file;
  return index.entries().size();
}

}  // namespace open_test
