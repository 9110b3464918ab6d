// [[inlet]] and [[outlet]] at load (docs/method.md, "Open boundaries"): the
// keys and their values in Case, and the cross checks of open_checks.cpp, each error naming the
// file, the line and the key.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <string>

#include "case_bodies_fixtures.hpp"

using namespace particula;
using namespace case_bodies_test;

namespace {

/// kBase (d0 = 1e-4 m, c = 0.5 m/s) cut to a channel `length` m long and 0.006 m high: walls
/// along the bottom and the top, an inlet on the left edge (fluid on its left: +x) and an
/// outlet on the right edge.
std::string channel(const std::string& length = "0.02") {
  const std::string base = with(kBase, "max = [0.02, 0.06]", fmt::format("max = [{}, 0.006]", length));
  return base + fmt::format(R"(
[[wall]]
name = "bottom"
from = [0.0, 0.0]
to = [{0}, 0.0]

[[wall]]
name = "top"
from = [{0}, 0.006]
to = [0.0, 0.006]

[[inlet]]
name = "in"
from = [0.0, 0.006]
to = [0.0, 0.0]
velocity = 0.01

[[outlet]]
name = "out"
from = [{0}, 0.0]
to = [{0}, 0.006]
)",
                            length);
}

const std::string kChannel = channel();

/// kChannel with the inlet's velocity line replaced by `lines` (e.g. a table profile).
std::string inlet_with(const std::string& lines) { return with(kChannel, "velocity = 0.01", lines); }

}  // namespace

TEST(CaseOpen, ChannelLoads) {
  const Case c = load(kChannel);
  ASSERT_EQ(c.inlets.size(), 1u);
  ASSERT_EQ(c.outlets.size(), 1u);
  const OpenSpec &in = c.inlets[0], &out = c.outlets[0];
  EXPECT_EQ(in.name, "in");
  EXPECT_EQ(in.kind, OpenKind::Inlet);
  EXPECT_EQ(in.from.x, 0.0);
  EXPECT_EQ(in.from.y, 0.006);
  EXPECT_EQ(in.profile, InletProfile::Uniform);
  EXPECT_EQ(in.velocity, 0.01);
  EXPECT_EQ(in.ramp_time, 0.0);
  EXPECT_EQ(in.layers, 0);
  EXPECT_EQ(c.open_layers(in), 4);  // ceil(2.6) + 1
  EXPECT_NEAR(in.inward_normal().x, 1, 1e-15);
  EXPECT_NEAR(in.inward_normal().y, 0, 1e-15);
  EXPECT_NEAR(in.width(), 0.006, 1e-15);
  EXPECT_EQ(out.name, "out");
  EXPECT_EQ(out.kind, OpenKind::Outlet);
  EXPECT_EQ(out.pressure, 0.0);
  EXPECT_EQ(c.open_layers(out), 4);
  EXPECT_NEAR(out.inward_normal().x, -1, 1e-15);
  EXPECT_NEAR(out.inward_normal().y, 0, 1e-15);
  const std::vector<OpenSpec> all = c.open_boundaries();
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].name, "in");
  EXPECT_EQ(all[1].name, "out");
}

TEST(CaseOpen, DefaultsOptionsAndRoundTrip) {
  std::string text = with(kChannel, "name = \"in\"\n", "");
  text = with(text, "name = \"out\"\n", "pressure = -50.0\nlayers = 6\n");
  text =
      with(text, "velocity = 0.01", "velocity = 0.01\nprofile = \"parabolic\"\nramp_time = 0.2\nlayers = 2");
  const Case c = load(text);
  EXPECT_EQ(c.inlets[0].name, "inlet0");
  EXPECT_EQ(c.outlets[0].name, "outlet0");
  EXPECT_EQ(c.inlets[0].profile, InletProfile::Parabolic);
  EXPECT_EQ(c.inlets[0].ramp_time, 0.2);
  EXPECT_EQ(c.open_layers(c.inlets[0]), 2);
  EXPECT_EQ(c.outlets[0].pressure, -50.0);
  EXPECT_EQ(c.open_layers(c.outlets[0]), 6);
  // The resolved case writes every key back and loads as the same case, kinds included.
  const std::string resolved = resolved_case_toml(c);
  EXPECT_NE(resolved.find("[[inlet]]\nname = \"inlet0\"\n"), std::string::npos) << resolved;
  EXPECT_NE(resolved.find("[[outlet]]\nname = \"outlet0\"\n"), std::string::npos) << resolved;
  const Case d = load_case_text(resolved, "run/case.toml");
  EXPECT_EQ(resolved_case_toml(d), resolved);
  EXPECT_EQ(d.inlets[0].kind, OpenKind::Inlet);
  EXPECT_EQ(d.outlets[0].kind, OpenKind::Outlet);
}

TEST(CaseOpen, Overrides) {
  const Case c =
      load(kChannel, {"inlet.0.velocity=0.02", "outlet.0.pressure=5", "inlet.0.profile=parabolic"});
  EXPECT_EQ(c.inlets[0].velocity, 0.02);
  EXPECT_EQ(c.inlets[0].profile, InletProfile::Parabolic);
  EXPECT_EQ(c.outlets[0].pressure, 5.0);
  expect_override_error(kChannel, {"inlet.0.layers=1"}, "inlet[0].layers", "at least 2 rows");
}

TEST(CaseOpen, TableProfileParses) {
  const Case c =
      load(inlet_with("profile = \"table\"\ntable = [\n  [0.0, 0.0],\n  [0.003, 0.02],\n  [0.006, 0.0],\n]"));
  const OpenSpec& in = c.inlets[0];
  EXPECT_EQ(in.profile, InletProfile::Table);
  ASSERT_EQ(in.table.size(), 3u);
  EXPECT_EQ(in.table[1].x, 0.003);
  EXPECT_EQ(in.table[1].y, 0.02);
}

TEST(CaseOpen, KeysByProfile) {
  expect_error(with(kChannel, "velocity = 0.01\n", ""), "inlet[0].velocity", "[[inlet]]",
               "missing required key for profile 'uniform'");
  expect_error(inlet_with("profile = \"table\""), "inlet[0].table", "[[inlet]]",
               "missing required key for profile 'table'");
  expect_error(inlet_with("velocity = 0.01\nprofile = \"table\"\ntable = [[0, 0.01], [0.006, 0.01]]"),
               "inlet[0].velocity", "velocity = 0.01", "not used by profile 'table'");
  expect_error(inlet_with("velocity = 0.01\ntable = [[0, 0.01], [0.006, 0.01]]"), "inlet[0].table",
               "table =", "not used by profile 'uniform'");
  expect_error(inlet_with("velocity = 0.0"), "inlet[0].velocity", "velocity = 0.0", "out of range");
  expect_error(inlet_with("velocity = 0.01\nprofile = \"cosine\""), "inlet[0].profile",
               "profile =", "parabolic");
  expect_error(inlet_with("velocity = 0.01\nramp_time = -1.0"), "inlet[0].ramp_time", "ramp_time",
               "out of range");
}

TEST(CaseOpen, MisspelledKeysAreUnknown) {
  expect_error(with(kChannel, "velocity = 0.01", "velocty = 0.01"), "inlet[0].velocty", "velocty",
               "unknown key (did you mean 'inlet[0].velocity'?)");
  expect_error(with(kChannel, "name = \"out\"", "name = \"out\"\npresure = 10.0"), "outlet[0].presure",
               "presure", "unknown key (did you mean 'outlet[0].pressure'?)");
  expect_error(with(kChannel, "name = \"out\"", "name = \"out\"\nvelocity = 0.01"), "outlet[0].velocity",
               "velocity = 0.01\nfrom = [0.02", "unknown key");
}

TEST(CaseOpen, AnOutletHoldsBodiesUnlessItRemovesThem) {
  EXPECT_EQ(load_case_text(kChannel, kFile).outlets.at(0).bodies, OutletBodies::Held);
  const std::string removes = with(kChannel, "name = \"out\"", "name = \"out\"\nbodies = \"removed\"");
  EXPECT_EQ(load_case_text(removes, kFile).outlets.at(0).bodies, OutletBodies::Removed);
  expect_error(with(kChannel, "name = \"out\"", "name = \"out\"\nbodies = \"gone\""), "outlet[0].bodies",
               "bodies = \"gone\"", "removed");
  // an inlet always holds bodies back: the key is not one of its keys
  expect_error(inlet_with("velocity = 0.01\nbodies = \"removed\""), "inlet[0].bodies",
               "bodies =", "unknown key");
}

TEST(CaseOpen, NamesUniqueAmongInletsAndOutlets) {
  expect_error(with(kChannel, "name = \"out\"", "name = \"in\""), "outlet[0].name",
               "name = \"in\"\nfrom = [0.02", "duplicate outlet name \"in\" (already used by inlet[0].name)");
  const std::string two =
      kChannel + "\n[[inlet]]\nname = \"in\"\nfrom = [0.0, 0.006]\nto = [0.0, 0.0]\nvelocity = 0.02\n";
  expect_error(two, "inlet[1].name", "name = \"in\"\nfrom = [0.0, 0.006]\nto = [0.0, 0.0]\nvelocity = 0.02",
               "duplicate inlet name");
}

TEST(CaseOpen, LayersZeroOrTwoToTwenty) {
  expect_error(inlet_with("velocity = 0.01\nlayers = 1"), "inlet[0].layers", "layers = 1",
               "needs at least 2 rows of particles; give 0 (the default: ceil(h / d0) + 1 = 4 rows here");
  expect_error(inlet_with("velocity = 0.01\nlayers = 21"), "inlet[0].layers", "layers = 21", "out of range");
  EXPECT_EQ(load(inlet_with("velocity = 0.01\nlayers = 20")).inlets[0].layers, 20);
}

// a. On one edge of the domain, not periodic, the fluid inside.
TEST(CaseOpen, SegmentOnADomainEdge) {
  const std::string inside = with(kChannel, "from = [0.0, 0.006]\nto = [0.0, 0.0]\nvelocity",
                                  "from = [0.001, 0.006]\nto = [0.001, 0.0]\nvelocity");
  expect_error(inside, "inlet[0].from", "from = [0.001, 0.006]", "does not lie on an edge of the domain");
  const std::string beyond = with(kChannel, "from = [0.0, 0.006]\nto = [0.0, 0.0]\nvelocity",
                                  "from = [0.0, 0.007]\nto = [0.0, 0.0]\nvelocity");
  expect_error(beyond, "inlet[0].from", "from = [0.0, 0.007]", "outside the domain");
  const std::string periodic =
      with(kChannel, "max = [0.02, 0.006]", "max = [0.02, 0.006]\nperiodic = [true, false]");
  expect_error(periodic, "inlet[0].from", "from = [0.0, 0.006]\nto = [0.0, 0.0]\nvelocity",
               "the domain is periodic along x");
  const std::string reversed = with(kChannel, "from = [0.0, 0.006]\nto = [0.0, 0.0]\nvelocity",
                                    "from = [0.0, 0.0]\nto = [0.0, 0.006]\nvelocity");
  expect_error(reversed, "inlet[0].from", "from = [0.0, 0.0]\nto = [0.0, 0.006]",
               "list it the other way round");
  const std::string outlet_reversed =
      with(kChannel, "from = [0.02, 0.0]\nto = [0.02, 0.006]", "from = [0.02, 0.006]\nto = [0.02, 0.0]");
  expect_error(outlet_reversed, "outlet[0].from", "from = [0.02, 0.006]\nto = [0.02, 0.0]",
               "list it the other way round");
}

// b. At least 4 d0 wide.
TEST(CaseOpen, AtLeastFourD0Wide) {
  const std::string narrow = with(kChannel, "from = [0.0, 0.006]\nto = [0.0, 0.0]\nvelocity",
                                  "from = [0.0, 0.006]\nto = [0.0, 0.0057]\nvelocity");
  expect_error(narrow, "inlet[0].to", "to = [0.0, 0.0057]", "less than 4 d0");
}

// c. Each end a domain corner or a wall end.
TEST(CaseOpen, EndsAtCornersOrWallEnds) {
  const std::string short_inlet = with(kChannel, "from = [0.0, 0.006]\nto = [0.0, 0.0]\nvelocity",
                                       "from = [0.0, 0.006]\nto = [0.0, 0.001]\nvelocity");
  expect_error(short_inlet, "inlet[0].to", "to = [0.0, 0.001]",
               "ends at [0.0, 0.001], which is neither a corner");
  // A wall chain ending there closes the region with it.
  const Case c = load(short_inlet + "\n[[wall]]\nname = \"foot\"\nfrom = [0.0, 0.001]\nto = [0.0, 0.0]\n");
  EXPECT_NEAR(c.inlets[0].width(), 0.005, 1e-15);
}

// d. No wall along it; no two open boundaries overlapping.
TEST(CaseOpen, NoWallAlongItAndNoOverlap) {
  expect_error(kChannel + "\n[[wall]]\nname = \"left\"\nfrom = [0.0, 0.003]\nto = [0.0, 0.0]\n",
               "inlet[0].from", "from = [0.0, 0.006]\nto = [0.0, 0.0]\nvelocity",
               "wall 'left' (wall[2]) runs along inlet 'in' (inlet[0]) for 0.003 m");
  const std::string twice =
      kChannel + "\n[[inlet]]\nname = \"in2\"\nfrom = [0.0, 0.006]\nto = [0.0, 0.0]\nvelocity = 0.02\n";
  expect_error(twice, "inlet[1].from", "from = [0.0, 0.006]\nto = [0.0, 0.0]\nvelocity = 0.02",
               "inlet 'in2' (inlet[1]) overlaps inlet 'in' (inlet[0]) for 0.006 m");
}

// e. No sliding or turning wall ends on it: a small triangle turning about a pivot that keeps it
// in the domain, with a corner on the inlet.
TEST(CaseOpen, NoMovingWallEndsOnIt) {
  std::string triangle;
  for (const auto& [from, to] :
       {std::pair{"[0.0, 0.003]", "[0.001, 0.0035]"}, std::pair{"[0.001, 0.0035]", "[0.001, 0.0025]"},
        std::pair{"[0.001, 0.0025]", "[0.0, 0.003]"}})
    triangle +=
        fmt::format("\n[[wall]]\nfrom = {}\nto = {}\nomega = 1.0\npivot = [0.002, 0.003]\n", from, to);
  expect_error(kChannel + triangle, "wall[2].omega", "omega = 1.0",
               "turns (omega 1 rad/s) and has an end at [0.0, 0.003] on inlet 'in' (inlet[0])");
}

// f. Table rows.
TEST(CaseOpen, TableRows) {
  const std::string table = "profile = \"table\"\ntable = [\n  [0.0, 0.01],\n  [0.003, 0.02],\n  {},\n]";
  expect_error(inlet_with(fmt::format(fmt::runtime(table), "[0.002, 0.01]")), "inlet[0].table",
               "[0.002, 0.01]", "s must increase strictly");
  expect_error(inlet_with(fmt::format(fmt::runtime(table), "[0.003, 0.01]")), "inlet[0].table",
               "[0.003, 0.01]", "s must increase strictly");
  expect_error(inlet_with(fmt::format(fmt::runtime(table), "[0.0071, 0.0]")), "inlet[0].table",
               "[0.0071, 0.0]", "lies outside the segment [0, 0.006] m");
  expect_error(inlet_with(fmt::format(fmt::runtime(table), "[0.006, -0.001]")), "inlet[0].table",
               "[0.006, -0.001]", "u = -0.001 m/s is negative");
  expect_error(inlet_with("profile = \"table\"\ntable = [[0.0, 0.0], [0.006, 0.0]]"), "inlet[0].table",
               "table =", "no fluid would enter");
  expect_error(inlet_with("profile = \"table\"\ntable = [[0.0, 0.01]]"), "inlet[0].table",
               "table =", "too few points");
  // s = width up to round-off is on the segment.
  EXPECT_NO_THROW(load(inlet_with(fmt::format(fmt::runtime(table), "[0.006000000000001, 0.0]"))));
}

// g. An inlet needs an outlet; an outlet alone is allowed.
TEST(CaseOpen, InletNeedsAnOutlet) {
  const std::string no_outlet = kChannel.substr(0, kChannel.find("[[outlet]]"));
  expect_error(no_outlet, "inlet[0]", "[[inlet]]", "fluid that enters would pile up");
  const std::string outlet_only = with(kChannel, "[[inlet]]\nname = \"in\"", "[[wall]]\nname = \"left\"");
  const Case c = load(with(outlet_only, "velocity = 0.01\n", ""));
  EXPECT_TRUE(c.inlets.empty());
  EXPECT_EQ(c.outlets.size(), 1u);
}

// h. Inlet and outlet at least L_b + 2 h apart.
TEST(CaseOpen, InletAndOutletFarEnoughApart) {
  // 0.0008 m apart, below L_b + 2 h = 4e-4 + 5.2e-4 m.
  expect_error(channel("0.0008"), "outlet[0].from", "from = [0.0008, 0.0]",
               "comes 0.0008 m from inlet 'in' (inlet[0]), closer than L_b + 2 h = 0.00092 m");
  EXPECT_NO_THROW(load(channel("0.001")));
}

// i. Every body starts beyond the boundary's screen (Case::open_screen_offset) by delta_c.
TEST(CaseOpen, BodiesClearOfOpenBoundaries) {
  const std::string body =
      "\n[[body]]\nname = \"post\"\nshape = \"circle\"\ncenter = [{}, 0.003]\nradius = 0.001\n"
      "motion = \"fixed\"\n";
  // Gap 0.0005 m, below the screen (5 h = 1.3e-3 m) + delta_c = 0.5e-4 m.
  expect_error(kChannel + fmt::format(fmt::runtime(body), "0.0015"), "body[0].center", "center = [0.0015",
               "comes 0.0005 m from inlet 'in' (inlet[0])");
  expect_error(kChannel + fmt::format(fmt::runtime(body), "0.0015"), "body[0].center", "center = [0.0015",
               "the boundary's screen, which holds bodies back, lies 0.0013 m inside the line");
  expect_error(kChannel + fmt::format(fmt::runtime(body), "0.0185"), "body[0].center", "center = [0.0185",
               "from outlet 'out' (outlet[0])");
  EXPECT_NO_THROW(load(kChannel + fmt::format(fmt::runtime(body), "0.01")));
  // With the momentum loads (the default) the screen lies 5 h = 1.3e-3 m in, so that the band of
  // the body's loads stays clear of the buffer; with the paper's loads at L_b + h = 6.6e-4 m.
  const std::string near = kChannel + fmt::format(fmt::runtime(body), "0.0021");  // gap 1.1e-3 m
  expect_error(near, "body[0].center", "center = [0.0021", "the band of the momentum loads");
  EXPECT_NO_THROW(load(near + "\n[numerics]\nforce = \"paper\"\n"));
}

// j. Only with single-layer walls.
TEST(CaseOpen, SingleLayerWallsOnly) {
  expect_error(kChannel + "\n[numerics]\nboundary = \"dummy\"\n", "numerics.boundary", "boundary = \"dummy\"",
               "does not support open boundaries");
}

// k. The inflow speed counts in the Mach check and the estimated time step.
TEST(CaseOpen, InflowSpeedInTheMachCheck) {
  expect_error(inlet_with("velocity = 0.6"), "fluid.c", "c = 0.5", "that inlet[0].velocity sets");
  expect_error(inlet_with("profile = \"table\"\ntable = [[0.0, 0.0], [0.003, 0.7], [0.006, 0.0]]"), "fluid.c",
               "c = 0.5", "0.7 m/s that inlet[0].table sets");
  EXPECT_LT(estimated_dt(load(inlet_with("velocity = 0.2"))), estimated_dt(load(kChannel)));
}
