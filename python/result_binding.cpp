#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "python/bindings.h"

namespace py = pybind11;

namespace tcpmsim::python {
namespace {

// A read-only numpy view of a run's samples; the array keeps the run alive.
py::array samples_view(const std::shared_ptr<const MemoryRun>& run, const double* data,
                       std::size_t rows, std::size_t columns, bool matrix) {
  static constexpr double kNoSamples = 0.0;
  auto* owner = new std::shared_ptr<const MemoryRun>(run);
  const py::capsule keep(
      owner, [](void* pointer) { delete static_cast<std::shared_ptr<const MemoryRun>*>(pointer); });
  const auto row_bytes = static_cast<py::ssize_t>(columns * sizeof(double));
  std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(rows)};
  std::vector<py::ssize_t> strides{row_bytes};
  if (matrix) {
    shape.push_back(static_cast<py::ssize_t>(columns));
    strides.push_back(static_cast<py::ssize_t>(sizeof(double)));
  }
  py::array view(py::dtype::of<double>(), shape, strides, rows ? data : &kNoSamples, keep);
  py::detail::array_proxy(view.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return view;
}

py::array channel(const PyResult& result, const std::string& name) {
  const MemoryRun& run = *result.run;
  if (name == "time") return samples_view(result.run, run.time.data(), run.time.size(), 1, false);
  std::size_t index = 0;
  const RecordSeries* series = run.find(name, &index);
  if (!series)
    throw py::key_error("no channel '" + name + "' in the result of '" +
                        result.scenario->settings.name + "'; see Result.channels");
  return samples_view(result.run, run.values[index].data(), run.time.size(),
                      series->signal_indices.size(), !series->members.empty());
}

std::vector<std::string> channel_names(const PyResult& result) {
  std::vector<std::string> names{"time"};
  for (const auto& series : result.run->series) names.push_back(series.group + "/" + series.name);
  return names;
}

py::dict statistics(const MemoryRun& run) {
  const SolverStatistics& s = run.statistics;
  py::dict stats;
  stats["steps"] = s.steps;
  stats["rhs_evaluations"] = s.rhs_evaluations;
  stats["rhs_evaluations_for_jacobian"] = s.rhs_evaluations_for_jacobian;
  stats["jacobian_evaluations"] = s.jacobian_evaluations;
  stats["linear_solver_setups"] = s.linear_solver_setups;
  stats["linear_iterations"] = s.linear_iterations;
  stats["error_test_failures"] = s.error_test_failures;
  stats["nonlinear_iterations"] = s.nonlinear_iterations;
  stats["nonlinear_convergence_failures"] = s.nonlinear_convergence_failures;
  stats["segments"] = s.segments;
  stats["events"] = s.events;
  stats["output_samples"] = s.output_samples;
  stats["wall_seconds"] = run.wall_seconds;
  return stats;
}

}  // namespace

void bind_result(py::module_& module) {
  py::class_<PyResult>(module, "Result",
                       "A run's samples by channel ('time', 'muscle/force', 'b/temperature' with "
                       "a column per member), with units, the resolved config and the solver's "
                       "statistics.")
      .def("__getitem__", &channel, py::arg("channel"))
      .def("__contains__",
           [](const PyResult& self, const std::string& name) {
             return name == "time" || self.run->find(name) != nullptr;
           })
      .def("keys", &channel_names)
      .def("__iter__", [](const PyResult& self) { return py::iter(py::cast(channel_names(self))); })
      .def("__len__", [](const PyResult& self) { return self.run->series.size() + 1; })
      .def_property_readonly("channels", &channel_names)
      .def_property_readonly("units",
                             [](const PyResult& self) {
                               py::dict units;
                               units["time"] = "s";
                               for (const auto& series : self.run->series)
                                 units[py::str(series.group + "/" + series.name)] = series.unit;
                               return units;
                             })
      .def_property_readonly("members",
                             [](const PyResult& self) {
                               py::dict members;
                               for (const auto& series : self.run->series)
                                 if (!series.members.empty())
                                   members[py::str(series.group + "/" + series.name)] =
                                       series.members;
                               return members;
                             })
      .def_property_readonly("config",
                             [](const PyResult& self) { return self.scenario->resolved_yaml; })
      .def_property_readonly("scenario",
                             [](const PyResult& self) { return self.scenario->settings.name; })
      .def_property_readonly("seed",
                             [](const PyResult& self) { return self.scenario->settings.seed; })
      .def_property_readonly("statistics",
                             [](const PyResult& self) { return statistics(*self.run); })
      .def_property_readonly("status", [](const PyResult& self) { return self.run->status; })
      .def_property_readonly("succeeded",
                             [](const PyResult& self) { return self.run->status == "complete"; })
      .def_property_readonly("reason", [](const PyResult& self) { return self.run->reason; })
      .def_property_readonly("time_reached",
                             [](const PyResult& self) { return self.run->time_reached; })
      .def(
          "save",
          [](const PyResult& self, const py::object& path) {
            const std::string file = py::str(path).cast<std::string>();
            const py::gil_scoped_release released;
            return save_record(*self.scenario, *self.run, file);
          },
          py::arg("path"),
          "Writes the record `tcpmsim run` writes (a failed run as <stem>.failed.h5); returns "
          "the path written.")
      .def("__repr__", [](const PyResult& self) {
        return "<tcpmsim.Result '" + self.scenario->settings.name + "': " + self.run->status +
               ", " + std::to_string(self.run->time.size()) + " samples of " +
               std::to_string(self.run->series.size()) + " channels>";
      });
}

}  // namespace tcpmsim::python
