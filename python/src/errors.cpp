// The library's exceptions as the Python classes of particula/errors.py, with the CLI's
// messages: bad input (exit code 2) as InputError (a ValueError), a case-file mistake as its
// subclass CaseError with the file, line and key; a file-system failure while writing (exit 4)
// as IoFailure (an OSError); a numerical failure (exit 3) as NumericalFailure.
#include <fmt/format.h>

#include "bindings.hpp"
#include "particula/case/error.hpp"
#include "particula/io/error.hpp"
#include "particula/run/run_dir.hpp"

namespace py = pybind11;

namespace particula::python {

StepFailure::StepFailure(const Failure& f, real t, std::int64_t s)
    : std::runtime_error(fmt::format("numerical failure at t = {:.9g} s, step {}: {} at ({:.6g}, {:.6g})", t,
                                     s, f.what, f.position.x, f.position.y)),
      failure(f),
      time(t),
      step(s) {}

StepFailure::StepFailure(const std::string& message, const StepFailure& cause)
    : std::runtime_error(message), failure(cause.failure), time(cause.time), step(cause.step) {}

namespace {

/// Raises particula.errors.<name>(*args, **kwargs) as the current Python error.
void raise(const char* name, const py::tuple& args, const py::dict& kwargs = py::dict()) {
  const py::object cls = py::module_::import("particula.errors").attr(name);
  const py::object error = cls(*args, **kwargs);
  PyErr_SetObject(cls.ptr(), error.ptr());
}

void translate(std::exception_ptr p) {
  try {
    if (p) std::rethrow_exception(p);
  } catch (const CaseError& e) {
    raise("CaseError", py::make_tuple(e.what()),
          py::dict(py::arg("file") = e.file(), py::arg("line") = e.line(), py::arg("key") = e.key(),
                   py::arg("message") = e.message()));
  } catch (const io::WriteError& e) {  // before IoError, of which it is a kind
    raise("IoFailure", py::make_tuple(e.what()));
  } catch (const io::IoError& e) {
    raise("InputError", py::make_tuple(e.what()));
  } catch (const RunDirRefused& e) {
    raise("InputError", py::make_tuple(e.what()));
  } catch (const UsageError& e) {
    raise("InputError", py::make_tuple(e.what()));
  } catch (const StepFailure& e) {
    raise("NumericalFailure", py::make_tuple(e.what()),
          py::dict(py::arg("time") = e.time, py::arg("step") = e.step,
                   py::arg("particle_id") = e.failure.particle_id,
                   py::arg("position") = py::make_tuple(e.failure.position.x, e.failure.position.y),
                   py::arg("reason") = e.failure.what));
  }
}

}  // namespace

void register_errors(py::module_& /*m*/) { py::register_exception_translator(&translate); }

}  // namespace particula::python
