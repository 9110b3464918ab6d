// Checks of the cases with bodies and open boundaries (robustness.hpp): a bed fluidized from
// below on its inlet's screen, and bodies carried through a channel to its outlet's screen.
// Heights and distances are measured along the open boundary's inward normal from its line.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "particula/io/csv.hpp"
#include "particula/io/error.hpp"
#include "particula/validation/robustness.hpp"
#include "robustness_support.hpp"

namespace particula {

namespace fs = std::filesystem;
using namespace robustness_support;

namespace {

/// Distance of x from an open boundary's line, into the fluid.
double depth_from(const OpenSpec& o, Vec2 x) { return dot(o.inward_normal(), x - o.from); }

/// The fluid mass at the end of open_boundaries.csv against that at t = 0, less one: the mean
/// density change of the fluid in the fixed domain.
double fluid_mass_change(const fs::path& run_dir) {
  const io::CsvTable t = io::read_csv(run_dir / "open_boundaries.csv");
  const std::size_t im = t.column_index("fluid_mass");
  if (t.rows.empty()) throw io::IoError(fmt::format("'{}': no rows", t.source.string()));
  return t.rows.back()[im] / t.rows.front()[im] - 1;
}

/// The body's extent along n from its centre (a circle's radius; otherwise its bounding radius,
/// which overstates it: the checks then err towards failing).
double reach_along(const BodySpec& b) {
  return b.shape == BodyShape::Circle ? b.radius : body_shape(b).bounding_radius();
}

}  // namespace

std::vector<ValidationCheck> check_fluidized_bed(const fs::path& run_dir, const Case& c, double min_expansion) {
  const std::vector<BodyTrack> tracks = tracks_or_throw(run_dir, c);
  const OpenSpec& in = c.inlets.at(0);
  const double screen = c.open_screen_offset(in), W = in.width();
  const std::size_t rows = common_rows(tracks);
  if (rows < 3) throw io::IoError(fmt::format("'{}': fewer than 3 rows in bodies.csv", run_dir.string()));
  // the lowest body surface over the run, and the bed height at each row
  double lowest = kInf, t_lowest = 0, area = 0;
  for (const BodySpec& b : c.bodies) area += body_shape(b).area();
  std::vector<double> t(rows), H(rows);
  for (std::size_t k = 0; k < rows; ++k) {
    double mean = 0;
    for (std::size_t b = 0; b < tracks.size(); ++b) {
      const double d = depth_from(in, {tracks[b].x[k], tracks[b].y[k]});
      mean += d;
      const double bottom = d - reach_along(c.bodies[b]);
      if (bottom < lowest) lowest = bottom, t_lowest = tracks[b].t[k];
    }
    mean /= static_cast<double>(tracks.size());
    t[k] = tracks[0].t[k];
    H[k] = 2 * (mean - screen);
  }
  const double packed = area / (W * 0.82);
  const double from = t.front() + (t.back() - t.front()) * 2.0 / 3.0;
  const LineFit fit = fit_line_from(t, H, from);
  const double H_end = mean_from(t, H, from);
  const double drift = std::fabs(fit.slope * (t.back() - from)) / H_end, wobble = fit.rms / H_end;
  std::vector<ValidationCheck> out;
  out.push_back(make_check("lowest body surface above the inlet's screen over the run (d0)", (lowest - screen) / c.d0,
                           fmt::format("{:.3f} at t = {:.4g} s (screen {:.3g} m inside the inlet)",
                                       (lowest - screen) / c.d0, t_lowest, screen),
                           "on or above the screen (no body leaves through the inlet)", ">= -0.25",
                           lowest - screen >= -0.25 * c.d0));
  out.push_back(make_check(
      "bed height 2 (mean centre height above the screen), last third / densest packing's height", H_end / packed,
      fmt::format("{:.3f} (H = {:.4g} m; N A / (W 0.82) = {:.4g} m; H at t = 0: {:.4g} m)", H_end / packed, H_end,
                  packed, H.front()),
      "> 1: the flow carries the bed", fmt::format(">= {:.3g}", 1 + min_expansion), H_end / packed >= 1 + min_expansion));
  out.push_back(make_check("bed height over the last third: drift of a fitted line / H; fluctuation about it / H",
                           drift, fmt::format("{:.3g}; {:.3g}", drift, wobble), "0 (a steady height)",
                           "drift < 5 %, fluctuation < 5 %", drift < 0.05 && wobble < 0.05));
  const double dm = fluid_mass_change(run_dir);
  out.push_back(report("fluid mass at the end / at t = 0 - 1 (the mean density change; an open defect, "
                       "docs/method.md, \"Open boundaries\")",
                       dm, fmt::format("{:+.3g}", dm)));
  out.push_back(open_mass_balance_check(run_dir, c));
  return out;
}

std::vector<ValidationCheck> check_particle_channel(const fs::path& run_dir, const Case& c, double min_travel) {
  const std::vector<BodyTrack> tracks = tracks_or_throw(run_dir, c);
  const OpenSpec& in = c.inlets.at(0);
  const OpenSpec& outlet = c.outlets.at(0);
  // the outlet's screen as a distance from the inlet's line, along the inlet's normal
  const double screen_out = depth_from(in, outlet.from) - c.open_screen_offset(outlet);
  double least_travel = kInf, furthest = -kInf, t_furthest = 0, lead_end = -kInf;
  std::size_t slowest = 0;
  for (std::size_t b = 0; b < tracks.size(); ++b) {
    const BodyTrack& tr = tracks[b];
    if (tr.size() == 0) continue;
    const double r = reach_along(c.bodies[b]);
    const double travel = depth_from(in, {tr.x.back(), tr.y.back()}) - depth_from(in, {tr.x[0], tr.y[0]});
    if (travel < least_travel) least_travel = travel, slowest = b;
    for (std::size_t k = 0; k < tr.size(); ++k) {
      const double front = depth_from(in, {tr.x[k], tr.y[k]}) + r;
      if (front > furthest) furthest = front, t_furthest = tr.t[k];
    }
    lead_end = std::max(lead_end, depth_from(in, {tr.x.back(), tr.y.back()}) + r);
  }
  std::vector<ValidationCheck> out;
  out.push_back(make_check("least distance a body was carried along the channel (m)", least_travel,
                           fmt::format("{:.4g} (body '{}')", least_travel, c.bodies.at(slowest).name),
                           "every body carried downstream", fmt::format(">= {:.3g}", min_travel),
                           least_travel >= min_travel));
  out.push_back(make_check("furthest body front past the outlet's screen over the run (d0)",
                           (furthest - screen_out) / c.d0,
                           fmt::format("{:+.3f} at t = {:.4g} s", (furthest - screen_out) / c.d0, t_furthest),
                           "<= 0 (the screen holds the bodies)", "<= 0.25", furthest - screen_out <= 0.25 * c.d0));
  const double lead_gap = screen_out - lead_end;
  out.push_back(make_check("leading body's gap to the outlet's screen at the end (d0)", lead_gap / c.d0,
                           fmt::format("{:.3f}", lead_gap / c.d0), "held at the screen",
                           fmt::format("<= {:.3g} (contact distance + d0)", c.contact_distance() / c.d0 + 1),
                           lead_gap <= c.contact_distance() + c.d0));
  // the flow still passes the screen: a queue of bodies clogging it behind a velocity inlet
  // would compress the fluid (exactly what the mass balance allows)
  const double dm = fluid_mass_change(run_dir);
  out.push_back(make_check("fluid mass at the end / at t = 0 - 1 (the mean density change)", dm,
                           fmt::format("{:+.3g}", dm), "0 (incompressible)", "within 1 %", std::fabs(dm) < 0.01));
  out.push_back(open_mass_balance_check(run_dir, c));
  return out;
}

}  // namespace particula
