// Helpers shared by the robustness checks: robustness.cpp (the checks every case shares) and
// robustness_cases.cpp (the case-specific checks and the entries). Internal to src/validation.
#pragma once

#include <filesystem>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "particula/case/case.hpp"
#include "particula/geometry/shape.hpp"
#include "particula/io/csv.hpp"
#include "particula/validation/robustness.hpp"
#include "particula/validation/validate.hpp"
#include "particula/scene/scene.hpp"

namespace particula::robustness_support {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

ValidationCheck make_check(std::string quantity, double value, std::string shown, std::string reference,
                           std::string tolerance, bool pass);
/// A row of the report with no pass/fail verdict.
ValidationCheck report(std::string quantity, double value, std::string shown);

/// a - b, through the nearest periodic image along periodic axes.
Vec2 separation(const Case& c, Vec2 a, Vec2 b);

/// The shapes of a case's bodies and their surface samples, built once per check (samples at
/// d0/4, fine enough to see an overlap of a tenth of d0 between two flat sides).
struct BodyGeometry {
  std::vector<Shape> shapes;
  std::vector<std::vector<SurfaceSample>> samples;
  explicit BodyGeometry(const Case& c) {
    for (const BodySpec& b : c.bodies) {
      shapes.push_back(body_shape(b));
      samples.push_back(shapes.back().sample_surface(c.d0 / 4));
    }
  }
};

/// Signed distance of world point p to a body of shape s placed at (pos, angle).
double distance_to_body(const Case& c, const Shape& s, Vec2 pos, double angle, Vec2 p);
/// Smallest gap between bodies a and b (sampled surfaces; the bounding circles' gap when far).
double gap_between(const Case& c, const BodyGeometry& g, std::size_t a, Vec2 pa, double aa, std::size_t b,
                   Vec2 pb, double ab);
/// Smallest distance of body a's samples over wall w, on the fluid's side.
double gap_to_wall(const BodyGeometry& g, std::size_t a, Vec2 pa, double aa, const WallSpec& w);

/// Index of the row of `tr` at time t (the nearest row; the checks read rows written together).
std::size_t row_at(const BodyTrack& tr, double t);
bool moving(const BodySpec& b);
/// Rows common to every body (bodies.csv writes all bodies at each output time).
std::size_t common_rows(const std::vector<BodyTrack>& tracks);
/// Every body's track; throws io::IoError with fewer than two rows per body.
std::vector<BodyTrack> tracks_or_throw(const std::filesystem::path& run_dir, const Case& c);

/// Rows of walls.csv: per wall, time and force.
struct WallTrack {
  std::vector<double> t, fx, fy;
  std::vector<double> fdx, fdy;  // the odd-even damping's sink (zeros for a file without the columns)
};

/// The value of column `name` in row r of `table`, 0 when the file has no such column (a
/// bodies.csv or walls.csv without the fdx, fdy columns of the odd-even damping's sink).
double column_or_zero(const io::CsvTable& table, const std::vector<double>& r, std::string_view name);

std::vector<WallTrack> read_wall_tracks(const std::filesystem::path& run_dir, std::size_t walls);
/// Mean of y over the samples with t >= from.
double mean_from(const std::vector<double>& t, const std::vector<double>& y, double from);
/// The least-squares line y = intercept + slope t through the samples with t >= from, and the
/// root mean square of the residuals about it.
struct LineFit {
  double slope = 0, intercept = 0, rms = 0;
  std::size_t n = 0;
};
LineFit fit_line_from(const std::vector<double>& t, const std::vector<double>& y, double from);
/// The restitution coefficient of the resolved case (0.8 by default, NaN for the P.38 model).
double restitution(const std::filesystem::path& run_dir);
/// The wall at y = `y` spanning the domain (the channel and Couette cases).
std::size_t wall_at_y(const Case& c, double y);

}  // namespace particula::robustness_support
