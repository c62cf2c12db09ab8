#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>

#include "python/bindings.h"
#include "sim/io/record_layout.h"
#include "sim/step_simulator.h"

namespace py = pybind11;

namespace tcpmsim::python {
namespace {

// tcpmsim.Simulator: a StepSimulator over a scenario Python built, with the scenario's source
// kept so that reset(seed=...) can build it again with another seed.
class PySimulator {
 public:
  explicit PySimulator(PyScenario scenario) : scenario_(std::move(scenario)) {
    build(scenario_.shared());
  }

  py::dict reset(const std::optional<std::uint64_t>& seed) {
    if (seed) {
      build(scenario_.with({"scenario.seed=" + std::to_string(*seed)}));
    } else {
      simulator_->reset();
    }
    return outputs();
  }

  py::dict advance_to(double time, const py::object& inputs) {
    set_inputs(inputs);
    {
      const py::gil_scoped_release released;
      simulator_->advance_to(time);
    }
    return outputs();
  }

  void set_parameter(const std::string& path, double value) {
    simulator_->set_parameter(path, value);
    parameters_.emplace_back(path, value);
  }

  py::dict step(const py::object& inputs, double dt) {
    if (!(dt > 0.0)) throw py::value_error("step: dt must be positive");
    set_inputs(inputs);
    {
      const py::gil_scoped_release released;
      simulator_->step(dt);
    }
    return outputs();
  }

  // An input's value as a number; anything else is a TypeError that names the input (pybind11's
  // own cast error is a bare RuntimeError).
  static double input_value(const std::string& name, const py::handle& value) {
    return number_argument(value, "inputs: " + name, "a number in the input's SI unit");
  }

  void set_inputs(const py::object& inputs) {
    if (inputs.is_none()) return;
    if (py::isinstance<py::dict>(inputs)) {
      for (const auto& [name, value] : inputs.cast<py::dict>()) {
        const std::string input = py::str(name).cast<std::string>();
        simulator_->set_input(input, input_value(input, value));
      }
      return;
    }
    // A bare number for the only input.
    const auto& all = simulator_->inputs();
    if (all.size() != 1) {
      throw py::type_error("inputs: expected a dict {name: value} (the scenario has " +
                           std::to_string(all.size()) + " external inputs)");
    }
    simulator_->set_input(all.front().name, input_value(all.front().name, inputs));
  }

  // Every recorded series at time(), as tcpmsim.Result names them: a float, or an array over a
  // bundle's members.
  py::dict outputs() const {
    py::dict values;
    const auto& signals = simulator_->signals();
    for (const RecordSeries& series : layout_) {
      const std::string key = series.group + "/" + series.name;
      if (series.signal_indices.size() == 1 && series.members.empty()) {
        values[py::str(key)] = signals[static_cast<std::size_t>(series.signal_indices.front())];
        continue;
      }
      py::array_t<double> array(static_cast<py::ssize_t>(series.signal_indices.size()));
      auto view = array.mutable_unchecked<1>();
      for (std::size_t i = 0; i < series.signal_indices.size(); ++i)
        view(static_cast<py::ssize_t>(i)) =
            signals[static_cast<std::size_t>(series.signal_indices[i])];
      values[py::str(key)] = array;
    }
    return values;
  }

  py::dict inputs() const {
    py::dict described;
    for (const auto& info : simulator_->inputs()) {
      const auto [lower, upper] = simulator_->input_range(info.name);
      py::dict entry;
      entry["unit"] = info.unit;
      entry["low"] = lower;
      entry["high"] = upper;
      entry["value"] = simulator_->input(info.name);
      described[py::str(info.name)] = entry;
    }
    return described;
  }

  PyResult result() const {
    return {std::make_shared<MemoryRun>(simulator_->record()),
            std::make_shared<const Scenario>(simulator_->scenario())};
  }

  StepSimulator& simulator() { return *simulator_; }
  const StepSimulator& simulator() const { return *simulator_; }
  const PyScenario& scenario() const { return scenario_; }

 private:
  void build(const std::shared_ptr<const Scenario>& scenario) {
    auto made = std::make_unique<StepSimulator>(*scenario);
    for (const auto& [path, value] : parameters_) made->set_parameter(path, value);
    if (!parameters_.empty()) made->reset();
    simulator_ = std::move(made);
    layout_ = record_layout(*simulator_->scenario().system);
  }

  PyScenario scenario_;
  std::unique_ptr<StepSimulator> simulator_;
  std::vector<RecordSeries> layout_;
  std::vector<std::pair<std::string, double>> parameters_;
};

}  // namespace

void bind_simulator(py::module_& module) {
  py::class_<PySimulator>(
      module, "Simulator",
      "A run that advances on request, for a controller written in Python. The scenario's "
      "controller section is of type external; its inputs (inputs()) are held from the time "
      "they are set, and the outputs read after a step are those a controller sampling at that "
      "instant sees (the estimator has acted). The record (result(), save()) is the one "
      "`tcpmsim run` writes.")
      .def(py::init([](const py::object& scenario) {
             if (py::isinstance<PyScenario>(scenario))
               return PySimulator(scenario.cast<PyScenario>());
             const py::object from_yaml =
                 py::module_::import("tcpmsim._core").attr("Scenario").attr("from_yaml");
             return PySimulator(from_yaml(scenario).cast<PyScenario>());
           }),
           py::arg("scenario"), "From a tcpmsim.Scenario, a file path or YAML text.")
      .def_property_readonly(
          "time", [](const PySimulator& self) { return self.simulator().time(); },
          "The time reached [s].")
      .def_property_readonly(
          "end_time", [](const PySimulator& self) { return self.simulator().end_time(); },
          "The scenario's duration [s]: a run cannot pass it.")
      .def_property_readonly("finished",
                             [](const PySimulator& self) { return self.simulator().finished(); })
      .def("inputs", &PySimulator::inputs,
           "The external inputs by name: their unit, range (low, high) and the value held now.")
      .def("outputs", &PySimulator::outputs,
           "Every recorded output at `time`, named as in Result (\"muscle/force\"): a float, or "
           "a numpy array over a bundle's members.")
      .def(
          "output",
          [](const PySimulator& self, const std::string& name) {
            return self.simulator().output(name);
          },
          py::arg("name"), "One output by \"group.name\" (\"estimator.force\"), SI.")
      .def(
          "state",
          [](const PySimulator& self, const std::string& name) {
            return self.simulator().state(name);
          },
          py::arg("name"), "One state by name (Scenario.states), SI.")
      .def("step", &PySimulator::step, py::arg("inputs") = py::none(), py::arg("dt"),
           "Holds `inputs` ({name: value} in SI, or a number for the only input) and advances by "
           "dt [s]; returns outputs(). Equal steps land on the grid k dt exactly.")
      .def("advance_to", &PySimulator::advance_to, py::arg("time"), py::arg("inputs") = py::none(),
           "Holds `inputs` and advances to `time` [s]; returns outputs().")
      .def(
          "set_input",
          [](PySimulator& self, const std::string& name, double value) {
            self.simulator().set_input(name, value);
          },
          py::arg("name"), py::arg("value"), "Holds one input from now on (SI).")
      .def(
          "parameter",
          [](const PySimulator& self, const std::string& path) {
            return self.simulator().parameter(path);
          },
          py::arg("path"), "A model parameter of this run by path, SI.")
      .def("set", &PySimulator::set_parameter, py::arg("path"), py::arg("value"),
           "Sets a model parameter by path in SI (Scenario.parameters) for the runs that start at "
           "the next reset(); raises ParameterError for an unknown path or a value out of range.")
      .def("reset", &PySimulator::reset, py::arg("seed") = py::none(),
           "Starts again at t = 0 (with another scenario seed if given: the drive's measurement "
           "noise); returns outputs().")
      .def("result", &PySimulator::result,
           "The run so far as a Result; status 'complete' at the end, 'interrupted' before.")
      .def(
          "save",
          [](const PySimulator& self, const std::string& path) {
            return self.simulator().save(path);
          },
          py::arg("path"),
          "Writes the run so far as tcpmsim run's record; returns the path written (a run not at "
          "its end: <stem>.interrupted.h5).")
      .def("__repr__", [](const PySimulator& self) {
        return "<tcpmsim.Simulator '" + self.simulator().scenario().settings.name +
               "' at t = " + std::to_string(self.simulator().time()) + " s>";
      });
}

}  // namespace tcpmsim::python
