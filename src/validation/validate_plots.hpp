// The figures of the validation cases (validate_plots.cpp), set as ValidationEntry::plot.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "particula/case/case.hpp"
#include "particula/validation/validate.hpp"

namespace particula {

/// vx(y) of probe_profile.csv at its last output against the probe's exact column (start-up
/// Couette and Poiseuille flow).
ValidationPlot plot_probe_profile(const std::filesystem::path& run_dir, const Case& c);
/// vx(y) of probe_profile.csv at its last output against the inflow's parabola (poiseuille_open).
ValidationPlot plot_open_profile(const std::filesystem::path& run_dir, const Case& c);
/// The peak fluid speed of each snapshot over U against exp(-8 pi^2 nu t / L^2).
ValidationPlot plot_taylor_green(const std::filesystem::path& run_dir, const Case& c);
/// The mean fluid pressure of each lattice row of the last snapshot against p0 + rho g (H - y).
ValidationPlot plot_hydrostatic(const std::filesystem::path& run_dir, const Case& c);
/// The torque on the turning container (walls.csv) against the Bessel series.
ValidationPlot plot_spin_up(const std::filesystem::path& run_dir, const Case& c);
/// C_D and C_L of coefficients.csv against time (the DFG benchmarks).
ValidationPlot plot_force_coefficients(const std::filesystem::path& run_dir, const Case& c);

/// A column of bodies.csv for some bodies against time, with published curves of reference/.
struct BodyCurve {
  std::string title, y_label;
  std::string column;      // x, y, vx, vy, angle or omega
  std::vector<int> bodies;  // indices in the case
  struct Reference {
    std::string label, file, column;
    int body = -1;  // the rows of this body of the file (-1: all)
  };
  std::vector<Reference> references;
};
ValidationPlot plot_body_curve(const std::filesystem::path& run_dir, const BodyCurve& spec);

}  // namespace particula
