#include <pybind11/complex.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <limits>

#include "analysis/record_analysis.h"
#include "python/bindings.h"
#include "sim/config/config_error.h"

namespace py = pybind11;

namespace tcpmsim::python {
namespace {

template <typename Item, typename Value>
py::array_t<Value> column(const std::vector<Item>& items, Value (*value)(const Item&)) {
  py::array_t<Value> values(static_cast<py::ssize_t>(items.size()));
  auto out = values.template mutable_unchecked<1>();
  for (std::size_t k = 0; k < items.size(); ++k) out(static_cast<py::ssize_t>(k)) = value(items[k]);
  return values;
}

py::dict steps_dict(const RecordAnalysis& analysis) {
  using S = StepMetrics;
  py::dict steps;
  const auto& all = analysis.steps;
  steps["step_time"] = column<S, double>(all, [](const S& s) { return s.step_time; });
  steps["hold"] = column<S, double>(all, [](const S& s) { return s.hold; });
  steps["reference"] = column<S, double>(all, [](const S& s) { return s.reference; });
  steps["start"] = column<S, double>(all, [](const S& s) { return s.start; });
  steps["final_value"] = column<S, double>(all, [](const S& s) { return s.final_value; });
  steps["rise_time"] = column<S, double>(all, [](const S& s) { return s.rise_time; });
  steps["settling_time"] = column<S, double>(all, [](const S& s) { return s.settling_time; });
  steps["time_constant"] = column<S, double>(all, [](const S& s) { return s.time_constant; });
  steps["settled"] = column<S, bool>(all, [](const S& s) { return s.settled; });
  steps["overshoot"] = column<S, double>(all, [](const S& s) { return s.overshoot; });
  steps["steady_state_error"] =
      column<S, double>(all, [](const S& s) { return s.steady_state_error; });
  return steps;
}

py::dict response_dict(const InputResponse& response) {
  using E = ResponseEstimate;
  const auto& all = response.estimates;
  py::dict result;
  result["unit"] = response.unit;
  result["frequency"] = column<E, double>(all, [](const E& e) { return e.frequency; });
  result["response"] = column<E, std::complex<double>>(all, [](const E& e) { return e.response; });
  result["magnitude"] = column<E, double>(all, [](const E& e) { return e.magnitude; });
  result["magnitude_db"] = column<E, double>(all, [](const E& e) { return e.magnitude_db; });
  result["phase"] = column<E, double>(all, [](const E& e) { return e.phase; });
  result["radius_95"] = column<E, double>(all, [](const E& e) { return e.radius_95; });
  result["coherence"] = column<E, double>(all, [](const E& e) { return e.coherence; });
  std::vector<std::string> overlap;
  for (const auto& estimate : all) overlap.push_back(estimate.overlap);
  result["overlap"] = overlap;
  result["bandwidth"] = response.bandwidth ? py::cast(*response.bandwidth) : py::none();
  result["reference_magnitude"] = response.reference_magnitude;
  result["bandwidth_relative"] = response.relative;  // against the lowest frequency's |H|
  return result;
}

py::dict analysis_dict(const RecordAnalysis& analysis) {
  py::dict result;
  result["source"] = analysis.source;
  result["output"] = analysis.output;
  result["output_unit"] = analysis.output_unit;
  result["window"] = py::make_tuple(analysis.from, analysis.to);
  if (!analysis.reference.empty()) {
    result["reference"] = analysis.reference;
    result["steps"] = steps_dict(analysis);
  }
  if (!analysis.responses.empty()) {
    result["method"] = analysis.method;
    py::dict responses;
    for (const auto& response : analysis.responses)
      responses[py::str(response.input)] = response_dict(response);
    result["responses"] = responses;
  }
  result["notes"] = analysis.notes;
  result["report"] = analysis_report(analysis);
  return result;
}

RecordChannels channels_of(const py::object& source) {
  if (py::isinstance<PyResult>(source)) {
    const auto& result = source.cast<const PyResult&>();
    return memory_record_channels(*result.scenario, *result.run);
  }
  if (!py::isinstance<py::str>(source) && !py::hasattr(source, "__fspath__"))
    throw UsageError(
        "analyze: source: expected a Result or a record's path (str or os.PathLike), "
        "got " +
        py::repr(source).cast<std::string>());
  return read_record_channels(py::str(source).cast<std::string>());  // a path
}

// An optional number argument; anything but a number or None is a TypeError naming it.
double or_default(const char* name, const py::object& value, double fallback) {
  return value.is_none() ? fallback : number_argument(value, std::string("analyze: ") + name);
}

}  // namespace

void bind_analysis(py::module_& module) {
  module.def(
      "analyze",
      [](const py::object& source, const std::string& response, const std::string& reference,
         const std::vector<std::string>& inputs, const py::object& start, const py::object& end,
         const std::string& method, const py::object& segment, double rise, double settling_band) {
        AnalysisRequest request;
        request.output = response;
        request.reference = reference;
        request.inputs = inputs;
        request.from = or_default("start", start, -std::numeric_limits<double>::infinity());
        request.to = or_default("end", end, std::numeric_limits<double>::infinity());
        request.method = method;
        request.segment = or_default("segment", segment, 0.0);
        request.steps.rise = {1.0 - rise, rise};
        request.steps.settling_band = settling_band;
        const RecordChannels channels = channels_of(source);
        RecordAnalysis analysis;
        {
          const py::gil_scoped_release released;
          analysis = analyze_record(channels, request);
        }
        return analysis_dict(analysis);
      },
      py::arg("source"), py::arg("response"), py::arg("reference") = "",
      py::arg("inputs") = std::vector<std::string>{}, py::arg("start") = py::none(),
      py::arg("end") = py::none(), py::arg("method") = "auto", py::arg("segment") = py::none(),
      py::arg("rise") = 0.9, py::arg("settling_band") = 0.02,
      "What `tcpmsim analyze` computes, on a Result or a record file: step metrics of `response` "
      "against `reference` (per step: rise, settling, overshoot, steady-state error), and/or its "
      "frequency response from `inputs` (default without a reference: every input the window "
      "[start, end] s excites) at a multisine's lines or by a multi-input H1 estimate, with 95 % "
      "confidence radii and the -3 dB point. Returns a dict of numpy arrays; 'report' is the "
      "command line's text. A request the record cannot serve raises ValueError.");
}

}  // namespace tcpmsim::python
