// particula._core: see bindings.hpp.
#include "bindings.hpp"

PYBIND11_MODULE(_core, m) {
  m.doc() = "particula's C++ solver (use the package `particula`, which wraps this module)";
  particula::python::register_errors(m);
  particula::python::register_simulation(m);
  particula::python::register_commands(m);
}
