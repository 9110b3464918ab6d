// The pybind11 extension particula._core: the C++ library behind the Python package `particula`
// (python/particula). Each part registers itself on the module; the Python package wraps them.
#pragma once

#include <pybind11/pybind11.h>

#include <cstdint>
#include <stdexcept>
#include <string>

#include "particula/solver/solver.hpp"

namespace particula::python {

/// A wrong argument from Python (an unknown backend, a --set key `resume` may not change):
/// raised as particula.InputError, like the CLI's exit code 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A numerical failure at the end of a step (the CLI's exit code 3): raised as
/// particula.NumericalFailure with the CLI's message and the failure's time, step and particle.
class StepFailure : public std::runtime_error {
 public:
  StepFailure(const Failure& f, real time, std::int64_t step);
  /// The same failure with another message (a Simulation refusing to step after it).
  StepFailure(const std::string& message, const StepFailure& cause);
  Failure failure;
  real time;
  std::int64_t step;
};

/// Throws UsageError unless `threads` is 0 (OpenMP's default team, itself checked:
/// default_threads_problem) or within [1, kMaxThreads].
void check_threads(int threads);

/// Maps the library's exceptions to the classes of particula/errors.py.
void register_errors(pybind11::module_& m);
/// particula._core.Simulation: a case built into a solver, stepped from Python.
void register_simulation(pybind11::module_& m);
/// particula._core.run_command / resume_command: the CLI's `run` and `resume`.
void register_commands(pybind11::module_& m);

}  // namespace particula::python
