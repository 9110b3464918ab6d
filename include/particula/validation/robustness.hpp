// The robustness group of `particula validate`: cases nobody tuned, run at default
// numerics, and checks of physical sanity on their run directories (bodies.csv, walls.csv,
// the snapshots): no body overlap, no fluid outside the domain or inside a solid, energy that
// decays, a rebound that matches the restitution coefficient, momentum balance in a channel.
// The cases are in cases/robustness/; each check takes the run directory and its resolved case.
#pragma once

#include <filesystem>
#include <vector>

#include "particula/case/case.hpp"
#include "particula/validation/validate.hpp"

namespace particula {

/// The robustness entries of validation_entries() (group Robustness), in report order.
std::vector<ValidationEntry> robustness_entries();

/// One body's history from bodies.csv (all columns the checks use).
struct BodyTrack {
  std::vector<double> t, x, y, angle, vx, vy, omega, fx, fy;
  std::vector<double> fdx, fdy;  // the odd-even damping's sink (zeros for a file without the columns)
  std::size_t size() const { return t.size(); }
};

/// Every body's history, indexed as the case's [[body]] list (a body without rows has an empty
/// track). Throws io::IoError when bodies.csv is missing or malformed.
std::vector<BodyTrack> read_body_tracks(const std::filesystem::path& run_dir, std::size_t bodies);

/// Smallest gap (m, negative when they overlap) between bodies a and b of case c placed at the
/// given centroid positions and angles (periodic images included).
double body_gap(const Case& c, std::size_t a, Vec2 pos_a, double angle_a, std::size_t b, Vec2 pos_b, double angle_b);
/// Smallest gap (m, negative when it crosses) between body a and wall w of case c (only where
/// the body lies over the segment, as for the contact model).
double wall_gap(const Case& c, std::size_t a, Vec2 pos_a, double angle_a, std::size_t w);

/// Over every row of bodies.csv: the deepest overlap between two bodies or a body and a wall
/// (pairs of two non-moving solids are skipped); fails when it exceeds `max_overlap` d0.
std::vector<ValidationCheck> check_no_overlap(const std::filesystem::path& run_dir, const Case& c,
                                              double max_overlap = 0.25);
/// Over every snapshot: fluid particles outside the domain (across a non-periodic edge) and
/// fluid particles more than `depth` d0 inside a body (pose from bodies.csv at the snapshot's
/// time); fails when there is any.
/// The time step never fell below kTimeStepDrop (1e-3) of the case's own (summary.json's
/// time_step.dt_min_ratio): a step that collapses is a defect even where the run reaches its end.
std::vector<ValidationCheck> check_time_step_held(const std::filesystem::path& run_dir);

std::vector<ValidationCheck> check_fluid_contained(const std::filesystem::path& run_dir, const Case& c,
                                                   double depth = 0.5);
/// Kinetic energy of the free bodies (translation and rotation): its mean over the rows of the last
/// `window` seconds of the run, over its peak, must be below `max_fraction` (the bodies came to
/// rest). A mean, not the last row: a pile that is still rearranging fluctuates by a factor of 2-3
/// from one row to the next (settling_pile: 1.6 % to 3.4 % of the peak within 0.15 s).
std::vector<ValidationCheck> check_kinetic_energy_decay(const std::filesystem::path& run_dir, const Case& c,
                                                        double max_fraction, double window = 0.1);
/// At the end every free body lies within `max_gap_m` metres of a wall or another body (it rests
/// on something). A distance, not a multiple of d0: the film under a resting body drains at the
/// rate its viscosity and load set, whatever the resolution, so a threshold of 1 d0 halved with d0
/// asked the fine level for twice the drainage in the same time (rising_lid at d0 = 5e-5 m: a
/// triangle 56 um under the lid, still closing on it at 0.2 mm/s, at 1.5 s).
std::vector<ValidationCheck> check_bodies_touching(const std::filesystem::path& run_dir, const Case& c,
                                                   double max_gap_m);
/// A body (index `body`) dropped onto wall `wall`: the ratio of the rebound speed (largest speed
/// away from the wall after the closest approach) to the impact speed (speed towards the wall
/// when the gap first falls below 1 d0) against the restitution coefficient of the case
/// (collision.restitution of the resolved case.toml, 0.8 when the key does not exist), within
/// `rel_tol`.
std::vector<ValidationCheck> check_rebound(const std::filesystem::path& run_dir, const Case& c, std::size_t body,
                                           std::size_t wall, double rel_tol);
/// A block (body `block`) on a fixed slope (body `slope`, whose longest edge is the slope): it
/// slides down at least `min_slide` m, stays on the slope (gap at the end within 1 d0, no
/// tumbling) and never moves faster along the slope than frictionless sliding without drag.
std::vector<ValidationCheck> check_incline_slide(const std::filesystem::path& run_dir, const Case& c,
                                                 std::size_t block, std::size_t slope, double min_slide);
/// A fixed cylinder (body 0) in a periodic channel driven by fluid.body_force: the x momentum
/// balance (cylinder drag + wall shear = rho f A_fluid) over the last `window` fraction of the
/// run, the Reynolds number of the mean fluid speed against `re_nominal` (within a factor 1.5),
/// and either a steady drag (`shedding` false: drift of the drag over the window below 2 %) or
/// a lift that oscillates (`shedding` true: at least two periods, amplitude above 5 % of the
/// drag); the drag coefficient and the Strouhal number are reported.
std::vector<ValidationCheck> check_channel_cylinder(const std::filesystem::path& run_dir, const Case& c,
                                                    double re_nominal, bool shedding, double window);
/// A suspension sheared between the walls at domain.min.y and domain.max.y (periodic in x): the
/// strain reached (at least `min_strain`), the relative viscosity (mean wall shear stress over
/// the second half of the run / (mu gamma)) within [lo, hi], and the two walls' forces
/// balancing (their sum within 10 % of either); `reference` is what the report shows as the
/// expected relative viscosity.
std::vector<ValidationCheck> check_sheared_suspension(const std::filesystem::path& run_dir, const Case& c,
                                                      double min_strain, double lo, double hi,
                                                      const std::string& reference = "about 2.5 (2D Krieger-Dougherty at 0.35)");
/// A dilute suspension of circles sheared as above: those checks (relative viscosity within
/// [1, 1 + 4 phi]) and the intrinsic viscosity (mu_r - 1) / phi against the 2D Einstein value 2
/// (within [1, 3]), mu_r the mean over the second half with its standard error from 10 block
/// means. phi = the circles' area over the domain's.
std::vector<ValidationCheck> check_dilute_viscosity(const std::filesystem::path& run_dir, const Case& c,
                                                    double min_strain);
/// Two prescribed bodies (0 and 1) pushed together and pulled apart along x: the smallest gap
/// against `target_gap` d0 (within 0.02 d0), the force on body 0 resisting the approach while
/// they close and holding them together while they part (lubrication and suction).
std::vector<ValidationCheck> check_prescribed_squeeze(const std::filesystem::path& run_dir, const Case& c,
                                                      double target_gap);

// Bodies with open boundaries (robustness_open.cpp; cases/fluidized_bed.toml, particle_channel.toml).
/// A bed of free bodies on the screen of inlet 0, fluidized by its inflow: no body ever below the
/// screen (by more than 0.25 d0); the bed height H = 2 (mean centre height above the screen)
/// expanded by at least `min_expansion` over the densest packing's height N A / (W phi_max),
/// phi_max = 0.82 (2D random close packing of discs), and steady over the last third of the run
/// (the drift of a fitted line below 5 % of H, the fluctuation about it below 5 %); the change of
/// the fluid mass (reported); the mass balance of the open boundaries.
std::vector<ValidationCheck> check_fluidized_bed(const std::filesystem::path& run_dir, const Case& c,
                                                 double min_expansion);
/// Free bodies carried by the flow from inlet 0 towards outlet 0: each moved at least
/// `min_travel` along the flow, none ever past the outlet's screen (by more than 0.25 d0), the
/// leading one held at the screen at the end (within the contact distance + d0); the fluid mass
/// at the end within 1 % of its start (a clogged screen behind a velocity inlet compresses the
/// fluid); the mass balance.
std::vector<ValidationCheck> check_particle_channel(const std::filesystem::path& run_dir, const Case& c,
                                                    double min_travel);

}  // namespace particula
