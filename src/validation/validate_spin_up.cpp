// Validation of the spin-up of fluid in a circular container (cases/spin_up.toml): the torque
// of the fluid on the turning container against the exact Bessel series, and the velocity
// error of every fluid particle.
#include <fmt/format.h>

#include <cmath>

#include "particula/analytic/solutions.hpp"
#include "particula/io/csv.hpp"
#include "particula/validation/validate.hpp"

namespace particula {

std::vector<ValidationCheck> check_spin_up(const std::filesystem::path& run_dir, const Case& c, double torque_tol,
                                           double profile_limit) {
  std::vector<ValidationCheck> out = check_profile_error(run_dir, profile_limit);
  out.front().quantity = "L2 error of the velocity (fluid particles, % of omega R) at time.end";
  const WallSpec& w = c.walls.at(0);
  const auto exact = [&](double t) { return analytic::spin_up_torque(t, w.radius, w.omega, c.mu(), c.nu); };
  // The window: from the time the series' first terms dominate to where the torque has decayed
  // (the torque falls as exp(-lambda_1^2 nu t/R^2); late values are round-off of a vanishing load).
  const double scale = w.radius * w.radius / c.nu;
  const double t0 = 0.02 * scale, t1 = 0.15 * scale, floor = 0.05 * std::fabs(exact(0.01 * scale));
  const io::CsvTable table = io::read_csv(run_dir / "walls.csv");
  const std::size_t it = table.column_index("time"), iq = table.column_index("torque");
  double worst = 0, at = 0;
  int n = 0;
  for (const auto& r : table.rows) {
    const double t = r[it], ref = exact(t);
    if (t < t0 - 1e-12 || t > t1 + 1e-12 || std::fabs(ref) < floor) continue;
    const double e = r[iq] / ref - 1;
    if (!(std::fabs(e) <= std::fabs(worst))) worst = e, at = t;  // NaN is kept as the worst
    ++n;
  }
  ValidationCheck q;
  q.quantity = fmt::format("torque on the container / exact, worst of {} times in [{:.3g}, {:.3g}] s", n, t0, t1);
  q.value = worst;
  q.shown = fmt::format("{:+.2f} % (t = {:.3g} s)", 100 * worst, at);
  q.reference = "-4 pi mu omega R^2 sum exp(-lambda_n^2 nu t/R^2)";
  q.tolerance = fmt::format("within {:.3g} %", 100 * torque_tol);
  q.pass = n > 0 && std::fabs(worst) <= torque_tol;
  q.error = worst;
  out.push_back(q);
  return out;
}

}  // namespace particula
