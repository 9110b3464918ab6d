// Bodies at open boundaries (docs/method.md, "Screens", "Bodies removed at an
// outlet"): screens that hold free bodies back from inlets and outlets (also against a flow
// pressing a body onto one), a prescribed body driven through a screen stopping the run, and an
// outlet that removes bodies: the fill, the mass balance, the checkpoint and a bitwise resume.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "cli_process.hpp"
#include "open_boundary_fixtures.hpp"
#include "particula/case/load.hpp"
#include "particula/io/csv.hpp"
#include "particula/io/error.hpp"
#include "particula/io/vtk.hpp"
#include "particula/run/checkpoint.hpp"
#include "particula/run/observers.hpp"
#include "particula/solver/momentum_loads.hpp"
#include "particula/solver/solver.hpp"

namespace fs = std::filesystem;
using namespace particula;
using namespace open_test;

TEST(OpenBoundary, ABodyDrivenThroughAScreenStopsTheRunNamingBoth) {
  // A prescribed body is not held by the outlet's screen (contacts act on free bodies): the run
  // stops when its surface comes within h of the line.
  Case c = channel({"resolution.d0=5e-5"});
  BodySpec b;
  b.name = "ball";
  b.shape = BodyShape::Circle;
  b.center = {4e-3, 5e-4};  // 0.75 mm from the outlet
  b.radius = 2.5e-4;
  b.motion = BodyMotion::Prescribed;
  b.velocity = {0.02, 0};  // carried towards the outlet at 2 cm/s
  c.bodies.push_back(b);
  Solver s = make_solver(c);
  std::optional<Failure> f;
  while (!f && s.time() < 0.2) f = s.step();
  ASSERT_TRUE(f.has_value()) << "the body passed into the outlet unnoticed";
  EXPECT_NE(f->what.find("body 'ball' has come within h of outlet 'out'"), std::string::npos) << f->what;
  EXPECT_NE(f->what.find("screen"), std::string::npos) << f->what;
  const real gap = 5e-3 - f->position.x - b.radius;
  EXPECT_LT(gap, s.params().h);
  EXPECT_GT(gap, s.params().h - 0.03 * s.last_dt() - 1e-12);
}

/// A column 6 mm wide and 12 mm tall, with an inflow of 1 mm/s from below and an outlet at the
/// top, a heavy disc (D = 2 mm = 10 d0, rho_s 2000) released 0.3 mm above the inlet's screen and
/// a light one (rho_s 500) 0.3 mm below the outlet's.
Case screened_column() {
  const std::string text = R"(
name = "screened_column"
[domain]
min = [0.0, 0.0]
max = [6.0e-3, 12.0e-3]
[resolution]
d0 = 2.0e-4
[fluid]
rho0 = 1000.0
mu = 0.01
c = 0.3
gravity = [0.0, -9.81]
[time]
end = 0.1
[output]
interval = 0.01
[[wall]]
name = "left"
from = [0.0, 12.0e-3]
to = [0.0, 0.0]
[[wall]]
name = "right"
from = [6.0e-3, 0.0]
to = [6.0e-3, 12.0e-3]
[[inlet]]
name = "in"
from = [0.0, 0.0]
to = [6.0e-3, 0.0]
velocity = 1.0e-3
[[outlet]]
name = "out"
from = [6.0e-3, 12.0e-3]
to = [0.0, 12.0e-3]
[[body]]
name = "heavy"
shape = "circle"
center = [3.0e-3, 3.9e-3]
radius = 1.0e-3
density = 2000.0
[[body]]
name = "light"
shape = "circle"
center = [3.0e-3, 8.1e-3]
radius = 1.0e-3
density = 500.0
)";
  return load_case_text(text, "screened_column.toml");
}

TEST(OpenBoundary, ScreensHoldFreeBodiesAwayFromAnInletAndAnOutlet) {
  const Case c = screened_column();
  const real screen = c.open_screen_offset(c.inlets.at(0)), delta_c = c.contact_distance(), R = 1e-3;
  ASSERT_NEAR(screen, c.open_screen_offset(c.outlets.at(0)), 1e-15);
  // the screen lies past the band of the momentum loads (5 h = 13 d0 = 2.6 mm here)
  EXPECT_NEAR(screen, kLoadBandReach * c.h(), 1e-15);
  Solver s = make_solver(c);
  const real m0 = fluid_mass(s.particles());
  std::optional<Failure> f;
  real lowest = 1e300, highest = -1e300;  // the heavy disc's bottom, the light one's top
  while (!f && s.time() < c.t_end) {
    f = s.step();
    lowest = std::min(lowest, s.groups().at(2).pos.y - R);
    highest = std::max(highest, s.groups().at(3).pos.y + R);
  }
  ASSERT_FALSE(f.has_value()) << f->what;
  // each disc came to its screen and rests on it within the contact distance, never crossing it
  // by more than the spring's overlap (0.1 d0 at the derived stiffness)
  const real bottom = s.groups().at(2).pos.y - R, top = s.groups().at(3).pos.y + R;
  EXPECT_GT(lowest, screen - 0.15 * c.d0);
  EXPECT_LT(highest, 12e-3 - screen + 0.15 * c.d0);
  EXPECT_LT(bottom, screen + delta_c) << "the heavy disc never reached the inlet's screen";
  EXPECT_GT(top, 12e-3 - screen - delta_c) << "the light disc never reached the outlet's screen";
  EXPECT_LT(std::fabs(s.groups().at(2).vel.y), 2e-3);
  EXPECT_LT(std::fabs(s.groups().at(3).vel.y), 2e-3);
  // the screens let the fluid through: a row entered at the inlet and fluid left at the outlet,
  // the fluid mass changing by exactly the net fluxes
  const auto& flux = s.open_flux();
  EXPECT_GT(flux.at(0).created, 0);
  EXPECT_GT(flux.at(1).mass - flux.at(1).backflow_mass, 0);
  EXPECT_LT(std::fabs(fluid_mass(s.particles()) - m0 - (flux[0].mass - flux[0].backflow_mass) +
                      (flux[1].mass - flux[1].backflow_mass)),
            1e-12 * m0);
}

/// A neutrally buoyant disc (D = 2 mm = 10 d0, its surface 0.3 mm before the outlet's screen) in
/// a viscous channel flow (mu = 0.1 Pa s) of 5 mm/s that carries it to the outlet; `outlet_extra`
/// adds keys to the [[outlet]] table.
namespace {
std::string pressed_disc_text(const std::string& outlet_extra = "") {
  std::string text = R"(
name = "pressed_disc"
[domain]
min = [0.0, 0.0]
max = [9.0e-3, 6.0e-3]
[resolution]
d0 = 2.0e-4
[fluid]
rho0 = 1000.0
mu = 0.1
c = 0.3
[time]
end = 0.2
[output]
interval = 0.01
[[wall]]
name = "lower"
from = [0.0, 0.0]
to = [9.0e-3, 0.0]
[[wall]]
name = "upper"
from = [9.0e-3, 6.0e-3]
to = [0.0, 6.0e-3]
[[inlet]]
name = "in"
from = [0.0, 6.0e-3]
to = [0.0, 0.0]
velocity = 5.0e-3
[[outlet]]
name = "out"
from = [9.0e-3, 0.0]
to = [9.0e-3, 6.0e-3]
[[body]]
name = "disc"
shape = "circle"
center = [5.1e-3, 3.0e-3]
radius = 1.0e-3
density = 1000.0
)";
  const std::string anchor = "to = [9.0e-3, 6.0e-3]\n[[body]]";
  text.replace(text.find(anchor), anchor.size(), "to = [9.0e-3, 6.0e-3]\n" + outlet_extra + "[[body]]");
  return text;
}
}  // namespace

TEST(OpenBoundary, AScreenHoldsABodyThatTheFlowPressesOntoIt) {
  // A neutrally buoyant disc (D = 2 mm = 10 d0) carried by a viscous channel flow (mu = 0.1 Pa s)
  // of 5 mm/s onto the outlet's screen. Its derived stiffness comes from its impact speed alone
  // (no weight), about 200 N/m^2, and the drag of the flow past the held disc is several times
  // k delta_max: without more it would press the disc about 0.5 d0 into the screen. The sustained
  // load stiffens the contact (Solver::hold_sustained_load) so that the spring holds it within
  // delta_max.
  const std::string text = pressed_disc_text();
  const Case c = load_case_text(text, "pressed_disc.toml");
  const real screen = 9e-3 - c.open_screen_offset(c.outlets.at(0)), R = 1e-3;
  const real delta_c = c.contact_distance(), delta_max = c.collision_max_overlap * c.d0;
  Solver s = make_solver(c);
  std::optional<Failure> f;
  real deepest = -1e300;  // largest spring compression delta_c - gap
  while (!f && s.time() < c.t_end) {
    f = s.step();
    deepest = std::max(deepest, delta_c - (screen - s.groups().at(2).pos.x - R));
  }
  ASSERT_FALSE(f.has_value()) << f->what;
  EXPECT_GT(deepest, 0) << "the disc never reached the screen";
  EXPECT_LT(deepest, 1.5 * delta_max) << "the screen let the disc in by " << deepest / c.d0 << " d0";
  EXPECT_GT(s.groups().at(2).contact_speed, 1e-3 * c.c) << "the held speed carries the load";
}

TEST(OpenBoundary, AnOutletThatRemovesBodiesTakesOutADiscCarriedToItAndFillsItsPlace) {
  // The pressed disc, with an outlet that removes bodies: the disc is taken out when its surface
  // reaches the screen's line, fluid of its area fills its place, the flow goes on, and the fluid
  // mass changes by exactly the fluxes and the fill.
  const Case c = load_case_text(pressed_disc_text("bodies = \"removed\"\n"), "removed_disc.toml");
  const real screen = 9e-3 - c.open_screen_offset(c.outlets.at(0)), R = 1e-3;
  Solver s = make_solver(c);
  const real m0 = fluid_mass(s.particles());
  const std::size_t nb0 = s.particles().n_boundary, disc_particles = s.groups().at(2).count;
  std::optional<Failure> f;
  real right = 0;     // the disc's right edge in the last step before its removal
  real rho_near = 0;  // the mean density of the fluid within 2 h of its surface then
  std::size_t fill = 0;
  while (!f && s.time() < 0.07) {
    f = s.step();
    if (!s.groups().at(2).removed) {
      right = s.groups().at(2).pos.x + R;
      real sum = 0, count = 0;
      for (std::size_t i = s.particles().n_boundary; i < s.particle_count(); ++i)
        if (s.particles().kind[i] == Kind::Fluid &&
            norm(s.particles().x[i] - s.groups().at(2).pos) < R + 2 * c.h()) {
          sum += s.particles().rho[i];
          count += 1;
        }
      rho_near = sum / count;
    }
    for (const Solver::BodyRemoval& r : s.removed_in_last_step()) {
      EXPECT_EQ(r.group, 2u);
      EXPECT_EQ(r.zone, 1u);
      fill = r.fill_particles;
      // the fill carries the fluid of the disc's area at the density of the fluid round it (the
      // channel's pressure compresses it by about 1 % at c = 0.3 m/s)
      EXPECT_NEAR(r.fill_mass, rho_near * M_PI * R * R, 2e-3 * rho_near * M_PI * R * R);
    }
  }
  ASSERT_FALSE(f.has_value()) << f->what;
  const RigidGroup& g = s.groups().at(2);
  ASSERT_TRUE(g.removed) << "the disc was not removed; its right edge at " << right << ", the screen at "
                         << screen;
  EXPECT_EQ(g.removed_at, 1);
  EXPECT_GT(g.removed_time, 0.03);
  EXPECT_LT(g.removed_time, 0.069);
  // removed in the step in which its surface reached the line, not before
  EXPECT_LT(right, screen);
  EXPECT_GT(right, screen - 0.1 * c.d0);
  EXPECT_EQ(g.count, 0u);
  EXPECT_EQ(s.particles().n_boundary, nb0 - disc_particles);
  // the points of the lattice at least d0/2 inside the disc (radius 4.5 d0: about 64)
  EXPECT_GE(fill, 50u);
  EXPECT_LE(fill, 80u);
  for (std::size_t i = 0; i < s.particles().n_boundary; ++i) EXPECT_NE(s.particles().group[i], 2) << i;
  // the flow closes over its place: no jet from the fill (the inflow's peak is 7.5 mm/s)
  real vmax = 0;
  for (std::size_t i = s.particles().n_boundary; i < s.particle_count(); ++i)
    if (s.particles().kind[i] == Kind::Fluid) vmax = std::max(vmax, norm(s.particles().v[i]));
  EXPECT_LT(vmax, 1.2e-2);
  const auto& fl = s.open_flux();
  EXPECT_EQ(fl.at(1).bodies_removed, 1);
  EXPECT_LT(std::fabs(fluid_mass(s.particles()) - m0 - (fl[0].mass - fl[0].backflow_mass) +
                      (fl[1].mass - fl[1].backflow_mass) - fl[1].body_fill_mass),
            1e-12 * m0);

  // A checkpoint of this state carries the removal, and a removal that does not fit is refused.
  const std::vector<OutputMark> marks;
  const Checkpoint k = decode_checkpoint(
      encode_checkpoint(CheckpointView{"name = \"x\"", 1, s.time(), s.step_count(), s.counters(), marks,
                                       s.particles(), s.groups(), s.open_flux(), s.load_band_state()}),
      "x.bin");
  ASSERT_TRUE(k.groups.at(2).removed);
  EXPECT_EQ(k.groups[2].removed_time, g.removed_time);
  EXPECT_EQ(k.open_flux.at(1).body_fill_mass, fl[1].body_fill_mass);
  EXPECT_NO_THROW(check_checkpoint_fits_case(k, c, "x.bin"));
  const auto refused = [&](const Checkpoint& bad, const char* why) {
    EXPECT_THROW(decode_checkpoint(encode_checkpoint(bad), "x.bin"), io::IoError) << why;
  };
  Checkpoint bad = k;
  bad.groups[2].removed_at = 7;
  refused(bad, "removed at an open boundary the checkpoint has no flux of");
  bad = k;
  bad.groups[2].removed = false;
  refused(bad, "an outlet index on a body that is not removed");
  bad = k;
  bad.groups[0].removed = true;
  bad.groups[0].removed_at = 1;
  refused(bad, "a wall removed");
  bad = k;
  bad.open_flux[1].body_fill_mass = -1;
  refused(bad, "negative fill");
  bad = k;
  bad.groups[2].removed_at = 0;
  EXPECT_THROW(check_checkpoint_fits_case(bad, c, "x.bin"), io::IoError) << "removed at the inlet";
  const Case holds = load_case_text(pressed_disc_text(), "pressed_disc.toml");
  EXPECT_THROW(check_checkpoint_fits_case(k, holds, "x.bin"), io::IoError)
      << "removed at an outlet that holds bodies";
}

TEST(OpenBoundary, ARunResumedAfterABodyWasRemovedIsBitwiseIdentical) {
  // The checkpoint holds the removed body (its flag, time and outlet) and the boundary block
  // without its particles; the resumed run repeats the whole one exactly. bodies.csv ends the
  // disc's rows at its removal, and summary.json lists it.
  const fs::path dir = cli_test::fresh_dir("removed_resume");
  const fs::path file = dir / "removed_disc.toml";
  std::ofstream(file) << pressed_disc_text("bodies = \"removed\"\n");
  const std::vector<std::string> common{"--quiet",   "--no-plots",
                                        "--threads", "1",
                                        "--set",     "output.interval=0.005",
                                        "--set",     "output.snapshot_interval=0.02"};
  const ResumeRuns r = whole_half_resumed(file, dir, common, "0.075", "0.065");  // removal at about 0.063 s
  ASSERT_EQ(r.whole.code, 0) << r.whole.output;
  ASSERT_EQ(r.half.code, 0) << r.half.output;
  {  // the removal lies before the end of the half, so the resume starts from a checkpoint holding it
    const std::string log = cli_test::read_text(dir / "whole" / "log.txt");
    const auto at = log.find("was removed");
    ASSERT_NE(at, std::string::npos) << log;
    const auto t = log.rfind("t = ", at);
    ASSERT_NE(t, std::string::npos);
    EXPECT_LT(std::stod(log.substr(t + 4, 20)), 0.065) << log.substr(t, at - t);
  }
  ASSERT_EQ(r.resumed.code, 0) << r.resumed.output;
  EXPECT_GE(expect_same_outputs(dir, {"open_boundaries.csv", "bodies.csv", "walls.csv"}), 3u);
  // bodies.csv: the disc's last row is the last output before its removal
  const io::CsvTable bodies = io::read_csv(dir / "whole" / "bodies.csv");
  ASSERT_FALSE(bodies.rows.empty());
  const double last = bodies.rows.back()[bodies.column_index("time")];
  EXPECT_GT(last, 0.03);
  EXPECT_LT(last, 0.065);
  const std::string summary = cli_test::read_text(dir / "whole" / "summary.json");
  EXPECT_NE(summary.find("\"bodies_removed\": [\n    {"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"outlet\": \"out\""), std::string::npos) << summary;
  EXPECT_NE(cli_test::read_text(dir / "whole" / "log.txt")
                .find("body 'disc' reached the screen of outlet 'out' and was removed"),
            std::string::npos);
}
