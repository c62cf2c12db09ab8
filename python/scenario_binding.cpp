#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <thread>

#include "kinds/standard_kinds.h"
#include "python/bindings.h"
#include "sim/config/config_error.h"
#include "sim/run.h"
#include "sim/value_check.h"
#include "sweep/run_pool.h"

namespace py = pybind11;

namespace tcpmsim::python {
namespace {

// A value as a --set takes it: text as given ("3 mN/mm"); a number as Python prints it (a count,
// a dimensionless value; a value with a unit must say it, as in a config); a bool as YAML's
// true/false.
std::string override_text(const py::handle& value) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value))
    return py::repr(value).cast<std::string>();
  throw py::type_error("a value is a str with its unit (\"3 mN/mm\"), or a plain number; got " +
                       py::repr(value).cast<std::string>());
}

// A value for Scenario.set: a plain number for a model parameter is in SI, as Context, the
// Simulator and the parameters dict give it ("muscle.mechanics.k2", 3.0 is 3 N/m); anything
// else as override_text reads it.
std::string set_text(const Scenario& scenario, const std::string& path, const py::handle& value) {
  const bool number = !py::isinstance<py::bool_>(value) &&
                      (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value));
  const auto index = scenario.system->parameter_index(path);
  if (!number || !index) return override_text(value);
  const std::string& unit =
      scenario.system->parameters()[static_cast<std::size_t>(*index)].declaration.unit;
  const std::string text = override_text(value);
  return unit.empty() || unit == "1" ? text : text + " " + unit;
}

// A run's duration or output rate: a number (in s, in Hz) or a text with its unit.
std::vector<std::string> run_overrides(const py::object& duration, const py::object& rate) {
  std::vector<std::string> overrides;
  const auto with_unit = [](const py::object& value, const char* unit) {
    const std::string text = override_text(value);
    return py::isinstance<py::str>(value) ? text : text + " " + unit;
  };
  if (!duration.is_none()) overrides.push_back("scenario.duration=" + with_unit(duration, "s"));
  if (!rate.is_none()) overrides.push_back("output.rate=" + with_unit(rate, "Hz"));
  return overrides;
}

// Asks Python for pending signals a few times a second while a run integrates without the GIL;
// Ctrl-C ends the run as interrupted, and the KeyboardInterrupt is raised after it.
Integrator::Progress signal_check() {
  auto last =
      std::make_shared<std::chrono::steady_clock::time_point>(std::chrono::steady_clock::now());
  return [last](double, long) {
    const auto now = std::chrono::steady_clock::now();
    if (now - *last < std::chrono::milliseconds(200)) return;
    *last = now;
    const py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) throw StopRequest("interrupted from Python");
  };
}

// SolverFailure with the solver's message (as `tcpmsim run` prints it), carrying the result.
[[noreturn]] void raise_failure(const py::object& type, const PyResult& result) {
  py::object error = type(result.run->reason);
  error.attr("result") = py::cast(result);
  PyErr_SetObject(type.ptr(), error.ptr());
  throw py::error_already_set();
}

void raise_pending_interrupt() {
  if (PyErr_Occurred()) throw py::error_already_set();
}

// The Python program that builds the scenario, for its records: "python3 script.py args".
std::string python_invocation() {
  std::ostringstream text;  // (a string built by += trips GCC 12's false -Wstringop-overflow)
  text << "python3";
  for (const auto& argument : py::module_::import("sys").attr("argv"))
    text << ' ' << py::str(argument).cast<std::string>();
  return text.str();
}

py::dict parameter_values(const Scenario& scenario) {
  Context context = scenario.make_context();
  scenario.system->prepare(context);
  py::dict values;
  const auto& parameters = scenario.system->parameters();
  for (std::size_t index = 0; index < parameters.size(); ++index)
    values[py::str(parameters[index].declaration.path)] =
        context.parameter(static_cast<int>(index));
  return values;
}

// A value outside its typical range, as Python's warnings show it (`warnings.simplefilter(
// "error")` makes it an exception, as --strict does).
void warn_implausible(const Scenario& scenario) {
  for (const auto& warning : scenario.warnings)
    py::module_::import("warnings")
        .attr("warn")(warning, py::module_::import("builtins").attr("UserWarning"), 3);
}

}  // namespace

PyScenario::PyScenario(std::string source, bool is_text, std::vector<std::string> overrides)
    : source_(std::move(source)),
      is_text_(is_text),
      overrides_(std::move(overrides)),
      units_(std::make_shared<UnitSystem>()) {
  scenario_ = load(overrides_);
  warn_implausible(*scenario_);
}

PyScenario PyScenario::from_file(const std::string& path, std::vector<std::string> overrides) {
  return PyScenario(path, false, std::move(overrides));
}
PyScenario PyScenario::from_text(const std::string& text, std::vector<std::string> overrides) {
  return PyScenario(text, true, std::move(overrides));
}

std::shared_ptr<const Scenario> PyScenario::load(const std::vector<std::string>& overrides) const {
  // A value Python set is located at the call that set it, not at a command line.
  const std::string origin = "tcpmsim.Scenario (set ";
  Scenario scenario =
      is_text_
          ? load_scenario_text(source_, "<yaml text>", overrides, units_, standard_kinds(), origin)
          : load_scenario(source_, overrides, units_, standard_kinds(), origin);
  scenario.invocation = python_invocation();
  return std::make_shared<const Scenario>(std::move(scenario));
}

void PyScenario::set(const std::string& path, const std::string& value) {
  std::vector<std::string> overrides = overrides_;
  overrides.push_back(path + "=" + value);
  auto scenario = load(overrides);  // throws before anything changes
  warn_implausible(*scenario);
  scenario_ = std::move(scenario);
  overrides_ = std::move(overrides);
}

std::shared_ptr<const Scenario> PyScenario::with(const std::vector<std::string>& extra) const {
  if (extra.empty()) return scenario_;
  std::vector<std::string> overrides = overrides_;
  overrides.insert(overrides.end(), extra.begin(), extra.end());
  return load(overrides);
}

PyResult run_scenario(const std::shared_ptr<const Scenario>& scenario, double limit_bytes) {
  auto run = std::make_shared<MemoryRun>();
  {
    const py::gil_scoped_release released;
    *run = run_in_memory(*scenario, signal_check(), limit_bytes);
  }
  raise_pending_interrupt();
  return {std::move(run), scenario};
}

std::vector<PyResult> run_scenarios(const std::vector<std::shared_ptr<const Scenario>>& scenarios,
                                    int jobs) {
  std::vector<PyResult> results(scenarios.size());
  if (jobs <= 0) jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  // Only Python's main thread sees signals: the pool's progress, on this thread, asks for them
  // and the runs stop at their next step.
  std::atomic<bool> interrupted{false};
  const Integrator::Progress stop_when_interrupted = [&](double, long) {
    if (interrupted) throw StopRequest("interrupted from Python");
  };
  {
    const py::gil_scoped_release released;
    sweep::CountingDispenser dispenser(scenarios.size());
    sweep::run_slots(
        scenarios.size(), jobs, dispenser,
        [&](std::size_t slot) {
          auto run =
              std::make_shared<MemoryRun>(run_in_memory(*scenarios[slot], stop_when_interrupted));
          results[slot] = {std::move(run), scenarios[slot]};
        },
        [&](std::size_t) {
          const py::gil_scoped_acquire gil;
          if (!interrupted && PyErr_CheckSignals() != 0) interrupted = true;
        });
  }
  raise_pending_interrupt();
  return results;
}

void bind_scenario(py::module_& module) {
  py::class_<PyScenario>(module, "Scenario",
                         "A scenario file (or YAML text) turned into a model, ready to run.")
      .def_static(
          "from_yaml",
          [](const py::object& source, const py::object& settings) {
            std::vector<std::string> overrides;
            if (!settings.is_none() && !py::isinstance<py::dict>(settings))
              throw py::type_error(
                  "set: expected a dict of path: value, e.g. {'measurement.file': 'm.csv'}; got " +
                  py::repr(settings).cast<std::string>());
            if (!settings.is_none())
              for (const auto& [path, value] : settings.cast<py::dict>())
                overrides.push_back(py::str(path).cast<std::string>() + "=" + override_text(value));
            if (py::isinstance<py::bytes>(source))  // YAML text as read from a file or a pipe
              return PyScenario::from_text(source.cast<std::string>(), std::move(overrides));
            if (py::isinstance<py::str>(source)) {
              const std::string text = source.cast<std::string>();
              if (text.find('\n') != std::string::npos)
                return PyScenario::from_text(text, std::move(overrides));
              return PyScenario::from_file(text, std::move(overrides));
            }
            return PyScenario::from_file(py::str(source).cast<std::string>(),  // os.PathLike
                                         std::move(overrides));
          },
          py::arg("source"), py::arg("set") = py::none(),
          "A scenario from a file path, or from YAML text (bytes, or any str holding a line "
          "break); `set` "
          "({'measurement.file': 'm.csv'}) applies values from the start, as --set does.")
      .def(
          "set",
          [](PyScenario& self, const std::string& path, const py::object& value) -> PyScenario& {
            self.set(path, set_text(self.scenario(), path, value));
            return self;
          },
          py::arg("path"), py::arg("value"),
          "Sets a value as --set does (\"muscle.mechanics.k2\", \"3 mN/mm\"); a plain number for "
          "a model parameter is in SI (3.0 is 3 N/m), as Scenario.parameters gives it. Returns "
          "the scenario.",
          py::return_value_policy::reference_internal)
      .def(
          "validate", [](PyScenario& self) -> PyScenario& { return self; },
          "Checks the scenario; a bad one raised already when it was read or set. Returns it.",
          py::return_value_policy::reference_internal)
      .def("copy", [](const PyScenario& self) { return PyScenario(self); })
      .def(
          "run",
          [failure = py::object(module.attr("SolverFailure"))](
              const PyScenario& self, const py::object& duration, const py::object& rate,
              bool check, double max_output_size) {
            if (!(max_output_size > 0.0))  // NaN too: a limit that no run could meet
              throw UsageError("run: max_output_size: expected a positive number of bytes, got " +
                               number_text(max_output_size));
            PyResult result =
                run_scenario(self.with(run_overrides(duration, rate)), max_output_size);
            if (check && result.run->status == "failed") raise_failure(failure, result);
            return result;
          },
          py::arg("duration") = py::none(), py::arg("output_rate") = py::none(),
          py::arg("check") = true, py::arg("max_output_size") = kDefaultRecordLimit,
          "Integrates the scenario and returns a Result (its samples by channel name). duration "
          "[s] and output_rate [Hz] override the file's (numbers in s and Hz, or text with a "
          "unit). "
          "If the solver gives up, raises SolverFailure (its `result` holds the samples up to "
          "there), or with check=False returns the result with status 'failed'. A run whose "
          "samples would exceed max_output_size bytes (2e9, as tcpmsim run's "
          "--max-output-size) raises ConfigError before it starts.")
      .def_property_readonly("name",
                             [](const PyScenario& self) { return self.scenario().settings.name; })
      .def_property_readonly(
          "duration", [](const PyScenario& self) { return self.scenario().settings.duration; })
      .def_property_readonly(
          "output_rate",
          [](const PyScenario& self) { return 1.0 / self.scenario().settings.output_interval; })
      .def_property_readonly("seed",
                             [](const PyScenario& self) { return self.scenario().settings.seed; })
      .def_property_readonly("config",
                             [](const PyScenario& self) { return self.scenario().resolved_yaml; })
      .def_property_readonly("overrides", &PyScenario::overrides)
      .def_property_readonly(
          "warnings", [](const PyScenario& self) { return self.scenario().warnings; },
          "Values outside their typical range, located as the command line prints them (each "
          "also raised as a UserWarning when the scenario is read or set).")
      .def_property_readonly(
          "parameters", [](const PyScenario& self) { return parameter_values(self.scenario()); },
          "Every model parameter by path, as a run takes it, in SI.")
      .def_property_readonly("states",
                             [](const PyScenario& self) {
                               py::dict states;
                               for (const auto& state : self.scenario().system->states())
                                 states[py::str(state.name)] = state.unit;
                               return states;
                             })
      .def("__repr__", [](const PyScenario& self) {
        return "<tcpmsim.Scenario '" + self.scenario().settings.name + "' from " +
               (self.is_text() ? std::string("YAML text") : self.source()) + ">";
      });

  module.def(
      "run_many",
      [](const std::vector<PyScenario>& scenarios, int jobs) {
        std::vector<std::shared_ptr<const Scenario>> built;
        for (const auto& scenario : scenarios) built.push_back(scenario.shared());
        return run_scenarios(built, jobs);
      },
      py::arg("scenarios"), py::arg("jobs") = 0,
      "Runs scenarios on `jobs` threads (0: one per core) with the GIL released; returns their "
      "Results in order. A run whose solver fails has status 'failed', the others go on.");
}

}  // namespace tcpmsim::python
