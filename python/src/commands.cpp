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

std::pair<int, std::string> run(const fs::path& case_file, const fs::path& out,
                                const std::vector<std::string>& overrides, int threads,
                                const std::string& backend, bool overwrite, bool quiet, bool plots) {
  RunOptions opt;
  opt.out_dir = out;
  opt.overrides = overrides;
  opt.threads = threads;
  opt.backend = backend;
  opt.overwrite = overwrite;
  opt.quiet = quiet;
  opt.plots = plots;
  check_threads(threads);
  return captured([&] { return run_command(case_file, opt); });
}

std::pair<int, std::string> resume(const fs::path& dir, const std::vector<std::string>& overrides,
                                   int threads, const std::string& backend, bool quiet, bool plots) {
  ResumeOptions opt;
  opt.run_dir = dir;
  opt.overrides = overrides;
  opt.threads = threads;
  opt.backend = backend;
  opt.quiet = quiet;
  opt.plots = plots;
  check_threads(threads);
  return captured([&] { return resume_command(opt); });
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
  m.def("run_command", &run, py::arg("case_file"), py::arg("out"), py::arg("overrides"), py::arg("threads"),
        py::arg("backend"), py::arg("overwrite"), py::arg("quiet"), py::arg("plots"),
        "`particula run`: (exit code, standard error text)");
  m.def("resume_command", &resume, py::arg("run_dir"), py::arg("overrides"), py::arg("threads"),
        py::arg("backend"), py::arg("quiet"), py::arg("plots"),
        "`particula resume`: (exit code, standard error text)");
}

}  // namespace particula::python
