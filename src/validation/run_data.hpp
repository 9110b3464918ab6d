// Reading what a validation run wrote (snapshots, bodies.csv) and the published curves of
// reference/: shared by the checks (validate.cpp) and the figures (validate_plots.cpp).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "particula/io/vtk.hpp"

namespace particula {

/// The last snapshot of a run directory (particles.pvd's last entry); `time` is set to its time.
io::VtpData last_snapshot(const std::filesystem::path& run_dir, double& time);

/// Largest speed of the fluid particles of a snapshot.
double peak_fluid_speed(const io::VtpData& vtp);

/// One body's rows of bodies.csv.
struct BodyHistory {
  std::vector<double> t, x, y, angle, vx, vy, omega;
  std::size_t size() const { return t.size(); }
};

/// The rows of body `body` (its index in the case); throws io::IoError with fewer than two.
BodyHistory body_history(const std::filesystem::path& run_dir, int body);

/// A reference curve of reference/ (columns t and `column`, optionally only the rows of one body).
struct Curve {
  std::vector<double> t, v;
};

Curve reference_curve(const std::string& file, const std::string& column, int body = -1);

}  // namespace particula
