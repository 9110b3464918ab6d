// Plots of a run directory, drawn by tools/plot_run.py with Debian's python3 and matplotlib.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace particula {

enum class PlotOutcome { Drawn, NoMatplotlib, NoScript, Failed, Interrupted };

/// The images tools/plot_run.py may draw into DIR/plots for a case with the probes `probes`:
/// probe_<name>_profiles.png, probe_<name>_error.png and probe_<name>_points.png of each probe,
/// flow_rates.png, bodies.png, coefficients.png and snapshot_fields.png.
std::vector<std::string> plot_file_names(const std::vector<std::string>& probes);

/// The Python interpreter used for plots: /usr/bin/python3 when it exists (Debian's, where
/// python3-matplotlib installs), else the first python3 on the PATH.
std::string plot_python();

/// Runs tools/plot_run.py on `run_dir`, appending its output to `log_file` (empty: the
/// script writes to this process's stdout and stderr). With `stop`, polled while the script
/// runs: when it returns true the script is terminated (Interrupted).
PlotOutcome draw_plots(const std::filesystem::path& run_dir, const std::filesystem::path& log_file = {},
                       const std::function<bool()>& stop = {});

/// `particula plot DIR`: exit 2 when DIR is not a run directory or matplotlib is missing,
/// 1 when the script fails, 0 when the plots are in DIR/plots.
int plot_command(const std::filesystem::path& run_dir);

}  // namespace particula
