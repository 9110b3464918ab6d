// particula._core.run_command / resume_command: the CLI's `particula run` and `particula resume`
// (src/run/runner.cpp), called in-process with the same options, so a run directory made from
// Python is the one the CLI makes. The runner reports on standard error and answers with the
// CLI's exit code; both come back to Python, which raises the matching exception
// (particula/commands.py).
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>
#include <unistd.h>

#include <cstdio>
#include <mutex>
#include <optional>
#include <string>
#include <utility>

#include "bindings.hpp"
#include "particula/case/load.hpp"
#include "particula/run/runner.hpp"

namespace py = pybind11;
namespace fs = std::filesystem;

namespace particula::python {

namespace {

/// Standard error (file descriptor 2) redirected into a temporary file while it lives: the
/// runner writes its messages there with fprintf, and Python gets them back as text (to raise
/// with the CLI's message, and to print where Python prints, e.g. in a notebook).
class CapturedStderr {
 public:
  CapturedStderr() {
    std::fflush(stderr);
    file_ = std::tmpfile();
    saved_ = dup(2);
    if (!file_ || saved_ < 0 || dup2(fileno(file_), 2) < 0) restore();  // not captured: still runs
  }
  ~CapturedStderr() {
    restore();
    if (file_) std::fclose(file_);
  }
  CapturedStderr(const CapturedStderr&) = delete;
  CapturedStderr& operator=(const CapturedStderr&) = delete;

  /// Ends the capture and returns what was written.
  std::string text() {
    restore();
    std::string out;
    if (!file_) return out;
    std::rewind(file_);
    char buf[4096];
    for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, file_)) > 0;) out.append(buf, n);
    return out;
  }

 private:
  void restore() {
    if (saved_ < 0) return;
    std::fflush(stderr);
    dup2(saved_, 2);
    close(saved_);
    saved_ = -1;
  }
  std::FILE* file_ = nullptr;
  int saved_ = -1;
};

/// One command at a time per process: the capture is of the process's file descriptor 2, and
/// the runner's signal handlers and OpenMP thread count are process-wide (run cases in parallel
/// in separate processes).
std::mutex g_command;

/// Runs `command` without the GIL, standard error captured: (exit code, what it wrote there).
template <class F>
std::pair<int, std::string> captured(F command) {
  py::gil_scoped_release nogil;
  std::lock_guard<std::mutex> lock(g_command);
  CapturedStderr capture;
  const int code = command();
  return {code, capture.text()};
}

/// A Python progress callable as the runner's ProgressCallback: called with the GIL as
/// callback(time, t_end, step); an exception it raises stops the run (as Ctrl-C would: outputs
/// and a checkpoint written) and is kept in `raised` to be raised again once the run has ended.
class PythonProgress {
 public:
  explicit PythonProgress(py::object callback) : callback_(std::move(callback)) {}
  ProgressCallback callback() {
    if (callback_.is_none()) return {};
    return [this](double t, double t_end, std::int64_t step) {
      py::gil_scoped_acquire gil;
      try {
        callback_(t, t_end, step);
        return true;
      } catch (py::error_already_set& e) {
        raised_ = std::move(e);
        return false;
      }
    };
  }
  /// Raises what the callable raised, if it did (with the GIL held).
  void raise_if_raised() {
    if (raised_) {
      py::error_already_set e = std::move(*raised_);
      raised_.reset();
      throw e;
    }
  }

 private:
  py::object callback_;
  std::optional<py::error_already_set> raised_;
};

std::pair<int, std::string> run(const fs::path& case_file, const fs::path& out,
                                const std::vector<std::string>& overrides, int threads,
                                const std::string& backend, bool overwrite, bool quiet, bool plots,
                                std::optional<std::string> case_text, py::object progress) {
  RunOptions opt;
  opt.out_dir = out;
  opt.overrides = overrides;
  opt.threads = threads;
  opt.backend = backend;
  opt.overwrite = overwrite;
  opt.quiet = quiet;
  opt.plots = plots;
  opt.case_text = std::move(case_text);
  PythonProgress tell(std::move(progress));
  opt.progress = tell.callback();
  check_threads(threads);
  auto result = captured([&] { return run_command(case_file, opt); });
  tell.raise_if_raised();
  return result;
}

std::pair<int, std::string> resume(const fs::path& dir, const std::vector<std::string>& overrides,
                                   int threads, const std::string& backend, bool quiet, bool plots,
                                   py::object progress) {
  ResumeOptions opt;
  opt.run_dir = dir;
  opt.overrides = overrides;
  opt.threads = threads;
  opt.backend = backend;
  opt.quiet = quiet;
  opt.plots = plots;
  PythonProgress tell(std::move(progress));
  opt.progress = tell.callback();
  check_threads(threads);
  auto result = captured([&] { return resume_command(opt); });
  tell.raise_if_raised();
  return result;
}

}  // namespace

void register_commands(py::module_& m) {
  m.def(
      "resolved_case",
      [](const fs::path& file, const std::vector<std::string>& overrides) {
        return resolved_case_toml(load_case(file, overrides));
      },
      py::arg("case_file"), py::arg("overrides"),
      "load_case: the resolved case as TOML text (raises CaseError)");
  m.def(
      "resolved_case_text",
      [](const std::string& text, const fs::path& source, const std::vector<std::string>& overrides) {
        return resolved_case_toml(load_case_text(text, source, overrides));
      },
      py::arg("text"), py::arg("source"), py::arg("overrides"),
      "a case's TOML text resolved as load_case resolves a file (raises CaseError naming `source`)");
  m.def("run_command", &run, py::arg("case_file"), py::arg("out"), py::arg("overrides"), py::arg("threads"),
        py::arg("backend"), py::arg("overwrite"), py::arg("quiet"), py::arg("plots"),
        py::arg("case_text") = std::nullopt, py::arg("progress") = py::none(),
        "`particula run`: (exit code, standard error text)");
  m.def("resume_command", &resume, py::arg("run_dir"), py::arg("overrides"), py::arg("threads"),
        py::arg("backend"), py::arg("quiet"), py::arg("plots"), py::arg("progress") = py::none(),
        "`particula resume`: (exit code, standard error text)");
}

}  // namespace particula::python
