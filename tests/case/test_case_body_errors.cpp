// [[body]] case-file errors and --set overrides of body keys: each error names the key and line.
#include <gtest/gtest.h>

#include "case_bodies_fixtures.hpp"

using namespace particula;
using namespace case_bodies_test;

TEST(CaseBodyErrors, KeyOfAnotherShape) {
  expect_error(with(kCase, "angle = 0.25", "angle = 0.25\nradius = 0.003"), "body[1].radius",
               "radius = 0.003", "not used by shape 'ellipse' (only by shape circle, half_disc)");
  expect_error(with(kCase, "vertices = [[", "center = [0.01, 0.02]\nvertices = [["), "body[2].center",
               "center = [0.01, 0.02]", "not used by shape 'polygon'");
  expect_error(with(kCase, "radius = 0.00125", "radius = 0.00125\nsemi_axes = [1, 1]"), "body[0].semi_axes",
               "semi_axes = [1, 1]", "not used by shape 'circle'");
  expect_error(with(kCase, "radius = 0.005", "radius = 0.005\nvertices = [[0, 0], [1, 0], [0, 1]]"),
               "body[3].vertices", "vertices = [[0, 0]", "not used by shape 'half_disc'");
}

TEST(CaseBodyErrors, MissingKeyOfTheShape) {
  expect_error(with(kCase, "radius = 0.00125\n", ""), "body[0].radius", "[[body]]",
               "missing required key for shape 'circle' (real, m)");
  const std::string no_axes = with(kCase, "semi_axes = [0.002, 0.001]\n", "");
  expect_error(no_axes, "body[1].semi_axes", "[[body]]\nshape = \"ellipse\"",
               "missing required key for shape 'ellipse' (vec2, m)");
  expect_error(with(kCase, "center = [0, 0.04]\n", ""), "body[3].center", "[[body]]\nname = \"obstacle\"",
               "missing required key for shape 'half_disc'");
  expect_error(with(kCase, "vertices = [[0.014, 0.02], [0.018, 0.02], [0.018, 0.024], [0.014, 0.024]]\n", ""),
               "body[2].vertices", "[[body]]\nname = \"paddle\"",
               "missing required key for shape 'polygon' (vec2 list, m)");
  expect_error(with(kCase, "shape = \"circle\"\n", ""), "body[0].shape", "[[body]]", "missing required key");
  expect_error(with(kCase, "shape = \"circle\"", "shape = \"square\""), "body[0].shape", "shape = \"square\"",
               "'square' is not a valid choice: expected one of circle, ellipse, polygon, half_disc");
}

TEST(CaseBodyErrors, ScheduleOnlyForPrescribedMotion) {
  expect_error(with(kCase, "omega = 0.5", "omega = 0.5\nschedule = [[0, 0, 0, 0], [1, 0, 0, 0]]"),
               "body[0].schedule", "schedule = [[0, 0",
               "not used by motion 'free' (only by motion prescribed)");
  expect_error(with(kCase, "motion = \"prescribed\"", "motion = \"fixed\""), "body[2].schedule",
               "schedule = [", "not used by motion 'fixed'");
}

TEST(CaseBodyErrors, FreeBodyNeedsADensity) {
  expect_error(with(kCase, "density = 1250\n", ""), "body[0].density", "[[body]]",
               "missing density: a free body");
  expect_error(with(kCase, "density = 1250", "density = 0"), "body[0].density", "density = 0",
               "a free body needs density > 0 kg/m^3 for its mass, got 0");
  expect_error(with(kCase, "density = 1250", "density = -1"), "body[0].density", "density = -1",
               "must be >= 0 kg/m^3");
}

TEST(CaseBodyErrors, FixedBodyDoesNotMove) {
  expect_error(with(kCase, "motion = \"fixed\"", "motion = \"fixed\"\nvelocity = [0, 1]"), "body[3].velocity",
               "velocity = [0, 1]", "a fixed body does not move");
  expect_error(with(kCase, "motion = \"fixed\"", "motion = \"fixed\"\nomega = 1"), "body[3].omega",
               "omega = 1", "a fixed body does not move");
}

TEST(CaseBodyErrors, DuplicateBodyName) {
  expect_error(with(kCase, "name = \"paddle\"", "name = \"disc\""), "body[2].name",
               "name = \"disc\"\nshape = \"polygon\"",
               "duplicate body name \"disc\" (already used by body[0].name)");
}

// ---------------------------------------------------------------------------------------------
// Values of the new types.

TEST(CaseBodyErrors, VerticesValues) {
  const std::string circle_free = "vertices = [[0.014, 0.02], [0.018, 0.02], [0.018, 0.024], [0.014, 0.024]]";
  expect_error(with(kCase, circle_free, "vertices = [[0.014, 0.02], [0.018, 0.02]]"), "body[2].vertices",
               "vertices = [[0.014", "too few points: expected an array of at least 3 points [x, y], got 2");
  expect_error(with(kCase, circle_free, "vertices = [0.014, 0.02]"), "body[2].vertices", "vertices = [0.014",
               "wrong type: expected an array of at least 3 points [x, y], got an array of 2 elements");
  expect_error(with(kCase, circle_free, "vertices = \"square\""), "body[2].vertices", "vertices = \"square\"",
               "got a string");
  // A bad point is reported on its own line.
  const std::string multi =
      with(kCase, circle_free, "vertices = [\n  [0.014, 0.02],\n  [0.018, 0.02, 0],\n  [0.018, 0.024],\n]");
  expect_error(multi, "body[2].vertices", "[0.018, 0.02, 0]",
               "point [1] must be [x, y] of two real numbers, got an array of 3 elements");
  expect_error(with(kCase, circle_free, "vertices = [[0.014, 0.02], [0.018, nan], [0.018, 0.024]]"),
               "body[2].vertices", "vertices = [[",
               "point [1] = [0.018, nan] is out of range: must be finite");
}

TEST(CaseBodyErrors, ScheduleValues) {
  const std::string rows = "schedule = [\n  [0, 0, 0, 0],\n  [0.5, 0.001, 0, 2],\n  [1.5, 0, -0.001, 0],\n]";
  expect_error(
      with(kCase, rows, "schedule = [[0, 0, 0, 0]]"), "body[2].schedule", "schedule = [[",
      "too few rows: expected an array of at least 2 rows [t, vx, vy, omega] of real numbers, got 1");
  expect_error(with(kCase, rows, "schedule = [\n  [0, 0, 0, 0],\n  [0.5, 0.001, 0],\n]"), "body[2].schedule",
               "[0.5, 0.001, 0]",
               "row [1] must be [t, vx, vy, omega] of four real numbers, got an array of 3");
  expect_error(with(kCase, rows, "schedule = [[0, 0, 0, 0], [1, 0, inf, 0]]"), "body[2].schedule",
               "schedule =", "out of range: must be finite");
  expect_error(with(kCase, rows, "schedule = [0, 0, 0, 0]"), "body[2].schedule", "schedule =", "wrong type");
}

TEST(CaseBodyErrors, ScheduleTimesIncreaseFromTheStart) {
  expect_error(
      with(kCase, "[0.5, 0.001, 0, 2]", "[0.5, 0.001, 0, 2],\n  [0.5, 0, 0, 0]"), "body[2].schedule",
      "[0.5, 0, 0, 0]",
      "schedule times must increase strictly: schedule[2] at t = 0.5 s does not come after schedule[1] at "
      "t = 0.5 s");
  expect_error(with(kCase, "[1.5, 0, -0.001, 0]", "[0.2, 0, -0.001, 0]"), "body[2].schedule",
               "[0.2, 0, -0.001, 0]", "must increase strictly");
  expect_error(with(kCase, "  [0, 0, 0, 0],", "  [0.1, 0, 0, 0],"), "body[2].schedule", "[0.1, 0, 0, 0]",
               "the first row must be at t <= 0");
}

TEST(CaseBodyErrors, SemiAxesMustBePositive) {
  expect_error(with(kCase, "semi_axes = [0.002, 0.001]", "semi_axes = [0.002, 0]"), "body[1].semi_axes",
               "semi_axes", "value [0.002, 0] is out of range: each component must be > 0 m");
  expect_error(with(kCase, "radius = 0.00125", "radius = 0"), "body[0].radius", "radius = 0",
               "must be > 0 m");
}

// ---------------------------------------------------------------------------------------------
// Polygons.

TEST(CaseBodyErrors, SelfIntersectingPolygon) {
  const std::string bow_tie = one_body(
      "shape = \"polygon\"\nmotion = \"fixed\"\nvertices = [\n  [0.01, 0.01],\n  [0.012, 0.012],\n"
      "  [0.012, 0.01],\n  [0.01, 0.012],\n]\n");
  expect_error(
      bow_tie, "body[0].vertices", "[0.012, 0.01],",
      "polygon intersects itself: edge vertices[0] -> vertices[1] ([0.01, 0.01] -> [0.012, 0.012]) meets "
      "edge vertices[2] -> vertices[3]");
  // An edge that folds back along the previous one.
  expect_error(one_body("shape = \"polygon\"\nmotion = \"fixed\"\n"
                        "vertices = [[0.01, 0.01], [0.015, 0.01], [0.012, 0.01], [0.012, 0.015]]\n"),
               "body[0].vertices", "vertices", "polygon intersects itself");
  // A vertex on a non-adjacent edge.
  expect_error(
      one_body("shape = \"polygon\"\nmotion = \"fixed\"\n"
               "vertices = [[0.01, 0.01], [0.014, 0.01], [0.014, 0.014], [0.012, 0.01], [0.01, 0.014]]\n"),
      "body[0].vertices", "vertices", "polygon intersects itself");
}

TEST(CaseBodyErrors, ZeroAreaPolygon) {
  expect_error(one_body("shape = \"polygon\"\nmotion = \"fixed\"\n"
                        "vertices = [[0.01, 0.01], [0.012, 0.01], [0.015, 0.01]]\n"),
               "body[0].vertices", "vertices", "polygon has zero area: all its vertices lie on one line");
  expect_error(one_body("shape = \"polygon\"\nmotion = \"fixed\"\n"
                        "vertices = [[0.01, 0.01], [0.015, 0.01], [0.015, 0.01], [0.015, 0.015]]\n"),
               "body[0].vertices", "vertices", "vertices[1] and vertices[2] are the same point");
}

TEST(CaseBodyErrors, BodyNameAtMost64Characters) {
  const std::string disc = one_body(
      "name = \"d\"\nshape = \"circle\"\ncenter = [0.01, 0.03]\nradius = 0.002\n"
      "density = 1000\n");
  EXPECT_NO_THROW(load(with(disc, "name = \"d\"", "name = \"" + std::string(64, 'd') + "\"")));
  expect_error(with(disc, "name = \"d\"", "name = \"" + std::string(65, 'd') + "\""), "body[0].name",
               "name = \"ddd", "(65 characters) is too long");
}

TEST(CaseBodyErrors, PolygonVerticesAtLeastHalfD0Apart) {
  // Two vertices 1e-8 m apart would make steps of 5e-11 s.
  const std::string close = one_body(
      "shape = \"polygon\"\nmotion = \"fixed\"\nvertices = [\n  [0.01, 0.01],\n  [0.012, 0.01],\n"
      "  [0.012, 0.012],\n  [0.01000001, 0.012],\n  [0.01, 0.012],\n]\n");
  expect_error(
      close, "body[0].vertices", "[0.01, 0.012],",
      "polygon vertices[3] [0.01000001, 0.012] and vertices[4] [0.01, 0.012] are 1e-08 m apart, closer "
      "than d0/2 = 5e-05 m");
  // Not neighbours along the outline: a notch whose two sides nearly meet.
  expect_error(
      one_body("shape = \"polygon\"\nmotion = \"fixed\"\nvertices = [[0.01, 0.01], [0.014, 0.01], "
               "[0.014, 0.014], [0.01202, 0.014], [0.0121, 0.011], [0.0119, 0.011], [0.01198, 0.014], "
               "[0.01, 0.014]]\n"),
      "body[0].vertices", "vertices",
      "polygon vertices[3] [0.01202, 0.014] and vertices[6] [0.01198, 0.014] are 4e-05 m apart");
  // Just over d0/2 apart is fine.
  EXPECT_NO_THROW(
      load(one_body("shape = \"polygon\"\nmotion = \"fixed\"\nvertices = [[0.01, 0.01], "
                    "[0.012, 0.01], [0.012, 0.012], [0.01006, 0.012], [0.01, 0.012]]\n")));
}

TEST(CaseBodyErrors, BodyOutsideTheDomain) {
  expect_error(with(kCase, "center = [0.01, 0.01]", "center = [0.0195, 0.01]"), "body[0].center",
               "center = [0.0195",
               "body 'disc' (circle) lies outside the domain: it reaches x = 0.02075 m, beyond the "
               "domain edge x = 0.02 m");
  // The ellipse is 0.002 long along x, but turned by 90 degrees it only reaches 0.001 along x.
  const std::string turned = with(with(kCase, "center = [0.01, 0.054]", "center = [0.0015, 0.03]"),
                                  "angle = 0.25", "angle = 1.5707963267948966");
  EXPECT_NO_THROW(load(turned));
  expect_error(with(turned, "angle = 1.5707963267948966", "angle = 0"), "body[1].center", "center = [0.0015",
               "lies outside the domain: it reaches x = -0.0005 m");
  expect_error(with(kCase, "vertices = [[0.014, 0.02]", "vertices = [[0.014, -0.001]"), "body[2].vertices",
               "vertices = [[0.014",
               "body 'paddle' (polygon) lies outside the domain: it reaches y = -0.001 m");
  // A fixed body may reach past an edge through a wall along it (the scene cuts it off there:
  // CaseWallErrors.OnlyAFixedBodyStandsOnAWall), a free one may not; wholly beyond the edge it
  // is refused.
  expect_error(with(kCase, "center = [0, 0.04]", "center = [-0.001, 0.04]"), "body[3].center",
               "center = [-0.001",
               "body 'obstacle' (half_disc) reaches past the domain edge x = 0 m, where no wall lies");
  expect_error(with(kCase, "center = [0.01, 0.01]", "center = [0.0195, 0.01]"), "body[0].center",
               "center = [0.0195", "(only a fixed body may reach past a domain edge)");
  expect_error(with(kCase, "center = [0, 0.04]", "center = [-0.006, 0.04]"), "body[3].center",
               "center = [-0.006",
               "body 'obstacle' (half_disc) lies wholly outside the domain: it spans x = -0.006 .. -0.001 m");
}

TEST(CaseBodyErrors, OnlyAHalfDiscMayTouchTheDomainEdge) {
  expect_error(
      with(kCase, "center = [0.01, 0.01]", "center = [0.01, 0.00125]"), "body[0].center",
      "center = [0.01, 0.00125]",
      "body 'disc' (circle) touches the domain edge y = 0 m: leave fluid between them (only a fixed body or "
      "a half_disc may sit on a domain edge)");
  EXPECT_NO_THROW(load(with(kCase, "center = [0.01, 0.01]", "center = [0.01, 0.0013]")));
}

TEST(CaseBodyErrors, OverlappingBodies) {
  // Two circles (exact test).
  expect_error(with(kCase, "center = [0.01, 0.01]", "center = [0.01, 0.052]"), "body[1].center",
               "center = [0.01, 0.054]",
               "body 'body1' (ellipse) overlaps body 'disc' (circle) (body[0]) at t = 0");
  const std::string circles = kBase +
                              "[[body]]\nshape = \"circle\"\ncenter = [0.005, 0.03]\nradius = 0.002\n"
                              "density = 1\n[[body]]\nshape = \"circle\"\ncenter = [0.0089, 0.03]\n"
                              "radius = 0.002\ndensity = 1\n";
  expect_error(circles, "body[1].center", "center = [0.0089", "overlaps body 'body0' (circle)");
  // Polygon with the half-disc obstacle.
  expect_error(with(kCase, "[[0.014, 0.02], [0.018, 0.02], [0.018, 0.024], [0.014, 0.024]]",
                    "[[0.004, 0.038], [0.008, 0.038], [0.008, 0.042], [0.004, 0.042]]"),
               "body[3].center", "center = [0, 0.04]",
               "body 'obstacle' (half_disc) overlaps body 'paddle' (polygon)");
  // A circle inside a polygon (no boundary crossing).
  expect_error(kBase +
                   "[[body]]\nshape = \"polygon\"\nmotion = \"fixed\"\n"
                   "vertices = [[0.002, 0.002], [0.018, 0.002], [0.018, 0.018], [0.002, 0.018]]\n"
                   "[[body]]\nshape = \"circle\"\ncenter = [0.01, 0.01]\nradius = 0.002\ndensity = 1\n",
               "body[1].center", "center = [0.01, 0.01]", "overlaps body 'body0' (polygon)");
  // The half-disc's round side reaches the circle.
  expect_error(
      kBase +
          "[[body]]\nshape = \"half_disc\"\ncenter = [0.01, 0.03]\nradius = 0.005\nmotion = \"fixed\"\n"
          "[[body]]\nshape = \"circle\"\ncenter = [0.0155, 0.03]\nradius = 0.001\ndensity = 1\n",
      "body[1].center", "center = [0.0155", "overlaps body 'body0' (half_disc)");
}

TEST(CaseBodyErrors, OverlapAcrossThePeriodicBoundary) {
  const std::string periodic =
      with(kBase, "max = [0.02, 0.06]", "max = [0.02, 0.06]\nperiodic = [true, false]");
  expect_error(periodic +
                   "[[body]]\nshape = \"ellipse\"\ncenter = [0.0005, 0.03]\nsemi_axes = [0.002, 0.001]\n"
                   "density = 1\n[[body]]\nshape = \"circle\"\ncenter = [0.018, 0.03]\nradius = 0.001\n"
                   "density = 1\n",
               "body[1].center", "center = [0.018",
               "overlaps body 'body0' (ellipse) (body[0]) at t = 0 across the "
               "periodic boundary");
  expect_error(
      periodic + "[[body]]\nshape = \"circle\"\ncenter = [0.01, 0.03]\nradius = 0.011\ndensity = 1\n",
      "body[0].center", "center = [0.01, 0.03]", "overlaps its own periodic image");
}

TEST(CaseBodyErrors, FreeBodyStartsInContact) {
  // d0 = 1e-4: the spring-dashpot's contact distance is 0.5 d0 = 5e-5 m.
  const std::string floor = kBase + "[[wall]]\nname = \"floor\"\nfrom = [0.0, 0.0]\nto = [0.02, 0.0]\n";
  const auto disc = [](const std::string& centre) {
    return "[[body]]\nshape = \"circle\"\ncenter = " + centre + "\nradius = 0.001\ndensity = 1100\n";
  };
  // Against a wall the default contact distance equals the wall clearance d0/2, so the wall
  // check (check_walls_clear_of_bodies, earlier in the list) answers first.
  expect_error(floor + disc("[0.01, 0.00103]"), "body[0].center", "center = [0.01, 0.00103]",
               "wall 'floor' (wall[0]) passes 3e-05 m from body 'body0' (circle)");
  EXPECT_NO_THROW(load(floor + disc("[0.01, 0.00106]")));
  // A fixed body is not a contact partner that starts moving.
  EXPECT_NO_THROW(load(floor +
                       "[collision]\nrange = 2e-4\n[[body]]\nshape = \"circle\"\ncenter = [0.01, 0.00106]\n"
                       "radius = 0.001\nmotion = \"fixed\"\n"));
  // Given collision.range.
  expect_error(floor + "[collision]\nrange = 2e-4\n" + disc("[0.01, 0.00115]"), "body[0].center",
               "center = [0.01, 0.00115]", "delta_c = 0.0002 m: collision.range)");
  // Sampled shapes: an ellipse's lowest point 1.2e-4 m above the floor, within a 2e-4 m range.
  expect_error(floor +
                   "[collision]\nrange = 2e-4\n[[body]]\nshape = \"ellipse\"\ncenter = [0.01, 0.00112]\n"
                   "semi_axes = [0.002, 0.001]\ndensity = 1100\n",
               "body[0].center", "center = [0.01, 0.00112]", "its gap at t = 0 is 0.00012 m");
  // Two free bodies 4e-5 m apart, and across a periodic boundary.
  expect_error(kBase + disc("[0.005, 0.03]") + disc("[0.00704, 0.03]"), "body[0].center",
               "center = [0.005, 0.03]",
               "starts in contact with body 'body1' (circle) (body[1]): its gap at t = 0 is 4e-05 m");
  const std::string periodic =
      with(kBase, "max = [0.02, 0.06]", "max = [0.02, 0.06]\nperiodic = [true, false]");
  expect_error(periodic + disc("[0.00101, 0.03]") + disc("[0.01898, 0.03]"), "body[0].center",
               "center = [0.00101, 0.03]", "starts in contact with body 'body1'");
  // The paper's force meets a wall as the body's mirror image: half of its 3 d0 there; without a
  // stiffness it is off and nothing starts in contact.
  const std::string paper = floor + "[collision]\nmodel = \"paper\"\nstiffness = 1.5e6\n";
  expect_error(paper + disc("[0.01, 0.00114]"), "body[0].center", "center = [0.01, 0.00114]",
               "below 0.00015 m, half the contact distance (P.38 meets a wall as the body's mirror image)");
  EXPECT_NO_THROW(load(paper + disc("[0.01, 0.00116]")));
  EXPECT_NO_THROW(load(floor + "[collision]\nmodel = \"paper\"\n" + disc("[0.01, 0.00106]")));
}

TEST(CaseBodyErrors, BodyTooSmallForD0) {
  expect_error(
      with(kCase, "radius = 0.00125", "radius = 0.0004"), "body[0].radius", "radius = 0.0004",
      "body 'disc' (circle) is too small for d0 = 0.0001 m: its smallest dimension (diameter) is 0.0008 m, "
      "only 8 particles across; it needs at least 10");
  expect_error(with(kCase, "semi_axes = [0.002, 0.001]", "semi_axes = [0.002, 0.00045]"), "body[1].semi_axes",
               "semi_axes = [0.002", "smallest dimension (minor axis) is 0.0009 m, only 9 particles across");
  expect_error(with(kCase, "[[0.014, 0.02], [0.018, 0.02], [0.018, 0.024], [0.014, 0.024]]",
                    "[[0.014, 0.02], [0.018, 0.02], [0.018, 0.0205], [0.014, 0.0205]]"),
               "body[2].vertices",
               "vertices =", "smallest dimension (width) is 0.0005 m, only 5 particles across");
  expect_error(with(kCase, "radius = 0.005", "radius = 0.0009"), "body[3].radius", "radius = 0.0009",
               "smallest dimension (radius) is 0.0009 m, only 9 particles across");
  EXPECT_NO_THROW(load(with(kCase, "radius = 0.00125", "radius = 0.0005")));  // exactly 10 across
}

// ---------------------------------------------------------------------------------------------
// Overrides.

TEST(CaseBodyOverrides, BodyKeys) {
  const Case c = load(kCase, {"body.0.radius=0.002", "body.1.angle=-0.5", "body.3.motion=prescribed",
                              "body.0.name=ball", "collision.stiffness=2e6", "collision.range=1e-4",
                              "body.2.vertices=[[0.012,0.02],[0.016,0.02],[0.014,0.023]]",
                              "body.2.schedule=[[0,0,0,0],[1,1e-3,-2e-3,3],[2,0,0,0]]"});
  EXPECT_EQ(c.bodies[0].radius, 0.002);
  EXPECT_EQ(c.bodies[0].name, "ball");
  EXPECT_EQ(c.bodies[1].angle, -0.5);
  EXPECT_EQ(c.bodies[3].motion, BodyMotion::Prescribed);
  EXPECT_EQ(c.collision_stiffness, 2e6);
  EXPECT_EQ(c.collision_range, 1e-4);
  ASSERT_EQ(c.bodies[2].vertices.size(), 3u);
  EXPECT_EQ(c.bodies[2].vertices[2].x, 0.014);
  EXPECT_EQ(c.bodies[2].vertices[2].y, 0.023);
  ASSERT_EQ(c.bodies[2].schedule.size(), 3u);
  EXPECT_EQ(c.bodies[2].schedule[1].t, 1.0);
  EXPECT_EQ(c.bodies[2].schedule[1].velocity.y, -2e-3);
  EXPECT_EQ(c.bodies[2].schedule[1].omega, 3.0);
  expect_round_trip(c);
}

TEST(CaseBodyOverrides, ChangingTheShape) {
  // A circle becomes a half-disc (same keys); an ellipse cannot become a circle without a radius,
  // and with one its semi_axes (in the file) are not used by a circle.
  EXPECT_EQ(load(kCase, {"body.0.shape=half_disc"}).bodies[0].shape, BodyShape::HalfDisc);
  const CaseError e = error_of(kCase, {"body.1.shape=circle"});
  EXPECT_EQ(e.key(), "body[1].radius") << e.what();
  EXPECT_EQ(e.file(), kFile);  // located at the [[body]] table in the file
  EXPECT_EQ(e.line(), line_of(kCase, "[[body]]\nshape = \"ellipse\"")) << e.what();
  EXPECT_NE(e.message().find("missing required key for shape 'circle'"), std::string::npos) << e.what();
  const CaseError f = error_of(kCase, {"body.1.shape=circle", "body.1.radius=0.001"});
  EXPECT_EQ(f.key(), "body[1].semi_axes") << f.what();
  EXPECT_EQ(f.line(), line_of(kCase, "semi_axes = [0.002, 0.001]")) << f.what();
  EXPECT_NE(f.message().find("not used by shape 'circle'"), std::string::npos) << f.what();
}

TEST(CaseBodyOverrides, Errors) {
  expect_override_error(kCase, {"body.0.vertices=[[0.01,0.01],[0.012,0.01],[0.01,0.012]]"},
                        "body[0].vertices", "not used by shape 'circle'");
  expect_override_error(kCase, {"body.2.vertices=[[0,0],[1,0]]"}, "body[2].vertices", "too few points");
  expect_override_error(kCase, {"body.2.vertices=[[0,0],[1,0],[0,\"y\"]]"}, "body[2].vertices",
                        "point [2] must be [x, y]");
  expect_override_error(kCase, {"body.2.schedule=[[0,0,0,0],[0,1,1,1]]"}, "body[2].schedule",
                        "must increase strictly");
  expect_override_error(kCase, {"body.2.vertices=[[0.014,0.02],[0.018,0.024],[0.018,0.02],[0.014,0.024]]"},
                        "body[2].vertices", "polygon intersects itself");
  expect_override_error(kCase, {"body.4.radius=1"}, "body[4].radius",
                        "no element 4 in [[body]]: the case has 4");
  expect_override_error(kCase, {"body.0.radiu=1"}, "body[0].radiu", "did you mean 'body[0].radius'?");
  expect_override_error(kCase, {"body.0.center=[0.0195,0.01]"}, "body[0].center", "lies outside the domain");
  expect_override_error(kCase, {"collision.stiffness=-1"}, "collision.stiffness",
                        "must be >= 0 N/m^2; paper: N/m^4");
}

// ---------------------------------------------------------------------------------------------
// Resolved case.

// Polygons with holes.

namespace {

/// A fixed 12 mm square (120 d0) with the holes given, one per line.
std::string square_with_holes(const std::vector<std::string>& holes) {
  std::string text =
      "shape = \"polygon\"\nmotion = \"fixed\"\n"
      "vertices = [[0.004, 0.02], [0.016, 0.02], [0.016, 0.032], [0.004, 0.032]]\nholes = [\n";
  for (const std::string& h : holes) text += "  " + h + ",\n";
  return one_body(text + "]\n");
}

}  // namespace

TEST(CaseBodyErrors, PolygonHolesInsideApartAndWideEnough) {
  const std::string middle = "[[0.007, 0.023], [0.013, 0.023], [0.013, 0.029], [0.007, 0.029]]";
  const Case ok =
      load(square_with_holes({"[[0.0055, 0.0215], [0.0085, 0.0215], [0.0085, 0.0245], [0.0055, 0.0245]]",
                              "[[0.0145, 0.0305], [0.0145, 0.026], [0.010, 0.0305]]"}));
  ASSERT_EQ(ok.bodies[0].holes.size(), 2u);
  EXPECT_EQ(ok.bodies[0].holes[1].size(), 3u);

  const std::string outside = "[[0.017, 0.021], [0.019, 0.021], [0.019, 0.023]]";
  expect_error(square_with_holes({middle, outside}), "body[0].holes", outside,
               "polygon hole holes[1] does not lie inside the polygon's vertices");
  const std::string crossing = "[[0.010, 0.023], [0.018, 0.023], [0.018, 0.029], [0.010, 0.029]]";
  expect_error(square_with_holes({crossing}), "body[0].holes", crossing,
               "polygon hole holes[0] does not lie inside the polygon's vertices");
  const std::string overlapping = "[[0.008, 0.024], [0.014, 0.024], [0.014, 0.030]]";
  expect_error(square_with_holes({middle, overlapping}), "body[0].holes", overlapping,
               "polygon holes holes[0] and holes[1] overlap");
  const std::string near_edge = "[[0.0045, 0.023], [0.013, 0.023], [0.013, 0.029], [0.0045, 0.029]]";
  expect_error(
      square_with_holes({near_edge}), "body[0].holes", near_edge,
      "body 'body0' (polygon) is too thin for d0 = 0.0001 m: the solid between polygon hole holes[0] "
      "and the outline (vertices) is 0.0005 m, only 5 particles across; it needs at least 10");
  const std::string tiny = "[[0.009, 0.025], [0.0095, 0.025], [0.0095, 0.0255], [0.009, 0.0255]]";
  expect_error(
      square_with_holes({tiny}), "body[0].holes", tiny,
      "polygon hole holes[0] of body 'body0' (polygon) is too small for d0 = 0.0001 m: it is 0.0005 m "
      "across, only 5 particles; the fluid in it needs at least 10");
  const std::string bow_tie = "[[0.007, 0.023], [0.013, 0.029], [0.013, 0.023], [0.007, 0.029]]";
  expect_error(square_with_holes({bow_tie}), "body[0].holes", bow_tie,
               "polygon hole holes[0] intersects itself: edge holes[0][0] -> holes[0][1]");
  const std::string two_points = "[[0.007, 0.023], [0.013, 0.023]]";
  expect_error(square_with_holes({middle, two_points}), "body[0].holes", two_points,
               "loop [1]: too few points");
  expect_error(one_body("shape = \"circle\"\ncenter = [0.01, 0.03]\nradius = 0.003\ndensity = 2000\n"
                        "holes = [[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]]\n"),
               "body[0].holes", "holes", "not used by shape 'circle' (only by shape polygon)");
}

TEST(CaseBodyErrors, PrescribedPathStopsShortOfWallsAndBodies) {
  // a disc driven down onto the floor: 0.00875 m of gap at the start, a path of 0.00874 m stops
  // 0.1 d0 short (loads), one of 0.0088 m runs 0.5 d0 into it
  const std::string free_disc = "density = 1250\nvelocity = [0.001, -0.002]\nomega = 0.5";
  const std::string towed = with(kCase, free_disc, "motion = \"prescribed\"\nvelocity = [0, -0.00874]");
  EXPECT_NO_THROW(load_case_text(towed, kFile, {}));
  expect_error(with(towed, "-0.00874", "-0.0088"), "body[0].velocity", "velocity = [0, -0.0088]",
               "body 'disc' (circle), moving as prescribed, runs into");
  // the paddle's schedule taken into the fixed half disc at the left edge
  const std::string rows = "schedule = [\n  [0, 0, 0, 0],\n  [0.5, 0.001, 0, 2],\n  [1.5, 0, -0.001, 0],\n]";
  const std::string into =
      with(kCase, rows, "schedule = [\n  [0, -0.012, 0.016, 0],\n  [1, -0.012, 0.016, 0],\n]");
  expect_error(into, "body[2].schedule", "schedule = [",
               "body 'paddle' (polygon), moving as prescribed, runs into body 'obstacle' (half_disc) "
               "(body[3]) at t = ");
}

TEST(CaseBodyErrors, PrescribedTurnSweepsTheWholeBody) {
  // a half disc turns about its centroid, 0.849 mm from the disc's centre for R = 2 mm: its
  // flat side's ends, 2.173 mm from the centroid, sweep 1.324 mm past where the flat side starts
  const auto turner = [](const std::string& x) {
    return kBase + "\n[[body]]\nname = \"turner\"\nshape = \"half_disc\"\ncenter = [" + x +
           ", 0.03]\nradius = 0.002\nmotion = \"prescribed\"\nomega = 4.0\n";
  };
  EXPECT_NO_THROW(load_case_text(turner("0.0014"), kFile, {}));
  expect_error(turner("0.0012"), "body[0].velocity", "[[body]]", "runs into the domain edge x = 0 m at t = ");
}
