// Plots of a run directory, drawn by tools/plot_run.py with Debian's python3 and matplotlib.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace particula {

enum class PlotOutcome { Drawn, NoMatplotlib, NoScript, Failed, Interrupted };

/// The image formats tools/plot_run.py draws (`particula plot --format`), the first the default.
const std::vector<std::string>& plot_formats();

/// The images tools/plot_run.py may draw into DIR/plots for a case with the probes `probes`, in
/// each of plot_formats(): probe_<name>_profiles, probe_<name>_error and probe_<name>_points of
/// each probe, flow_rates, bodies, coefficients and snapshot_fields (e.g. bodies.png, bodies.svg).
std::vector<std::string> plot_file_names(const std::vector<std::string>& probes);

/// The Python interpreter used for plots: /usr/bin/python3 when it exists (Debian's, where
/// python3-matplotlib installs), else the first python3 on the PATH.
std::string plot_python();

/// Runs tools/plot_run.py on `run_dir`, appending its output to `log_file` (empty: the
/// script writes to this process's stdout and stderr). With `stop`, polled while the script
/// runs: when it returns true the script is terminated (Interrupted). `format` is one of
/// plot_formats().
PlotOutcome draw_plots(const std::filesystem::path& run_dir, const std::filesystem::path& log_file = {},
                       const std::function<bool()>& stop = {}, const std::string& format = "png");

/// `particula plot DIR [--format FORMAT]`: exit 2 when DIR is not a run directory, FORMAT is not
/// one of plot_formats() or matplotlib is missing (nothing drawn), 1 when the script fails, 0
/// when the plots are in DIR/plots.
int plot_command(const std::filesystem::path& run_dir, const std::string& format = "png");

}  // namespace particula
