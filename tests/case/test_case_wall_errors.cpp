// [[wall]] cross checks at load: orientation on the domain edges, periodic edges,
// overlapping walls, chains (gaps, joints, head to tail), walls against bodies. Each error
// names the file, the line and the key; every shipped case still loads.
#include <gtest/gtest.h>

#include <filesystem>
#include <fmt/format.h>

#include "case_bodies_fixtures.hpp"

using namespace particula;
using namespace case_bodies_test;

namespace {

/// kBase (0.02 x 0.06 m, d0 = 1e-4 m) closed by four walls listed counter-clockwise.
const std::string kWalls = R"(
[[wall]]
name = "bottom"
from = [0.0, 0.0]
to = [0.02, 0.0]

[[wall]]
name = "right"
from = [0.02, 0.0]
to = [0.02, 0.06]

[[wall]]
name = "top"
from = [0.02, 0.06]
to = [0.0, 0.06]

[[wall]]
name = "left"
from = [0.0, 0.06]
to = [0.0, 0.0]
)";

const std::string kBox = kBase + kWalls;

/// kBox with one more [[wall]] table.
std::string box_with_wall(const std::string& name, const std::string& from, const std::string& to) {
  return kBox + "\n[[wall]]\nname = \"" + name + "\"\nfrom = " + from + "\nto = " + to + "\n";
}

/// A shelf in the middle of kBox: a closed plate 1 mm thick listed clockwise (the fluid outside),
/// whose top side is the baffle (wall[4], fluid above it: its left side).
const std::string kBaffle = box_with_wall("baffle", "[0.005, 0.03]", "[0.015, 0.03]") +
                            "\n[[wall]]\nname = \"shelf_right\"\nfrom = [0.015, 0.03]\nto = [0.015, 0.029]\n"
                            "\n[[wall]]\nname = \"shelf_under\"\nfrom = [0.015, 0.029]\nto = [0.005, 0.029]\n"
                            "\n[[wall]]\nname = \"shelf_left\"\nfrom = [0.005, 0.029]\nto = [0.005, 0.03]\n";

/// kBox made periodic along x, with walls only along the bottom and top.
std::string periodic_x_channel() {
  std::string text = with(kBase, "max = [0.02, 0.06]", "max = [0.02, 0.06]\nperiodic = [true, false]");
  return text + R"(
[[wall]]
name = "lower"
from = [0.0, 0.0]
to = [0.02, 0.0]

[[wall]]
name = "upper"
from = [0.02, 0.06]
to = [0.0, 0.06]
)";
}

}  // namespace

TEST(CaseWallErrors, ShippedCasesAndFixturesLoad) {
  const std::filesystem::path source = PARTICULA_SOURCE_DIR;
  int n = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(source / "cases")) {
    if (e.path().extension() != ".toml") continue;
    EXPECT_NO_THROW(load_case(e.path())) << e.path();
    ++n;
  }
  EXPECT_GE(n, 30);
  EXPECT_NO_THROW(load_case(source / "tests" / "data" / "bodies.toml"));
  EXPECT_NO_THROW(load(kBox));
  EXPECT_NO_THROW(load(kBaffle));
  EXPECT_NO_THROW(load(periodic_x_channel()));
}

// ---------------------------------------------------------------------------------------------
// Orientation on the domain edges.

TEST(CaseWallErrors, ClockwiseWallOnADomainEdge) {
  expect_error(
      with(kBox, "from = [0.0, 0.0]\nto = [0.02, 0.0]", "from = [0.02, 0.0]\nto = [0.0, 0.0]"),
      "wall[0].from", "from = [0.02, 0.0]",
      "the fluid would be on the right of wall 'bottom' (wall[0]) (it lies on the domain edge y = 0 m; "
      "the fluid lies on the left walking from `from` to `to`): swap from and to");
  expect_error(
      with(kBox, "from = [0.02, 0.0]\nto = [0.02, 0.06]", "from = [0.02, 0.06]\nto = [0.02, 0.0]"),
      "wall[1].from", "from = [0.02, 0.06]\nto = [0.02, 0.0]",
      "the fluid would be on the right of wall 'right' (wall[1]) (it lies on the domain edge x = 0.02 m");
  expect_error(with(kBox, "from = [0.02, 0.06]\nto = [0.0, 0.06]", "from = [0.0, 0.06]\nto = [0.02, 0.06]"),
               "wall[2].from", "from = [0.0, 0.06]\nto = [0.02, 0.06]",
               "wall 'top' (wall[2]) (it lies on the domain edge y = 0.06 m");
  expect_error(with(kBox, "from = [0.0, 0.06]\nto = [0.0, 0.0]", "from = [0.0, 0.0]\nto = [0.0, 0.06]"),
               "wall[3].from", "from = [0.0, 0.0]\nto = [0.0, 0.06]",
               "wall 'left' (wall[3]) (it lies on the domain edge x = 0 m");
  // A wall on part of an edge counts too.
  expect_error(kBase + "\n[[wall]]\nname = \"ledge\"\nfrom = [0.0, 0.02]\nto = [0.0, 0.03]\n", "wall[0].from",
               "from = [0.0, 0.02]", "the fluid would be on the right of wall 'ledge' (wall[0])");
}

TEST(CaseWallErrors, WallOnAPeriodicBoundary) {
  const std::string box = with(kBox, "max = [0.02, 0.06]", "max = [0.02, 0.06]\nperiodic = [true, false]");
  expect_error(
      box, "wall[1].from", "from = [0.02, 0.0]\nto = [0.02, 0.06]",
      "wall 'right' (wall[1]) lies on the domain edge x = 0.02 m, but the domain is periodic along x: "
      "the fluid wraps around that edge and would be on both sides of the wall");
  // Even a correctly oriented wall along a periodic edge (the check runs before orientation).
  const std::string channel = with(periodic_x_channel(), "max = [0.02, 0.06]\nperiodic = [true, false]",
                                   "max = [0.02, 0.06]\nperiodic = [false, true]");
  expect_error(channel, "wall[0].from", "from = [0.0, 0.0]",
               "wall 'lower' (wall[0]) lies on the domain edge y = 0 m, but the domain is periodic along y");
}

// ---------------------------------------------------------------------------------------------
// Walls on one line.

TEST(CaseWallErrors, DuplicatedWall) {
  expect_error(
      box_with_wall("again", "[0, 0]", "[0.02, 0]"), "wall[4].from", "from = [0, 0]",
      "wall 'again' (wall[4]) duplicates wall 'bottom' (wall[0]): they share 0.02 m of the same line");
  expect_error(kBaffle + "\n[[wall]]\nname = \"back\"\nfrom = [0.015, 0.03]\nto = [0.005, 0.03]\n",
               "wall[8].from", "from = [0.015, 0.03]\nto = [0.005, 0.03]",
               "wall 'back' (wall[8]) duplicates (reversed) wall 'baffle' (wall[4])");
}

TEST(CaseWallErrors, CollinearWallsOverlapping) {
  expect_error(
      box_with_wall("patch", "[0.005, 0.0]", "[0.01, 0.0]"), "wall[4].from", "from = [0.005, 0.0]",
      "wall 'patch' (wall[4]) overlaps wall 'bottom' (wall[0]): they share 0.005 m of the same line");
  // Collinear pieces that meet at an end point are a split wall, which is fine.
  EXPECT_NO_THROW(load(with(kBox, "to = [0.02, 0.0]\n",
                            "to = [0.012, 0.0]\n\n[[wall]]\nname = \"bottom2\"\nfrom = [0.012, 0.0]\n"
                            "to = [0.02, 0.0]\n")));
}

TEST(CaseWallErrors, WallShorterThanHalfD0) {
  // A 1e-15 m wall would give NaN at step 1.
  expect_error(box_with_wall("tiny", "[0.01, 0.03]", "[0.01, 0.030000000000001]"), "wall[4].to",
               "to = [0.01, 0.030000000000001]",
               "wall 'tiny' is 1e-15 m long, shorter than d0/2 = 5e-05 m");
  // The right wall in two pieces, the lower one d0/2 long.
  EXPECT_NO_THROW(load(with(kBox, "from = [0.02, 0.0]\nto = [0.02, 0.06]",
                            "from = [0.02, 0.0]\nto = [0.02, 0.00005]\n\n[[wall]]\nname = \"short\"\n"
                            "from = [0.02, 0.00005]\nto = [0.02, 0.06]")));
}

TEST(CaseWallErrors, SlidingWallOnlyAlongAPeriodicAxis) {
  // A lid sliding in a closed box runs into the next wall after d0/|v| (the time step collapsed).
  expect_error(with(kBox, "to = [0.0, 0.06]\n", "to = [0.0, 0.06]\nvelocity = [-0.01, 0.0]\n"),
               "wall[2].velocity", "velocity = [-0.01",
               "wall 'top' (wall[2]) slides (velocity [-0.01, 0.0]), but it does not run along a periodic axis "
               "of the domain: a sliding wall moves along itself, so its particles would run into the next wall "
               "or out of the domain after d0/|v| = 0.01 s");
  // Along the periodic axis of a channel it wraps around: Couette flow.
  const std::string channel =
      with(periodic_x_channel(), "to = [0.0, 0.06]\n", "to = [0.0, 0.06]\nvelocity = [-0.01, 0.0]\n");
  EXPECT_NO_THROW(load(channel));
  // ... but not joined to another wall: the joint would come apart.
  expect_error(box_with_wall("baffle", "[0.0, 0.03]", "[0.02, 0.03]") +
                   "velocity = [0.01, 0.0]\n",
               "wall[4].velocity", "velocity = [0.01", "but it does not run along a periodic axis");
  // The upper wall in two pieces, the second sliding.
  const std::string joined = with(channel, "from = [0.02, 0.06]\nto = [0.0, 0.06]",
                                  "from = [0.02, 0.06]\nto = [0.01, 0.06]\n\n[[wall]]\nname = \"upper2\"\n"
                                  "from = [0.01, 0.06]\nto = [0.0, 0.06]");
  expect_error(joined, "wall[2].velocity", "velocity = [-0.01",
               "wall 'upper2' (wall[2]) slides (velocity [-0.01, 0.0]) but starts where wall 'upper' (wall[1]) "
               "ends: the joint would come apart");
}

// ---------------------------------------------------------------------------------------------
// Chains.

TEST(CaseWallErrors, ChainNotClosed) {
  expect_error(
      with(kBox, "to = [0.0, 0.0]", "to = [0.0, 0.00003]"), "wall[3].to", "to = [0.0, 0.00003]",
      "wall 'left' (wall[3]) ends at [0.0, 3e-05], a gap of 3e-05 m from where wall 'bottom' (wall[0]) "
      "starts ([0.0, 0.0]): end points closer than d0/2 = 5e-05 m must be the same point");
  // Across the periodic boundary: the lower wall nearly spans the period.
  expect_error(
      with(periodic_x_channel(), "to = [0.02, 0.0]", "to = [0.01997, 0.0]"), "wall[0].to",
      "to = [0.01997, 0.0]",
      "wall 'lower' (wall[0]) ends at [0.01997, 0.0], a gap of 3e-05 m from where wall 'lower' (wall[0]) "
      "starts");
  // d0/2 apart is an opening, not a gap.
  EXPECT_NO_THROW(load(with(kBox, "to = [0.0, 0.0]", "to = [0.0, 0.00005]")));
}

TEST(CaseWallErrors, MoreThanTwoWallsAtAPoint) {
  expect_error(
      box_with_wall("diagonal", "[0.0, 0.0]", "[0.01, 0.01]"), "wall[4].from",
      "from = [0.0, 0.0]\nto = [0.01, 0.01]",
      "3 wall ends meet at [0.0, 0.0]: wall 'bottom' (wall[0]), wall 'left' (wall[3]), wall 'diagonal' "
      "(wall[4]); at most two walls may share an end point");
}

TEST(CaseWallErrors, JoinedWallsWithOppositeOrientations) {
  // Two inner walls that both end at [0.01, 0.02].
  const std::string vee = kBox +
                          "\n[[wall]]\nname = \"a\"\nfrom = [0.005, 0.02]\nto = [0.01, 0.02]\n"
                          "\n[[wall]]\nname = \"b\"\nfrom = [0.01, 0.03]\nto = [0.010, 0.020]\n";
  expect_error(vee, "wall[5].to", "to = [0.010, 0.020]",
               "wall 'b' (wall[5]) and wall 'a' (wall[4]) both end at [0.01, 0.02]: they have opposite "
               "orientations");
  EXPECT_NE(error_of(vee).message().find("swap from and to of wall 'b' (wall[5])"), std::string::npos);
  // Head to tail they are a chain, but one that ends inside the domain: it encloses no region.
  expect_error(with(vee, "from = [0.01, 0.03]\nto = [0.010, 0.020]", "from = [0.010, 0.020]\nto = [0.01, 0.03]"),
               "wall[4].from", "from = [0.005, 0.02]",
               "wall 'a' (wall[4]) starts at [0.005, 0.02], inside the domain and joined to no other wall: the region "
               "the walls enclose is not closed");
  // A step on the floor listed against the floor: the wall on the domain edge is the one that is right.
  const std::string step = kBase +
                           "\n[[wall]]\nname = \"riser\"\nfrom = [0.01, 0.005]\nto = [0.01, 0.0]\n"
                           "\n[[wall]]\nname = \"floor\"\nfrom = [0.0, 0.0]\nto = [0.010, 0.0]\n";
  expect_error(step, "wall[1].to", "to = [0.010, 0.0]",
               "wall 'floor' (wall[1]) and wall 'riser' (wall[0]) both end at [0.01, 0.0]");
  EXPECT_NE(error_of(step).message().find("swap from and to of wall 'riser' (wall[0])"), std::string::npos);
  // Two that both start at a point.
  expect_error(kBase +
                   "\n[[wall]]\nfrom = [0.005, 0.02]\nto = [0.01, 0.02]\n"
                   "\n[[wall]]\nfrom = [0.005, 0.02]\nto = [0.005, 0.03]\n",
               "wall[1].from", "from = [0.005, 0.02]\nto = [0.005, 0.03]",
               "wall 'wall1' (wall[1]) and wall 'wall0' (wall[0]) both start at [0.005, 0.02]");
}

// ---------------------------------------------------------------------------------------------
// Walls against bodies.

TEST(CaseWallErrors, WallCutsThroughABody) {
  expect_error(kBaffle +
                   "\n[[body]]\nshape = \"circle\"\ncenter = [0.01, 0.031]\nradius = 0.00125\n"
                   "density = 1000\n",
               "body[0].center", "center = [0.01, 0.031]",
               "wall 'baffle' (wall[4]) cuts through body 'body0' (circle) at t = 0: move the body clear of "
               "the wall");
  // A wall entirely inside a polygon.
  expect_error(kBaffle +
                   "\n[[body]]\nshape = \"polygon\"\nmotion = \"fixed\"\n"
                   "vertices = [[0.004, 0.029], [0.016, 0.029], [0.016, 0.031], [0.004, 0.031]]\n",
               "body[0].vertices", "vertices = [[0.004",
               "wall 'baffle' (wall[4]) lies inside body 'body0' (polygon) at t = 0: a wall may cross a fixed "
               "body, not hide in it");
}

TEST(CaseWallErrors, BodyWithinHalfD0OfAWall) {
  const std::string disc = kBox +
                           "\n[[body]]\nname = \"disc\"\nshape = \"circle\"\ncenter = [0.01, 0.00129]\n"
                           "radius = 0.00125\ndensity = 1000\n";
  expect_error(
      disc, "body[0].center", "center = [0.01, 0.00129]",
      "wall 'bottom' (wall[0]) passes 4e-05 m from body 'disc' (circle) at t = 0, closer than d0/2 = "
      "5e-05 m (the wall particles there would be left out): move the body at least d0/2 from the wall");
  EXPECT_NO_THROW(load(with(disc, "center = [0.01, 0.00129]", "center = [0.01, 0.0013]")));
  // Sampled shapes: an ellipse and a polygon near a wall.
  expect_error(kBox +
                   "\n[[body]]\nshape = \"ellipse\"\ncenter = [0.01, 0.00104]\nsemi_axes = [0.002, 0.001]\n"
                   "density = 1000\n",
               "body[0].center", "center = [0.01, 0.00104]",
               "wall 'bottom' (wall[0]) passes 4e-05 m from body 'body0' (ellipse)");
  expect_error(kBox +
                   "\n[[body]]\nshape = \"polygon\"\ndensity = 1000\n"
                   "vertices = [[0.019, 0.01], [0.01997, 0.011], [0.019, 0.012], [0.018, 0.011]]\n",
               "body[0].vertices", "vertices = [[0.019",
               "wall 'right' (wall[1]) passes 3e-05 m from body 'body0' (polygon)");
}

TEST(CaseWallErrors, BodyNearAWallAcrossThePeriodicBoundary) {
  // A closed plate (clockwise: the fluid outside) whose left side is at x = 0.001; the disc near
  // x = 0.02 reaches across the periodic boundary x = 0.02 to within 4e-5 m of it.
  const std::string text = periodic_x_channel() +
                           "\n[[wall]]\nname = \"plate_left\"\nfrom = [0.001, 0.029]\nto = [0.001, 0.031]\n"
                           "\n[[wall]]\nname = \"plate_under\"\nfrom = [0.005, 0.029]\nto = [0.001, 0.029]\n"
                           "\n[[wall]]\nname = \"plate_right\"\nfrom = [0.005, 0.031]\nto = [0.005, 0.029]\n"
                           "\n[[wall]]\nname = \"plate_top\"\nfrom = [0.001, 0.031]\nto = [0.005, 0.031]\n"
                           "\n[[body]]\nshape = \"circle\"\ncenter = [0.01971, 0.03]\nradius = 0.00125\n"
                           "density = 1000\n";
  expect_error(
      text, "body[0].center", "center = [0.01971, 0.03]",
      "wall 'plate_left' (wall[2]) passes 4e-05 m from body 'body0' (circle) at t = 0 across the periodic "
      "boundary");
  EXPECT_NO_THROW(load(with(text, "center = [0.01971, 0.03]", "center = [0.0197, 0.03]")));
}

TEST(CaseWallErrors, OnlyAFixedBodyStandsOnAWall) {
  // The half-disc obstacle of paper 7.5 on the left wall loads when fixed (as cases/ellipse_obstacle.toml).
  const std::string obstacle = kBox +
                               "\n[[body]]\nname = \"obstacle\"\nshape = \"half_disc\"\n"
                               "center = [0.0, 0.04]\nradius = 0.005\nmotion = \"fixed\"\n";
  EXPECT_NO_THROW(load(obstacle));
  expect_error(with(obstacle, "motion = \"fixed\"", "density = 1000"), "body[0].center",
               "center = [0.0, 0.04]",
               "wall 'left' (wall[3]) touches body 'obstacle' (half_disc) at t = 0, closer than d0/2");
  // Standing with a gap under it is not standing.
  expect_error(with(obstacle, "center = [0.0, 0.04]", "center = [0.00003, 0.04]"), "body[0].center",
               "center = [0.00003, 0.04]", "wall 'left' (wall[3]) passes 3e-05 m from body 'obstacle'");
  // On an inner wall: a half-disc or polygon on its fluid side stands on it, on the other side
  // it does not (the fluid would be inside it).
  const std::string dome = kBaffle +
                           "\n[[body]]\nshape = \"half_disc\"\ncenter = [0.01, 0.03]\nradius = 0.004\n"
                           "angle = 1.5707963267948966\nmotion = \"fixed\"\n";
  EXPECT_NO_THROW(load(dome));
  expect_error(with(dome, "angle = 1.5707963267948966", "angle = -1.5707963267948966"), "body[0].center",
               "center = [0.01, 0.03]", "wall 'baffle' (wall[4]) touches body 'body0' (half_disc)");
  const std::string block = kBaffle +
                            "\n[[body]]\nshape = \"polygon\"\nmotion = \"fixed\"\n"
                            "vertices = [[0.008, 0.03], [0.012, 0.03], [0.012, 0.032], [0.008, 0.032]]\n";
  EXPECT_NO_THROW(load(block));
  expect_error(with(block, "[0.012, 0.032], [0.008, 0.032]", "[0.012, 0.028], [0.008, 0.028]"),
               "body[0].vertices", "vertices = [[0.008",
               "wall 'baffle' (wall[4]) touches body 'body0' (polygon)");
  // A fixed block standing on the baffle and reaching through the shelf (an L shape) crosses it
  // at right angles; sunk into the shelf at a shallow angle it is refused (a thin wedge of fluid).
  EXPECT_NO_THROW(load(kBaffle +
                       "\n[[body]]\nshape = \"polygon\"\nmotion = \"fixed\"\n"
                       "vertices = [[0.008, 0.03], [0.0095, 0.03], [0.0095, 0.028], [0.0115, 0.028], "
                       "[0.0115, 0.032], [0.008, 0.032]]\n"));
  expect_error(kBox + "\n[[body]]\nshape = \"circle\"\ncenter = [0.01, 0.0018]\nradius = 0.002\nmotion = \"fixed\"\n",
               "body[0].center", "center = [0.01, 0.0018]",
               "body 'body0' (circle) meets wall 'bottom' (wall[0]) at 25.5 degrees at [0.00912822, 0] at t = 0, "
               "less than 30");
  EXPECT_NO_THROW(load(kBox + "\n[[body]]\nshape = \"circle\"\ncenter = [0.01, 0.001]\nradius = 0.002\n"
                              "motion = \"fixed\"\n"));
  // past the domain's edge through the wall along it
  EXPECT_NO_THROW(load(kBox + "\n[[body]]\nshape = \"circle\"\ncenter = [0.01, -0.001]\nradius = 0.002\n"
                              "motion = \"fixed\"\n"));
}

// ---------------------------------------------------------------------------------------------
// Arcs, turning walls and the enclosed region.

namespace {

/// kBase's domain holding one circular container (an arc turning counter-clockwise).
std::string container(const std::string& extra = "") {
  return kBase +
         "\n[[wall]]\nname = \"drum\"\nshape = \"arc\"\ncenter = [0.01, 0.03]\nradius = 0.008\n"
         "start_angle = 0.0\nend_angle = 6.283185307179586\n" +
         extra;
}

}  // namespace

TEST(CaseWallErrors, ArcsAreCheckedAtLoad) {
  EXPECT_NO_THROW(load(container()));
  EXPECT_NO_THROW(load(container("omega = 3.0\npivot = [0.01, 0.03]\n")));
  expect_error(with(container(), "end_angle = 6.283185307179586", "end_angle = 7.0"), "wall[0].end_angle",
               "end_angle = 7.0", "wall 'drum' (wall[0]) turns through 7 rad, more than a full circle");
  expect_error(with(container(), "end_angle = 6.283185307179586", "end_angle = 0.0"), "wall[0].end_angle",
               "end_angle = 0.0", "arc has zero length");
  expect_error(with(container(), "radius = 0.008", "radius = 0.0002"), "wall[0].radius", "radius = 0.0002",
               "below the smoothing length h");
  expect_error(with(container(), "radius = 0.008", "radius = 0.0105"), "wall[0].center", "center = [0.01, 0.03]",
               "wall 'drum' (wall[0]) leaves the domain");
  expect_error(container("velocity = [0.01, 0.0]\n"), "wall[0].velocity", "velocity = [0.01",
               "is an arc and cannot slide");
  // Segment keys on an arc are refused like a body's keys of another shape.
  expect_error(container("from = [0.0, 0.0]\n"), "wall[0].from", "from = [0.0, 0.0]", "");
  // The same circle twice.
  expect_error(container() + "\n[[wall]]\nname = \"again\"\nshape = \"arc\"\ncenter = [0.01, 0.03]\n"
                              "radius = 0.008\nstart_angle = 3.0\nend_angle = 4.0\n",
               "wall[1].shape", "shape = \"arc\"\ncenter = [0.01, 0.03]\nradius = 0.008\nstart_angle = 3.0",
               "wall 'again' (wall[1]) runs along wall 'drum' (wall[0])");
}

TEST(CaseWallErrors, TurningWallsStayInTheDomainAndTurnWithTheirChain) {
  expect_error(container("omega = 3.0\n"), "wall[0].pivot", "[[wall]]",
               "wall 'drum' (wall[0]) turns about [0.0, 0.0] and reaches");
  // A square drum turning about its centre, one of its sides left out of the turning.
  std::string drum = kBase;
  const char* corners[5] = {"[0.005, 0.025]", "[0.015, 0.025]", "[0.015, 0.035]", "[0.005, 0.035]", "[0.005, 0.025]"};
  for (int k = 0; k < 4; ++k)
    drum += fmt::format("\n[[wall]]\nname = \"side{}\"\nfrom = {}\nto = {}\n{}", k, corners[k], corners[k + 1],
                        k == 1 ? "" : "omega = 1.0\npivot = [0.01, 0.03]\n");
  expect_error(drum, "wall[0].omega", "omega = 1.0",
               "wall 'side0' (wall[0]) turns (omega 1 rad/s about [0.01, 0.03]) but shares an end point with wall "
               "'side1' (wall[1]), which does not turn with it");
  EXPECT_NO_THROW(load(with(drum, "to = [0.015, 0.035]\n", "to = [0.015, 0.035]\nomega = 1.0\npivot = [0.01, 0.03]\n")));
}

TEST(CaseWallErrors, TheWallsMustEncloseTheFluid) {
  // A wall ending on another wall's side: split it there.
  expect_error(box_with_wall("shelf", "[0.0, 0.03]", "[0.01, 0.03]"), "wall[4].from", "from = [0.0, 0.03]",
               "wall 'shelf' (wall[4]) starts at [0.0, 0.03], on the side of wall 'left' (wall[3]): split wall "
               "'left' (wall[3]) there into two walls");
  // An open arc inside the domain.
  expect_error(with(container(), "end_angle = 6.283185307179586", "end_angle = 3.0"), "wall[0].end_angle",
               "end_angle = 3.0", "inside the domain and joined to no other wall: the region the walls enclose is "
               "not closed");
}

TEST(CaseWallErrors, SpinUpNeedsOneTurningCircularContainer) {
  const std::string spin = container("omega = 3.0\npivot = [0.01, 0.03]\n") + "\n[validation]\nexact = \"spin_up\"\n";
  EXPECT_NO_THROW(load(spin));
  expect_error(with(spin, "omega = 3.0\n", ""), "validation.exact", "exact = \"spin_up\"",
               "validation.exact = \"spin_up\" needs the wall to turn");
  expect_error(with(spin, "end_angle = 6.283185307179586", "end_angle = -6.283185307179586"), "validation.exact",
               "exact = \"spin_up\"", "a full circle turning counter-clockwise");
  expect_error(spin + "\n[[body]]\nshape = \"circle\"\ncenter = [0.01, 0.03]\nradius = 0.002\nmotion = \"fixed\"\n",
               "validation.exact", "exact = \"spin_up\"", "needs no bodies");
}

// ---------------------------------------------------------------------------------------------
// Closed chains whose fluid sides contradict each other.

namespace {

/// A full circle of radius r round (0.01, 0.03): counter-clockwise (fluid inside) or clockwise.
std::string circle(const std::string& name, double r, bool fluid_inside) {
  return fmt::format("\n[[wall]]\ncenter = [0.01, 0.03]\nname = \"{}\"\nshape = \"arc\"\nradius = {}\n"
                     "start_angle = {}\nend_angle = {}\n",
                     name, r, fluid_inside ? "0.0" : "6.283185307179586", fluid_inside ? "6.283185307179586" : "0.0");
}

}  // namespace

TEST(CaseWallErrors, NestedChainsTurnOppositeWays) {
  // A box (fluid inside) round an obstacle (fluid outside), and a pocket of fluid in a thick ring.
  EXPECT_NO_THROW(load(kBox + circle("obstacle", 0.008, false)));
  EXPECT_NO_THROW(load(kBox + circle("ring_out", 0.008, false) + circle("ring_in", 0.004, true)));
  // A box round a circular container: between them fluid by the box, solid by the circle.
  const std::string two_containers = kBox + circle("drum", 0.008, true);
  expect_error(two_containers, "wall[4].center", "center = [0.01, 0.03]\nname = \"drum\"",
               "the closed chain of wall 'drum' (wall[4]) (fluid inside: counter-clockwise) lies inside the closed "
               "chain of wall 'bottom' (wall[0]), wall 'right' (wall[1]), wall 'top' (wall[2]), wall 'left' "
               "(wall[3]) (fluid inside: counter-clockwise): the region between them would be fluid by the outer "
               "chain and solid by the inner one");
  EXPECT_EQ(error_of(two_containers).file(), kFile);
  // An obstacle inside an obstacle: between them solid by the outer, fluid by the inner.
  expect_error(kBox + circle("outer", 0.008, false) + circle("inner", 0.004, false), "wall[5].center",
               "center = [0.01, 0.03]\nname = \"inner\"", "would be solid by the outer chain and fluid by the inner one");
  // The nearest enclosing chain decides: a container in the ring's pocket is inside two chains.
  expect_error(kBox + circle("ring_out", 0.008, false) + circle("ring_in", 0.006, true) + circle("cup", 0.003, true),
               "wall[6].center", "center = [0.01, 0.03]\nname = \"cup\"", "lies inside the closed chain of wall 'ring_in' (wall[5])");
}

TEST(CaseWallErrors, OutermostChainsAgreeWithTheRegionRoundThem) {
  // In a channel (walls closing through the periodic sides) an obstacle, not a container.
  EXPECT_NO_THROW(load(periodic_x_channel() + circle("obstacle", 0.008, false)));
  expect_error(periodic_x_channel() + circle("drum", 0.008, true), "wall[2].center", "center = [0.01, 0.03]\nname = \"drum\"",
               "stands in the region that the walls ending on the domain's edge or closing through a periodic side "
               "make fluid");
  // Without other walls: two drums, or two obstacles, side by side, but not one of each.
  const std::string drum = with(circle("left", 0.004, true), "center = [0.01, 0.03]", "center = [0.01, 0.015]");
  const std::string obstacle = with(circle("right", 0.004, false), "center = [0.01, 0.03]", "center = [0.01, 0.045]");
  EXPECT_NO_THROW(load(kBase + drum + with(drum, "0.015", "0.045")));
  expect_error(kBase + drum + obstacle, "wall[1].center", "center = [0.01, 0.045]\nname = \"right\"",
               "stand side by side, inside no other chain: the region round them would be solid by the first and "
               "fluid by the second");
}
