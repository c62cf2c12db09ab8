#include "python/bindings.h"
#include "sim/config/config_error.h"
#include "sim/integrator.h"
#include "sim/parameters.h"
#include "tcpmsim/version.h"

namespace py = pybind11;

namespace tcpmsim::python {

double number_argument(const py::handle& value, const std::string& what,
                       const std::string& expected) {
  if (!py::isinstance<py::float_>(value) && !py::isinstance<py::int_>(value) &&
      !py::hasattr(value, "__float__"))
    throw py::type_error(what + ": expected " + expected + ", got " +
                         py::repr(value).cast<std::string>());
  return py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>();
}

// The command line's errors as Python exceptions with the same message: a bad config value
// (file:line:column or the set's path, the key, what was expected) is a ConfigError; a unit
// udunits cannot read a UnitError; a parameter outside its range a ParameterError; all three
// are ValueErrors. A run the solver gave up raises SolverFailure (a RuntimeError).
void bind_errors(py::module_& module) {
  const auto& config_error =
      py::register_exception<ConfigError>(module, "ConfigError", PyExc_ValueError);
  py::register_exception<UnitError>(module, "UnitError", config_error.ptr());
  py::register_exception<ParameterError>(module, "ParameterError", config_error.ptr());
  py::register_exception<UsageError>(module, "UsageError", PyExc_ValueError);
  // Raised by Scenario.run when the solver gives up; its `result` holds the samples before.
  py::register_exception<SolverFailure>(module, "SolverFailure", PyExc_RuntimeError);
}

}  // namespace tcpmsim::python

PYBIND11_MODULE(_core, module) {
  module.doc() = "tcpmsim's C++ engine: scenarios, runs in memory, records.";
  module.attr("__version__") = tcpmsim::kVersion;
  module.attr("git_commit") = tcpmsim::kGitCommit;
  tcpmsim::python::bind_errors(module);
  tcpmsim::python::bind_scenario(module);
  tcpmsim::python::bind_result(module);
  tcpmsim::python::bind_analysis(module);
  tcpmsim::python::bind_control_task(module);
  tcpmsim::python::bind_simulator(module);
}
