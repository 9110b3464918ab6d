// The typed, validated description of a run (SI units). Built from a TOML case file by
// load_case(); physics code reads only this struct, never the file. Its members carry no defaults
// of their own (they are value-initialised): the defaults are the schema's (src/case/schema.cpp),
// and default_case() is the Case that holds them.
#pragma once

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "particula/core/types.hpp"
#include "particula/geometry/wall_piece.hpp"

namespace particula {

enum class LaplacianScheme { FatehiManzari, Morris };
enum class BoundaryModel { SingleLayer, Dummy };
enum class NormalModel { Kernel, Analytic };
/// How the hydrodynamic loads on solids are evaluated (docs/method.md, "Forces on solids"):
/// the paper's sum of the surface traction over the surface particles (P.26-P.27) with the
/// lattice masses of the paper's fill, or the momentum balance of the fluid in a band around each
/// solid, with fluid masses that fill the region outside the bodies exactly.
enum class ForceModel { Paper, Momentum };
/// The first-derivative weights of fluid particles (docs/method.md, "The self-coupled mode:
/// zeroth-order gradient correction"): the paper's renormalization (P.7), exact for linear fields,
/// or the same with the kernel gradient also corrected to zeroth order (the weights of a particle
/// sum to zero).
enum class GradientScheme { Consistent, Paper };
enum class InitialFlow { Rest, TaylorGreen, Couette };
/// Exact solution a case is compared with (probes get a vx_exact column, summary.json the error).
enum class ExactSolution { None, Couette, Poiseuille, SpinUp };
/// Solid-solid contact law (docs/method.md, "Contacts").
enum class ContactModel { SpringDashpot, Paper };

enum class WallShape { Segment, Arc };

/// A wall: a straight segment or a circular arc. The fluid lies on its LEFT when walking from
/// its start to its end (so a closed container is listed counter-clockwise, and an arc turning
/// counter-clockwise, end_angle > start_angle, has the fluid inside its circle). A segment may
/// slide along itself at `velocity`; any wall may turn rigidly about `pivot` at the rate `omega`.
struct WallSpec {
  std::string name;
  Vec2 from, to;  // segment; for an arc its end points (derived at load)
  Vec2 velocity;  // must be tangential (parallel to to - from)
  WallShape shape{};
  Vec2 center{};  // arc
  real radius{}, start_angle{}, end_angle{};
  real omega{};  // rigid rotation rate about `pivot` (rad/s, counter-clockwise), from t = 0
  Vec2 pivot{};

  WallPiece piece() const {
    return shape == WallShape::Arc ? WallPiece::arc(center, radius, start_angle, end_angle)
                                   : WallPiece::segment(from, to);
  }
};

/// An open boundary (docs/method.md, "Open boundaries"): a straight segment on a bounded
/// edge of the domain, fluid on its LEFT walking from `from` to `to` (as for walls), where fluid
/// enters (an inlet, with a prescribed velocity along the inward normal) or leaves (an outlet, at
/// a prescribed pressure). Outside the domain behind it lies a buffer of `layers` rows of
/// particles whose fields the boundary sets.
enum class OpenKind { Inlet, Outlet };
/// The inlet's velocity profile across the segment: uniform, a parabola that vanishes at both
/// ends (peak `velocity` in the middle), or a table of (distance from `from`, speed), linear in
/// between.
enum class InletProfile { Uniform, Parabolic, Table };

/// What an outlet does with a body carried to it: hold it back at its screen, or remove it
/// there (docs/method.md, "Screens").
enum class OutletBodies { Held, Removed };

struct OpenSpec {
  std::string name;
  OpenKind kind{};
  Vec2 from, to;
  InletProfile profile{};   // inlet
  real velocity{};          // inlet: uniform speed or parabola peak (m/s, into the fluid)
  std::vector<Vec2> table;  // inlet, profile table: (s in m from `from`, speed in m/s)
  real ramp_time{};         // inlet: speed ramped as (1 - cos(pi t / T)) / 2 until T; 0 = none
  real pressure{};          // outlet: P on the line is fluid.p0 + pressure (Pa)
  OutletBodies bodies{};    // outlet: bodies held at its screen or removed there
  int layers{};             // rows of buffer particles; 0 = ceil(h / d0) + 1

  /// Unit tangent (from -> to) and inward normal (its left).
  Vec2 tangent() const { return (to - from) / norm(to - from); }
  Vec2 inward_normal() const {
    const Vec2 t = tangent();
    return {-t.y, t.x};
  }
  real width() const { return norm(to - from); }
};

/// A probe is a line (`points` equally spaced points from `from` to `to`, both ends included)
/// or a list of points (`at`).
enum class ProbeKind { Line, Points };

/// A probe: fields interpolated (moving least squares, src/solver/interpolation.cpp) at its
/// points, written every `interval` seconds; a line probe also writes its flow rate.
struct ProbeSpec {
  std::string name;
  Vec2 from, to;  // kind Line
  int points{};
  real interval{};
  ProbeKind kind{};
  std::vector<Vec2> at;  // kind Points
};

/// The points of a probe: equally spaced along a line probe, or its `at` list.
inline std::vector<Vec2> probe_points(const ProbeSpec& p) {
  if (p.kind == ProbeKind::Points) return p.at;
  std::vector<Vec2> pts;
  for (int k = 0; k < p.points; ++k) {
    const real s = p.points > 1 ? static_cast<real>(k) / (p.points - 1) : 0.0;
    pts.push_back(p.from + s * (p.to - p.from));
  }
  return pts;
}

/// The number of points of a probe.
inline std::size_t probe_point_count(const ProbeSpec& p) {
  return p.kind == ProbeKind::Points ? p.at.size() : static_cast<std::size_t>(p.points);
}

enum class BodyShape { Circle, Ellipse, Polygon, HalfDisc };
enum class BodyMotion { Free, Fixed, Prescribed };

/// One knot of a prescribed piecewise-linear motion: velocity and angular velocity at time t.
struct MotionKnot {
  real t{};
  Vec2 velocity;
  real omega{};
};

/// A rigid body. Its position is its area centroid; `angle` (rad, counter-clockwise) rotates
/// the body frame to the world frame.
struct BodySpec {
  std::string name;
  BodyShape shape{};
  Vec2 center;     // circle, ellipse: centroid; half_disc: centre of the full disc
  real radius{};   // circle, half_disc
  Vec2 semi_axes;  // ellipse: (a along the body x axis, b along the body y axis)
  std::vector<Vec2>
      vertices;  // polygon: vertices in world coordinates at t = 0 (angle applies about the centroid)
  std::vector<std::vector<Vec2>> holes;  // polygon: holes (fluid inside), world coordinates at t = 0
  real angle{};
  real density{};  // kg/m^3 (free bodies)
  BodyMotion motion{};
  Vec2 velocity;                     // initial velocity (free) or constant prescribed velocity
  real omega{};                      // initial / constant prescribed angular velocity (rad/s)
  std::vector<MotionKnot> schedule;  // prescribed: piecewise-linear in time (overrides velocity/omega)
  Vec2 reference_velocity;           // coefficients.csv: free stream relative to the body (0 = [analysis]'s)
  real reference_length{};           // coefficients.csv: length in the coefficients (0 = [analysis]'s)
};

struct Case {
  std::string name;
  std::string description;
  std::filesystem::path source;  // the case file it was read from

  // [domain]
  Vec2 domain_min, domain_max;
  bool periodic_x{}, periodic_y{};

  // [resolution]
  real d0{};
  real h_over_d0{};

  // [fluid]
  real rho0{};
  real nu{};  // kinematic viscosity; the file gives fluid.nu or fluid.mu (then nu = mu/rho0)
  real c{};   // artificial sound speed
  real p0{};  // background pressure of the equation of state
  Vec2 gravity;
  bool gravity_in_fluid{};
  Vec2 body_force;  // uniform acceleration on the fluid only (e.g. Poiseuille driving)

  // [time]
  real t_end{};
  real cfl{};                // alpha of P.29
  real dt_max{};             // 0 = no cap
  std::int64_t max_steps{};  // 0 = unlimited

  // [numerics]
  LaplacianScheme laplacian{};
  BoundaryModel boundary{};
  NormalModel normals{};  // P.18 is selectable; docs/method.md, "7. Boundary normals"
  ForceModel force{};
  GradientScheme gradient{};
  real rhie_chow_factor{};
  real shifting_beta{};
  real odd_even_damping{};
  real surface_guard{};
  real film_gap{};
  real load_band_motion{};  // d0
  int wall_pressure_sweeps{};

  // [initial]
  real perturbation{};  // fraction of d0
  std::uint64_t seed{};
  InitialFlow initial_flow{};
  real initial_amplitude{};  // m/s, for taylor_green
  bool hydrostatic{};        // start from hydrostatic density when gravity is in the fluid

  // [output]
  real output_interval{};
  bool snapshots{};
  real snapshot_interval{};    // 0 = output_interval
  real checkpoint_interval{};  // 0 = only at the end and on interruption

  // [guard]
  real rho_min_ratio{};
  real rho_max_ratio{};

  // [validation]
  ExactSolution exact{};

  // [analysis]: references of the dimensionless coefficients (coefficients.csv); 0 = none
  Vec2 reference_velocity;
  real reference_length{};

  // [collision]
  ContactModel collision_model{};
  real collision_stiffness{};    // spring_dashpot: k_n (N/m^2), 0 = derived; paper: k of P.38, 0 = off
  real collision_range{};        // contact distance delta_c (m); 0 = 0.5 d0 (spring_dashpot), 3 d0 (paper)
  real collision_restitution{};  // e of a dry impact (spring_dashpot)
  real collision_friction{};     // Coulomb coefficient mu (spring_dashpot)
  real collision_max_overlap{};  // delta_max / d0 of the derived stiffness
  bool collision_lubrication{};  // squeeze-film correction below the resolution
  real collision_lubrication_range{};  // g_range (m); 0 = 2 d0

  std::vector<WallSpec> walls;
  std::vector<ProbeSpec> probes;
  std::vector<BodySpec> bodies;
  std::vector<OpenSpec> inlets;   // kind Inlet
  std::vector<OpenSpec> outlets;  // kind Outlet

  real h() const { return h_over_d0 * d0; }
  real mu() const { return nu * rho0; }
  /// The gap below which solids are in contact: collision.range, or its model's default.
  real contact_distance() const {
    if (collision_range > 0) return collision_range;
    return collision_model == ContactModel::Paper ? 3 * d0 : 0.5 * d0;
  }
  /// Whether solids interact at all (the paper's force is off without a stiffness).
  bool contacts_active() const { return collision_model != ContactModel::Paper || collision_stiffness > 0; }
  /// Rows of buffer particles behind open boundary `o` (its own, or ceil(h/d0) + 1).
  int open_layers(const OpenSpec& o) const {
    return o.layers > 0 ? o.layers : static_cast<int>(std::ceil(h_over_d0 - 1e-9)) + 1;
  }
  /// Distance from open boundary `o` into the fluid of its screen (docs/method.md, "Open
  /// boundaries"): the line, parallel to `o`, that bodies touch like a wall and never cross, so
  /// that they stay clear of what the buffer needs: the fluid within L_b + h of the line sets the
  /// buffer's fields by the fit at the mirrored ghost points, and with the momentum loads the band
  /// of kLoadBandReach h round a body must hold fluid only. Defined in src/case/open_checks.cpp.
  real open_screen_offset(const OpenSpec& o) const;
  /// Inlets then outlets: the order of the open boundaries (zones) in the solver and outputs.
  std::vector<OpenSpec> open_boundaries() const {
    std::vector<OpenSpec> all = inlets;
    all.insert(all.end(), outlets.begin(), outlets.end());
    return all;
  }
};

/// The Case of the schema's defaults: every key that has a default holds it (each row's default
/// applied through its binding, src/case/default_case.cpp), the required keys are value-initialised
/// and the arrays empty. Code that builds a Case by hand starts from it.
Case default_case();

/// The reference of a body's coefficients: its own velocity and length where given, else the
/// [analysis] ones. `velocity` is the free stream relative to the body: the drag is the force
/// along it, the lift the force 90 degrees counter-clockwise from it.
struct BodyReference {
  Vec2 velocity;
  real length{};
  bool complete() const { return length > 0 && (velocity.x != 0 || velocity.y != 0); }
};

inline BodyReference body_reference(const Case& c, std::size_t body) {
  const BodySpec& b = c.bodies.at(body);
  const bool own_v = b.reference_velocity.x != 0 || b.reference_velocity.y != 0;
  return {own_v ? b.reference_velocity : c.reference_velocity,
          b.reference_length > 0 ? b.reference_length : c.reference_length};
}

/// a - b through the nearest periodic image along the case's periodic axes (the minimum-image
/// convention of Domain::separation, for code that has a Case and no Domain).
inline Vec2 periodic_separation(const Case& c, Vec2 a, Vec2 b) {
  Vec2 d = a - b;
  const Vec2 span = c.domain_max - c.domain_min;
  if (c.periodic_x) d.x -= span.x * std::nearbyint(d.x / span.x);
  if (c.periodic_y) d.y -= span.y * std::nearbyint(d.y / span.y);
  return d;
}

}  // namespace particula
