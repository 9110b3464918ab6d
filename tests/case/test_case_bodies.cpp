// [[body]] and [collision]: every shape loads with its values, and the resolved case reads back
// identically. The errors and --set overrides are in test_case_body_errors.cpp.
#include <gtest/gtest.h>

#include "case_bodies_fixtures.hpp"

using namespace particula;
using namespace case_bodies_test;

TEST(CaseBodies, EveryShapeLoadsWithItsValues) {
  const Case c = load(kCase);
  EXPECT_EQ(c.collision_stiffness, 1.5e6);
  EXPECT_EQ(c.collision_range, 3e-4);
  ASSERT_EQ(c.bodies.size(), 4u);

  const BodySpec& disc = c.bodies[0];
  EXPECT_EQ(disc.name, "disc");
  EXPECT_EQ(disc.shape, BodyShape::Circle);
  EXPECT_EQ(disc.center.x, 0.01);
  EXPECT_EQ(disc.center.y, 0.01);
  EXPECT_EQ(disc.radius, 0.00125);
  EXPECT_EQ(disc.density, 1250.0);
  EXPECT_EQ(disc.motion, BodyMotion::Free);
  EXPECT_EQ(disc.velocity.x, 0.001);
  EXPECT_EQ(disc.velocity.y, -0.002);
  EXPECT_EQ(disc.omega, 0.5);
  EXPECT_EQ(disc.angle, 0.0);
  EXPECT_TRUE(disc.vertices.empty());
  EXPECT_TRUE(disc.schedule.empty());

  const BodySpec& ellipse = c.bodies[1];
  EXPECT_EQ(ellipse.name, "body1");  // default name: body<index>
  EXPECT_EQ(ellipse.shape, BodyShape::Ellipse);
  EXPECT_EQ(ellipse.semi_axes.x, 0.002);
  EXPECT_EQ(ellipse.semi_axes.y, 0.001);
  EXPECT_EQ(ellipse.angle, 0.25);
  EXPECT_EQ(ellipse.radius, 0.0);  // not used by an ellipse
  EXPECT_EQ(ellipse.velocity.x, 0.0);
  EXPECT_EQ(ellipse.omega, 0.0);

  const BodySpec& paddle = c.bodies[2];
  EXPECT_EQ(paddle.shape, BodyShape::Polygon);
  EXPECT_EQ(paddle.motion, BodyMotion::Prescribed);
  EXPECT_EQ(paddle.density, 0.0);  // not needed by a prescribed body
  ASSERT_EQ(paddle.vertices.size(), 4u);
  EXPECT_EQ(paddle.vertices[1].x, 0.018);
  EXPECT_EQ(paddle.vertices[3].y, 0.024);
  ASSERT_EQ(paddle.schedule.size(), 3u);
  EXPECT_EQ(paddle.schedule[0].t, 0.0);  // integers read as reals
  EXPECT_EQ(paddle.schedule[1].t, 0.5);
  EXPECT_EQ(paddle.schedule[1].velocity.x, 0.001);
  EXPECT_EQ(paddle.schedule[1].omega, 2.0);
  EXPECT_EQ(paddle.schedule[2].velocity.y, -0.001);

  const BodySpec& obstacle = c.bodies[3];
  EXPECT_EQ(obstacle.shape, BodyShape::HalfDisc);
  EXPECT_EQ(obstacle.motion, BodyMotion::Fixed);
  EXPECT_EQ(obstacle.center.x, 0.0);  // its flat side on the left wall
  EXPECT_EQ(obstacle.radius, 0.005);
}

TEST(CaseBodies, NoBodiesAndCollisionDefaults) {
  const Case c = load(kBase);
  EXPECT_TRUE(c.bodies.empty());
  EXPECT_EQ(c.collision_stiffness, 0.0);
  EXPECT_EQ(c.collision_range, 0.0);
}

TEST(CaseBodies, PrescribedWithoutScheduleAndNegativeStartTime) {
  const Case c =
      load(one_body("shape = \"circle\"\ncenter = [0.01, 0.03]\nradius = 0.002\nmotion = "
                    "\"prescribed\"\nvelocity = [0, 1e-3]\n"));
  EXPECT_EQ(c.bodies[0].velocity.y, 1e-3);
  EXPECT_TRUE(c.bodies[0].schedule.empty());
  EXPECT_NO_THROW(
      load(one_body("shape = \"circle\"\ncenter = [0.01, 0.03]\nradius = 0.002\n"
                    "motion = \"prescribed\"\nschedule = [[-1, 0, 0, 0], [1e-9, 0.001, 0.001, 1]]\n")));
}

TEST(CaseBodies, HalfDiscMaySitOnAnyWallWithItsFlatSide) {
  // Left wall (faces +x at angle 0), bottom (angle pi/2), right (angle pi), top (angle -pi/2).
  for (const char* placement :
       {"center = [0, 0.03]\nangle = 0", "center = [0.01, 0]\nangle = 1.5707963267948966",
        "center = [0.02, 0.03]\nangle = 3.141592653589793",
        "center = [0.01, 0.06]\nangle = -1.5707963267948966"}) {
    SCOPED_TRACE(placement);
    EXPECT_NO_THROW(load(one_body(std::string("shape = \"half_disc\"\nradius = 0.005\nmotion = \"fixed\"\n") +
                                  placement + "\n")));
  }
}

TEST(CaseBodies, PeriodicAxesAreNotBounded) {
  // Across the periodic x boundary: the body may stick out of the box along x.
  const std::string text = with(kBase, "max = [0.02, 0.06]", "max = [0.02, 0.06]\nperiodic = [true, false]");
  EXPECT_NO_THROW(load(text + "\n[[body]]\nshape = \"circle\"\ncenter = [0.0005, 0.03]\nradius = 0.002\n"
                              "density = 1000\n"));
}

TEST(CaseBodies, DisjointShapesWhoseBoundingCirclesMeet) {
  // A circle in the missing half of a half-disc's full disc, an ellipse next to a square.
  EXPECT_NO_THROW(load(kBase + R"(
[[body]]
shape = "half_disc"
center = [0.01, 0.03]
radius = 0.005
motion = "fixed"

[[body]]
shape = "circle"
center = [0.0075, 0.03]
radius = 0.0015
density = 1000

[[body]]
shape = "ellipse"
center = [0.01, 0.045]
semi_axes = [0.004, 0.001]
density = 1000

[[body]]
shape = "polygon"
vertices = [[0.011, 0.0465], [0.013, 0.0465], [0.013, 0.0485], [0.011, 0.0485]]
density = 1000
)"));
  // Two circles that touch do not overlap (fixed: a free body may not start in contact).
  EXPECT_NO_THROW(
      load(kBase + "[[body]]\nshape = \"circle\"\ncenter = [0.005, 0.03]\nradius = 0.002\nmotion = \"fixed\"\n"
                   "[[body]]\nshape = \"circle\"\ncenter = [0.009, 0.03]\nradius = 0.002\nmotion = \"fixed\"\n"));
}

// ---------------------------------------------------------------------------------------------
// Keys of the shape and motion.

TEST(CaseBodies, PolygonEitherOrientationAndNonConvex) {
  // Clockwise, and an L shape (non-convex, 10 d0 wide arms).
  EXPECT_NO_THROW(
      load(one_body("shape = \"polygon\"\nmotion = \"fixed\"\n"
                    "vertices = [[0.01, 0.01], [0.01, 0.012], [0.012, 0.012], [0.012, 0.01]]\n")));
  EXPECT_NO_THROW(
      load(one_body("shape = \"polygon\"\nmotion = \"fixed\"\nvertices = [[0.005, 0.01], [0.01, 0.01], "
                    "[0.01, 0.011], [0.006, 0.011], [0.006, 0.02], [0.005, 0.02]]\n")));
}

// ---------------------------------------------------------------------------------------------
// Placement.

TEST(CaseBodyRoundTrip, ResolvedCaseReadsBackIdentically) {
  const Case a = load(kCase);
  const std::string text = resolved_case_toml(a);
  EXPECT_NE(text.find("\n[collision]\nmodel = \"spring_dashpot\"\nstiffness = 1500000.0\nrange = 0.0003\n"),
            std::string::npos)
      << text;
  // Only the keys of each body's shape and motion are written.
  EXPECT_NE(
      text.find(
          "[[body]]\nname = \"disc\"\nshape = \"circle\"\ncenter = [0.01, 0.01]\nradius = 0.00125\n"
          "angle = 0.0\ndensity = 1250.0\nmotion = \"free\"\nvelocity = [0.001, -0.002]\nomega = 0.5\n"),
      std::string::npos)
      << text;
  EXPECT_NE(text.find("vertices = [[0.014, 0.02], [0.018, 0.02], [0.018, 0.024], [0.014, 0.024]]\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("schedule = [[0.0, 0.0, 0.0, 0.0], [0.5, 0.001, 0.0, 2.0], [1.5, 0.0, -0.001, 0.0]]\n"),
            std::string::npos)
      << text;
  EXPECT_EQ(text.find("radius = 0.0\n"), std::string::npos) << text;
  EXPECT_EQ(text.find("semi_axes = [0.0, 0.0]"), std::string::npos) << text;
  expect_round_trip(a);
}

TEST(CaseBodyRoundTrip, AwkwardRealsAndLongLists) {
  // Reals that need 17 digits, -0.0, and lists long enough to be written one item per line.
  Case a = load(kCase);
  a.bodies[2].vertices = {{0.014, 0.02},
                          {0.30000000000000004 / 20, 0.02},
                          {0.018, 0.024},
                          {0.016, 0.0250000000000001},
                          {0.014, 0.024}};
  a.bodies[2].schedule.clear();
  for (int i = 0; i < 7; ++i)
    a.bodies[2].schedule.push_back({i / 3.0 - 0.0, {std::sqrt(2.0) * i / 1e5, -0.0}, 1.0 / (i + 1)});
  a.bodies[1].angle = -0.0;
  a.bodies[0].center = {0.1 / 9, 1.0 / 97};
  const std::string text = resolved_case_toml(a);
  EXPECT_NE(text.find("schedule = [\n  [0.0, 0.0, -0.0, 1.0],\n  [0.3333333333333333,"), std::string::npos)
      << text;
  EXPECT_NE(text.find("vertices = [\n  [0.014, 0.02],\n"), std::string::npos) << text;
  expect_round_trip(a);
  EXPECT_TRUE(std::signbit(load_case_text(text, "case.toml").bodies[1].angle));
}

TEST(CaseBodyRoundTrip, PrescribedWithoutScheduleWritesNoSchedule) {
  const Case a =
      load(one_body("shape = \"circle\"\ncenter = [0.01, 0.03]\nradius = 0.002\n"
                    "motion = \"prescribed\"\nvelocity = [0, 1e-3]\n"));
  const std::string text = resolved_case_toml(a);
  EXPECT_EQ(text.find("schedule"), std::string::npos) << text;
  expect_round_trip(a);
}

// ---------------------------------------------------------------------------------------------
// A case file on disk.

TEST(CaseBodies, ExampleFile) {
  const std::filesystem::path file =
      std::filesystem::path(PARTICULA_SOURCE_DIR) / "tests" / "data" / "bodies.toml";
  const Case c = load_case(file);
  ASSERT_EQ(c.bodies.size(), 4u);
  EXPECT_EQ(c.bodies[1].name, "obstacle");
  EXPECT_EQ(c.bodies[1].shape, BodyShape::HalfDisc);
  EXPECT_EQ(c.bodies[3].vertices.size(), 4u);
  EXPECT_EQ(c.bodies[3].schedule.size(), 3u);
  EXPECT_EQ(c.walls.size(), 4u);
  expect_round_trip(c);
  // Moved by an override, the cylinder overlaps the paddle: the error names the later body.
  try {
    load_case(file, {"body.2.center=[0.006, 0.013]"});
    FAIL() << "no error";
  } catch (const CaseError& e) {
    EXPECT_EQ(e.file(), file.string()) << e.what();
    EXPECT_EQ(e.line(), 74) << e.what();  // vertices = [
    EXPECT_EQ(e.key(), "body[3].vertices") << e.what();
    EXPECT_NE(e.message().find("body 'paddle' (polygon) overlaps body 'cylinder' (circle) (body[2])"),
              std::string::npos)
        << e.what();
  }
}
