// The case-file schema: the one table of every key (see include/particula/case/schema.hpp).
//
// To add a key, append one row below: its builder names the key, unit, default, range and
// meaning, and its binding (`field(&Case::x)`, `member(&Case::walls, &WallSpec::x)`) is the
// assignment into Case. Rows are applied in order, so a row may use fields set by earlier rows
// (fluid.mu uses fluid.rho0). A new array of tables also needs one row in make_sections()
// (schema_sections.cpp).
#include "particula/case/schema.hpp"

#include <algorithm>
#include <type_traits>
#include <utility>

#include "schema_rows.hpp"

namespace particula {
namespace {

using namespace schema_rows;  // the row builders (schema_rows.hpp)

// ---------------------------------------------------------------------------------------------
// THE TABLE.

std::vector<KeySpec> make_schema() {
  const Vec2 zero{0, 0};
  const auto W = &Case::walls;
  const auto P = &Case::probes;
  const auto B = &Case::bodies;
  const auto I = &Case::inlets;
  const auto O = &Case::outlets;
  const std::string shape = "body[].shape", motion = "body[].motion", wall_shape = "wall[].shape";
  const std::string inlet_profile = "inlet[].profile";
  return {
      // top level
      string_key("name", required(), "Name of the case; the default run directory is `runs/<name>`.",
                 field(&Case::name), /*name=*/true),
      string_key("description", def(std::string{}), "Free text describing the case.",
                 field(&Case::description)),
      // [domain]
      vec2_key("domain.min", "m", required(), "Lower-left corner of the rectangular domain.",
               field(&Case::domain_min)),
      vec2_key("domain.max", "m", required(),
               "Upper-right corner of the domain; must exceed domain.min in both components.",
               field(&Case::domain_max)),
      bool2_key("domain.periodic", def(Bool2{false, false}),
                "Periodicity along x and y; a periodic axis must be at least 3 h long.",
                pair_field(&Case::periodic_x, &Case::periodic_y)),
      // [resolution]
      real_key("resolution.d0", "m", required(), gt(0),
               "Initial particle spacing; every length that scales with resolution derives from it.",
               field(&Case::d0)),
      real_key("resolution.h_over_d0", "-", def(2.6), closed(1.5, 4), "Smoothing length h in units of d0.",
               field(&Case::h_over_d0)),
      // [fluid]
      real_key("fluid.rho0", "kg/m^3", def(1000.0), gt(0), "Reference density of the fluid.",
               field(&Case::rho0)),
      real_key("fluid.nu", "m^2/s", one_of("viscosity"), gt(0),
               "Kinematic viscosity (give this or fluid.mu).", field(&Case::nu)),
      real_key("fluid.mu", "Pa s", one_of("viscosity"), gt(0),
               "Dynamic viscosity (give this or fluid.nu); stored as nu = mu / rho0.", dynamic_viscosity()),
      real_key(
          "fluid.c", "m/s", required(), gt(0),
          "Artificial speed of sound of the equation of state: at least 10 times the fastest speed of the "
          "flow (a case setting a speed at or above it is refused).",
          field(&Case::c)),
      real_key("fluid.p0", "Pa", def(0.0), ge(0), "Background pressure of the equation of state.",
               field(&Case::p0)),
      vec2_key("fluid.gravity", "m/s^2", def(zero), "Gravitational acceleration.", field(&Case::gravity)),
      bool_key("fluid.gravity_in_fluid", def(false),
               "Whether gravity also acts on the fluid particles (otherwise on bodies only).",
               field(&Case::gravity_in_fluid)),
      vec2_key("fluid.body_force", "m/s^2", def(zero),
               "Uniform acceleration on the fluid only (e.g. to drive Poiseuille flow).",
               field(&Case::body_force)),
      // [time]
      real_key("time.end", "s", required(), gt(0), "Simulated time at which the run stops.",
               field(&Case::t_end)),
      real_key("time.cfl", "-", def(0.5), open_closed(0, 1), "Safety factor on the stable time step.",
               field(&Case::cfl)),
      real_key("time.dt_max", "s", def(0.0, "0 (no cap)"), ge(0), "Upper bound on the time step.",
               field(&Case::dt_max)),
      int_key("time.max_steps", def(std::int64_t{0}, "0 (unlimited)"), ge(0), "Maximum number of steps.",
              field(&Case::max_steps)),
      // [numerics]
      choice_key("numerics.laplacian", {"fatehi_manzari", "morris"}, def(std::string{"fatehi_manzari"}),
                 "Discretisation of the viscous Laplacian.", &Case::laplacian),
      choice_key("numerics.boundary", {"single_layer", "dummy"}, def(std::string{"single_layer"}),
                 "Wall model: one layer of wall particles with solved pressure, or dummy particles.",
                 &Case::boundary),
      choice_key("numerics.normals", {"kernel", "analytic"}, def(std::string{"analytic"}),
                 "Surface normals in the wall pressure (P.20) and forces: the exact normals of the geometry, "
                 "or the kernel sums of P.18 (noisy by a few degrees on a perturbed lattice; see "
                 "docs/method.md, \"7. Boundary normals\").",
                 &Case::normals),
      choice_key(
          "numerics.force", {"paper", "momentum"}, def(std::string{"momentum"}),
          "Hydrodynamic loads on bodies and walls: `momentum` takes them from the momentum balance of "
          "the fluid in a band of 5 h around each solid, with fluid masses that fill the region outside "
          "the bodies exactly (second order, in balance with the momentum put into the fluid); `paper` "
          "sums the surface traction over the surface particles (P.26-P.27) with the lattice masses of "
          "the paper's fill, to reproduce its results (docs/method.md, \"Forces on solids\").",
          &Case::force),
      choice_key(
          "numerics.gradient", {"consistent", "paper"}, def(std::string{"consistent"}),
          "First derivatives at fluid particles (pressure gradient, velocity gradient and divergence): "
          "`consistent` corrects the kernel gradient so that a particle's weights sum to zero and then "
          "renormalizes it (exact for constant and linear fields on any particle distribution); `paper` "
          "renormalizes only (P.7), which on an irregular distribution couples a particle's own pressure "
          "and velocity into a mode that grows at the rate c |sum_j w_j B gradW_ij| and ended runs with "
          "fluid at twice rho0 (docs/method.md, \"The self-coupled mode: zeroth-order gradient "
          "correction\").",
          &Case::gradient),
      real_key("numerics.rhie_chow_factor", "-", def(1.0), closed(0, 10),
               "Scale of the Rhie-Chow pressure stabilisation in the continuity equation.",
               field(&Case::rhie_chow_factor)),
      real_key("numerics.shifting_beta", "-", def(0.05), closed(0, 0.2),
               "Strength of particle shifting, which keeps the particle distribution uniform.",
               field(&Case::shifting_beta)),
      real_key(
          "numerics.odd_even_damping", "-", def(0.005), closed(0, 0.05),
          "Strength alpha of the damping of odd-even (checkerboard) velocity modes, kappa = alpha c h times "
          "the difference of the compact and the wide Laplacian of V (zero for quadratic fields; "
          "docs/method.md, \"Odd-even velocity damping\"). 0 is the paper's scheme.",
          field(&Case::odd_even_damping)),
      real_key("numerics.surface_guard", "-", def(0.25), closed(0, 0.45),
               "Keep-out distance of fluid particles from walls and body surfaces, in d0: a fluid particle "
               "closer than this is put back and loses its velocity into the surface (0 turns the guard off; "
               "docs/method.md, \"Surface guard\").",
               field(&Case::surface_guard)),
      real_key("numerics.film_gap", "-", def(2.0), closed(0, 4),
               "Gap between two facing surfaces, in d0, below which the fluid between them is an unresolved "
               "film: the particles' volume change is left out of the continuity equation (fully below half "
               "this gap), so that a closing or opening gap builds no spurious cushion or suction; the "
               "lubrication force of the contact model stands for the film (0 turns it off; "
               "docs/method.md, \"Unresolved films\").",
               field(&Case::film_gap)),
      real_key("numerics.load_band_motion", "-", def(0.1), closed(0, 0.5),
               "With numerics.force = \"momentum\": how far, in d0, a solid or a particle (relative to its "
               "closest solid) may move before the band of the momentum loads is built again; less between "
               "two solids close together (docs/method.md, \"The kept band\"). 0 builds it every "
               "step (the reference the default is measured against); 0.1 makes many-body steps faster.",
               field(&Case::load_band_motion)),
      int_key("numerics.wall_pressure_sweeps", def(std::int64_t{1}), closed(1, 50),
              "Sweeps of the single-layer wall pressure update per step.",
              field(&Case::wall_pressure_sweeps)),
      // [initial]
      real_key("initial.perturbation", "-", def(0.05), closed(0, 0.3),
               "Random perturbation of the initial lattice, as a fraction of d0.",
               field(&Case::perturbation)),
      int_key("initial.seed", def(std::int64_t{1}), ge(0), "Seed of the random initial perturbation.",
              field(&Case::seed)),
      choice_key("initial.flow", {"rest", "taylor_green", "couette"}, def(std::string{"rest"}),
                 "Initial velocity field: fluid at rest, a Taylor-Green vortex, or the developed linear "
                 "shear between the walls at domain.min.y and domain.max.y (their velocities).",
                 &Case::initial_flow),
      real_key("initial.amplitude", "m/s", def(1.0), gt(0), "Velocity amplitude of the initial flow.",
               field(&Case::initial_amplitude)),
      bool_key("initial.hydrostatic", def(false),
               "Whether to start from the hydrostatic density when gravity acts on the fluid.",
               field(&Case::hydrostatic)),
      // [output]
      real_key("output.interval", "s", required(), gt(0), "Time between outputs (body history rows).",
               field(&Case::output_interval)),
      bool_key("output.snapshots", def(true), "Whether to write VTK particle snapshots.",
               field(&Case::snapshots)),
      real_key("output.snapshot_interval", "s", def(0.0, "0 (= output.interval)"), ge(0),
               "Time between VTK snapshots.", field(&Case::snapshot_interval)),
      real_key("output.checkpoint_interval", "s", def(0.0, "0 (end and interruption only)"), ge(0),
               "Time between checkpoints.", field(&Case::checkpoint_interval)),
      // [guard]
      real_key("guard.rho_min_ratio", "-", def(0.5), open(0, 1),
               "The run stops when a density falls below this fraction of rho0.",
               field(&Case::rho_min_ratio)),
      real_key("guard.rho_max_ratio", "-", def(2.0), gt(1),
               "The run stops when a density exceeds this multiple of rho0.", field(&Case::rho_max_ratio)),
      // [validation]
      choice_key(
          "validation.exact", {"none", "couette", "poiseuille", "spin_up"}, def(std::string{"none"}),
          "Exact solution to compare with: probes get vx_exact and vy_exact columns and summary.json the L2 "
          "profile error. couette, poiseuille: start-up channel flows along x between walls at domain.min.y "
          "and domain.max.y (error of vx); spin_up: fluid at rest in a circular container (one full-circle "
          "arc wall) that starts turning at wall[].omega about its centre at t = 0 (error of the velocity "
          "vector).",
          &Case::exact),
      // [analysis]
      vec2_key(
          "analysis.reference_velocity", "m/s", def(zero, "[0, 0] (none)"),
          "Free-stream velocity U relative to the bodies, for coefficients.csv: the drag is the hydrodynamic "
          "force along U, the lift the force 90 degrees counter-clockwise from it, C_D = F_D / (0.5 rho0 "
          "|U|^2 L), C_L = F_L / (0.5 rho0 |U|^2 L), C_M = torque / (0.5 rho0 |U|^2 L^2), Re = |U| L / nu "
          "(per unit depth). A body's own body[].reference_velocity replaces it.",
          field(&Case::reference_velocity)),
      real_key("analysis.reference_length", "m", def(0.0, "0 (none)"), ge(0),
               "Reference length L of the coefficients (e.g. a cylinder's diameter). A body's own "
               "body[].reference_length replaces it.",
               field(&Case::reference_length)),
      // [collision]
      choice_key(
          "collision.model", {"spring_dashpot", "paper"}, def(std::string{"spring_dashpot"}),
          "Contact law between solids: a linear spring and dashpot whose stiffness is derived from the "
          "impact speed (no tuning), with damping from collision.restitution, optional friction and a "
          "lubrication correction, or the paper's repulsion P.38 (needs collision.stiffness); see "
          "docs/method.md, \"Contacts\".",
          &Case::collision_model),
      real_key("collision.stiffness", "N/m^2; paper: N/m^4",
               def(0.0, "0 (spring_dashpot: derived; paper: no repulsion)"), ge(0),
               "spring_dashpot: normal stiffness k_n, force per unit depth per metre of overlap (0 = derived "
               "from the impact speed and collision.max_overlap); paper: k of P.38, between two bodies and "
               "between a body and its mirror image in a wall.",
               field(&Case::collision_stiffness)),
      real_key("collision.range", "m", def(0.0, "0 (spring_dashpot: 0.5 d0; paper: 3 d0)"), ge(0),
               "Contact distance delta_c (the paper's eps): solids are in contact where the gap between "
               "their surfaces is below it.",
               field(&Case::collision_range)),
      real_key("collision.restitution", "-", def(0.8), open_closed(0, 1),
               "spring_dashpot: coefficient of restitution e of a dry normal impact, which sets the dashpot "
               "(below about 0.7 the rebound is somewhat livelier, since the force never pulls).",
               field(&Case::collision_restitution)),
      real_key("collision.friction", "-", def(0.0), ge(0),
               "spring_dashpot: Coulomb friction coefficient between solids (history-free, regularized).",
               field(&Case::collision_friction)),
      real_key("collision.max_overlap", "-", def(0.1), open_closed(0, 1),
               "spring_dashpot: overlap reached at the characteristic impact speed, as a fraction of d0; it "
               "sets the derived stiffness (smaller = stiffer contact and smaller time step).",
               field(&Case::collision_max_overlap)),
      bool_key("collision.lubrication", def(true),
               "spring_dashpot: add the analytic squeeze-film force between solids closer than "
               "collision.lubrication_range, which the particles cannot resolve (the fluid always has a "
               "viscosity, hence on by default).",
               field(&Case::collision_lubrication)),
      real_key("collision.lubrication_range", "m", def(0.0, "0 (= 2 d0)"), ge(0),
               "spring_dashpot: gap below which the lubrication correction acts.",
               field(&Case::collision_lubrication_range)),
      // [[wall]]
      string_key("wall[].name", per_index(wall_name, "wall<k> (k = index from 0)"),
                 "Name of the wall in output and messages.", member(W, &WallSpec::name), /*name=*/true),
      choice_member(
          "wall[].shape", {"segment", "arc"}, def(std::string{"segment"}),
          "A straight segment (from, to) or a circular arc (center, radius, start_angle, end_angle).", W,
          &WallSpec::shape),
      used_when(vec2_key("wall[].from", "m", required(),
                         "Start of the segment; the fluid lies on the left walking from `from` to `to`.",
                         member(W, &WallSpec::from)),
                wall_shape, {"segment"}),
      used_when(vec2_key("wall[].to", "m", required(), "End of the segment.", member(W, &WallSpec::to)),
                wall_shape, {"segment"}),
      used_when(vec2_key("wall[].center", "m", required(), "Centre of the arc's circle.",
                         member(W, &WallSpec::center)),
                wall_shape, {"arc"}),
      used_when(real_key("wall[].radius", "m", required(), gt(0), "Radius of the arc.",
                         member(W, &WallSpec::radius)),
                wall_shape, {"arc"}),
      used_when(real_key("wall[].start_angle", "rad", required(), any(),
                         "Angle of the arc's start, counter-clockwise from +x about the centre.",
                         member(W, &WallSpec::start_angle)),
                wall_shape, {"arc"}),
      used_when(
          real_key("wall[].end_angle", "rad", required(), any(),
                   "Angle of the arc's end. end_angle > start_angle turns counter-clockwise, with the fluid "
                   "inside the circle (a container); end_angle < start_angle clockwise, fluid outside; "
                   "|end_angle - start_angle| = 2 pi (6.283185307179586) is a full circle.",
                   member(W, &WallSpec::end_angle)),
          wall_shape, {"arc"}),
      vec2_key("wall[].velocity", "m/s", def(zero),
               "Sliding velocity of a segment; must be parallel to to - from.",
               member(W, &WallSpec::velocity)),
      real_key("wall[].omega", "rad/s", def(0.0), any(),
               "Rate at which the wall turns rigidly about wall[].pivot (counter-clockwise), impulsively "
               "from t = 0: "
               "a rotating drum, the outer cylinder of a Couette cell. Walls that share an end point turn "
               "together.",
               member(W, &WallSpec::omega)),
      vec2_key("wall[].pivot", "m", def(zero),
               "Point the wall turns about when omega is not 0 (an arc turning "
               "about its own centre: its center).",
               member(W, &WallSpec::pivot)),
      // [[probe]]
      string_key("probe[].name", required(),
                 "Name of the probe; it writes `probe_<name>.csv` (a line probe also `flow_<name>.csv`).",
                 member(P, &ProbeSpec::name), /*name=*/true, /*unique=*/true),
      choice_member(
          "probe[].kind", {"line", "points"}, def(std::string{"line"}),
          "A line of equally spaced points (from, to, points), which also writes its flow rate, or a "
          "list of points (at).",
          P, &ProbeSpec::kind),
      used_when(vec2_key("probe[].from", "m", required(), "First point of the probe line.",
                         member(P, &ProbeSpec::from)),
                "probe[].kind", {"line"}),
      used_when(
          vec2_key("probe[].to", "m", required(), "Last point of the probe line.", member(P, &ProbeSpec::to)),
          "probe[].kind", {"line"}),
      used_when(
          int_key("probe[].points", required(), closed(2, 1e6),
                  "Number of equally spaced points, both ends included.", member(P, &ProbeSpec::points)),
          "probe[].kind", {"line"}),
      used_when(vec2_list_key("probe[].at", "m", required(), 1, "The probe's points [[x, y], ...].",
                              member(P, &ProbeSpec::at)),
                "probe[].kind", {"points"}),
      real_key("probe[].interval", "s", required(), gt(0), "Time between probe outputs.",
               member(P, &ProbeSpec::interval)),
      // [[body]]
      string_key("body[].name", per_index(body_name, "body<k> (k = index from 0)"),
                 "Name of the body in output and messages.", member(B, &BodySpec::name), /*name=*/true,
                 /*unique=*/true),
      choice_member("body[].shape", {"circle", "ellipse", "polygon", "half_disc"}, required(),
                    "Shape of the body; each shape has its own keys (center, radius, semi_axes, vertices).",
                    B, &BodySpec::shape),
      used_when(
          vec2_key("body[].center", "m", required(),
                   "Position at t = 0: the centre of a circle or ellipse, or the centre of the full disc "
                   "of a half_disc (the middle of its flat side).",
                   member(B, &BodySpec::center)),
          shape, {"circle", "ellipse", "half_disc"}),
      used_when(real_key("body[].radius", "m", required(), gt(0), "Radius of a circle or half_disc.",
                         member(B, &BodySpec::radius)),
                shape, {"circle", "half_disc"}),
      used_when(vec2_key("body[].semi_axes", "m", required(),
                         "Semi-axes [a, b] of an ellipse, a along the body x axis (horizontal at angle 0).",
                         member(B, &BodySpec::semi_axes), gt(0)),
                shape, {"ellipse"}),
      used_when(vec2_list_key("body[].vertices", "m", required(), 3,
                              "Polygon vertices [[x, y], ...] in world coordinates at t = 0, in either "
                              "orientation, not self-intersecting and at least d0/2 apart (each is a surface "
                              "particle); a non-zero angle rotates them about their area centroid.",
                              member(B, &BodySpec::vertices)),
                shape, {"polygon"}),
      used_when(
          row("body[].holes", ValueType::Vec2Loops, "m", def(std::vector<std::vector<Vec2>>{}, "none"), any(),
              "Holes of a polygon, each a list of vertices [[x, y], ...] like `vertices` (world coordinates "
              "at t = 0, either orientation): a hole lies inside the polygon, clear of its outline and of "
              "the other holes by at least 10 d0 of solid, and the fluid fills it (a container as a body: "
              "a pipe, a ring, a perforated plate). The solid between two of its boundaries counts as the "
              "body's smallest width.",
              polygon_holes()),
          shape, {"polygon"}),
      real_key("body[].angle", "rad", def(0.0), any(),
               "Orientation at t = 0, counter-clockwise from the body frame (a half_disc's round side faces "
               "+x at angle 0).",
               member(B, &BodySpec::angle)),
      real_key("body[].density", "kg/m^3", def(0.0, "0 (not used); required (> 0) for motion free"), ge(0),
               "Density of the solid, which gives a free body its mass and moment of inertia; a free body "
               "needs a density > 0.",
               member(B, &BodySpec::density)),
      choice_member("body[].motion", {"free", "fixed", "prescribed"}, def(std::string{"free"}),
                    "How the body moves: under the forces on it (free), not at all (fixed), or with a given "
                    "velocity (prescribed). No contact acts on a prescribed body: checked at load, its path up to "
                    "time.end does not run into a wall, a domain edge or a fixed or prescribed body (it may come "
                    "close; touching, to within 0.05 d0, is refused).",
                    B, &BodySpec::motion),
      vec2_key("body[].velocity", "m/s", def(zero),
               "Initial velocity of a free body, or the constant velocity of a prescribed body without a "
               "schedule.",
               member(B, &BodySpec::velocity)),
      real_key("body[].omega", "rad/s", def(0.0), any(),
               "Initial angular velocity (counter-clockwise) of a free body, or the constant one of a "
               "prescribed body without a schedule.",
               member(B, &BodySpec::omega)),
      used_when(
          real4_table_key("body[].schedule", "s, m/s, m/s, rad/s",
                          def(std::vector<Real4>{}, "none (constant velocity and omega)"),
                          {"t", "vx", "vy", "omega"}, 2,
                          "Prescribed velocity and angular velocity, linear in time between rows "
                          "[t, vx, vy, omega] (t strictly increasing, the first row at t <= 0, the last "
                          "row held after its time); replaces velocity and omega.",
                          motion_schedule()),
          motion, {"prescribed"}),
      vec2_key("body[].reference_velocity", "m/s", def(zero, "[0, 0] (analysis.reference_velocity)"),
               "This body's free-stream velocity U for coefficients.csv (see analysis.reference_velocity), "
               "e.g. [0, U] for a body settling at speed U in fluid at rest.",
               member(B, &BodySpec::reference_velocity)),
      real_key("body[].reference_length", "m", def(0.0, "0 (analysis.reference_length)"), ge(0),
               "This body's reference length L for coefficients.csv (e.g. its diameter).",
               member(B, &BodySpec::reference_length)),
      // [[inlet]]
      string_key("inlet[].name", per_index(inlet_name, "inlet<k> (k = index from 0)"),
                 "Name of the inlet in output and messages, unique among all inlets and outlets.",
                 member(I, &OpenSpec::name), /*name=*/true, /*unique=*/true),
      vec2_key(
          "inlet[].from", "m", required(),
          "Start of the inlet segment, on an edge of the domain; the fluid lies on the left walking from "
          "`from` to `to`, as for walls.",
          member(I, &OpenSpec::from)),
      vec2_key("inlet[].to", "m", required(), "End of the inlet segment.", member(I, &OpenSpec::to)),
      choice_member(
          "inlet[].profile", {"uniform", "parabolic", "table"}, def(std::string{"uniform"}),
          "Inflow speed across the segment: the same everywhere (uniform), a parabola that is 0 at both "
          "ends and `velocity` in the middle (parabolic), or given by `table`.",
          I, &OpenSpec::profile),
      used_when(real_key("inlet[].velocity", "m/s", required(), gt(0),
                         "The uniform speed, or the parabola's peak, of the flow into the domain along the "
                         "segment's inward normal.",
                         member(I, &OpenSpec::velocity)),
                inlet_profile, {"uniform", "parabolic"}),
      used_when(
          vec2_list_key("inlet[].table", "m, m/s", required(), 2,
                        "Inflow speed across the segment as rows [[s, u], ...]: s the distance from `from` "
                        "along the segment (strictly increasing, within [0, width]), u the speed into the "
                        "domain (>= 0, at least one > 0), linear in between and held at the first and last "
                        "rows beyond them.",
                        member(I, &OpenSpec::table)),
          inlet_profile, {"table"}),
      real_key(
          "inlet[].ramp_time", "s", def(0.0, "0 (no ramp)"), ge(0),
          "Time T over which the inflow starts: the speed is multiplied by (1 - cos(pi t / T)) / 2 until T, "
          "which avoids the pressure wave of an impulsive start.",
          member(I, &OpenSpec::ramp_time)),
      int_key("inlet[].layers", def(std::int64_t{0}, "0 (= ceil(h / d0) + 1)"), closed(0, 20),
              "Rows of buffer particles outside the domain behind the segment, d0 apart: 0 (the default, "
              "ceil(h / d0) + 1, so that the buffer is deeper than h) or 2 to 20.",
              member(I, &OpenSpec::layers)),
      // [[outlet]]
      string_key("outlet[].name", per_index(outlet_name, "outlet<k> (k = index from 0)"),
                 "Name of the outlet in output and messages, unique among all inlets and outlets.",
                 member(O, &OpenSpec::name), /*name=*/true, /*unique=*/true),
      vec2_key(
          "outlet[].from", "m", required(),
          "Start of the outlet segment, on an edge of the domain; the fluid lies on the left walking from "
          "`from` to `to`, as for walls.",
          member(O, &OpenSpec::from)),
      vec2_key("outlet[].to", "m", required(), "End of the outlet segment.", member(O, &OpenSpec::to)),
      real_key("outlet[].pressure", "Pa", def(0.0), any(),
               "Pressure on the segment relative to the background: the fluid's pressure there is "
               "fluid.p0 + pressure.",
               member(O, &OpenSpec::pressure)),
      choice_member(
          "outlet[].bodies", {"held", "removed"}, def(std::string{"held"}),
          "What the outlet does with a free or prescribed body carried to it: `held`, its screen (a line "
          "max(L_b + h, 5 h) inside the segment) stops the body like a fixed wall; `removed`, the body is "
          "taken out of the run when its surface reaches that line, and fluid particles at rest relative "
          "to it fill the place it held (logged, and listed in summary.json).",
          O, &OpenSpec::bodies),
      int_key("outlet[].layers", def(std::int64_t{0}, "0 (= ceil(h / d0) + 1)"), closed(0, 20),
              "Rows of buffer particles outside the domain behind the segment, d0 apart: 0 (the default, "
              "ceil(h / d0) + 1, so that the buffer is deeper than h) or 2 to 20.",
              member(O, &OpenSpec::layers)),
  };
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// KeySpec helpers and look-ups.

std::string KeySpec::section() const {
  const auto dot = key.find('.');
  if (dot == std::string::npos) return "";
  std::string s = key.substr(0, dot);
  if (s.size() >= 2 && s.ends_with("[]")) s.resize(s.size() - 2);
  return s;
}

std::string KeySpec::leaf() const {
  const auto dot = key.rfind('.');
  return dot == std::string::npos ? key : key.substr(dot + 1);
}

bool KeySpec::in_array() const { return key.find("[]") != std::string::npos; }

Value KeySpec::default_at(std::size_t index) const {
  return default_for ? default_for(index) : default_value;
}

bool KeySpec::used_for(const Case& c, std::size_t index) const {
  if (!used_when) return true;
  const KeySpec* decider = find_key(used_when->key);
  const std::optional<Value> v = decider ? decider->bind.get(c, index) : std::nullopt;
  const auto* choice = v ? std::get_if<std::string>(&*v) : nullptr;
  return choice &&
         std::find(used_when->values.begin(), used_when->values.end(), *choice) != used_when->values.end();
}

const std::vector<KeySpec>& case_schema() {
  static const std::vector<KeySpec> schema = make_schema();
  return schema;
}

const KeySpec* find_key(std::string_view key) {
  for (const KeySpec& s : case_schema())
    if (s.key == key) return &s;
  return nullptr;
}

}  // namespace particula
