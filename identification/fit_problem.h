#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "sim/io/measured_data.h"
#include "sim/scenario.h"

namespace tcpmsim::fit {

// A measured channel and the model output it is compared with, weighted by its noise.
struct FitOutput {
  std::string channel;  // in the measurement: "force"
  std::string output;   // of the model: "load.force"
  std::string unit;     // the SI unit both are in
  double noise = 1.0;   // the measurement's standard deviation [unit]; residuals are divided by it
};

// A model parameter to estimate, by its path, within bounds (SI).
struct FitParameter {
  std::string path;  // "muscle.mechanics.k1"
  std::string unit;  // its SI unit
  double lower = 0.0;
  double upper = 0.0;
};

// A time window of the measurement [from, to].
struct TimeWindow {
  double from = 0.0;
  double to = 0.0;
};

// An output-error identification: simulate `model` (its inputs replay `data`), compare its
// outputs with the measured channels at the samples inside `identification`, and choose the
// parameters within their bounds that minimise the weighted squared error.
struct FitProblem {
  std::shared_ptr<const Scenario> model;
  std::shared_ptr<const MeasuredData> data;
  std::vector<FitOutput> outputs;
  std::vector<FitParameter> parameters;
  TimeWindow identification;
  TimeWindow validation;  // from == to: none
};

// The output of `system` a file names at `node` ("load.force"), or a located error saying that
// the `owner` ("model", "scenario") has none.
const ChannelInfo& named_output(const System& system, const ConfigNode& node,
                                std::string_view owner);

// Keeps the chosen outputs ("load.force") of a run at its output times.
class OutputPicker final : public OutputSink {
 public:
  // Throws std::invalid_argument for an output the system does not have.
  OutputPicker(const System& system, const std::vector<std::string>& outputs);
  void record(double time, std::span<const double> signals) override;
  std::vector<double> times;
  std::vector<std::vector<double>> values;  // by output

 private:
  std::vector<int> indices_;
};

// The model outputs at the measurement's samples inside a window, one vector per output; a run
// of `problem.model` in a context with `values` set for the fitted parameters (SI). Throws
// SolverFailure or ParameterError when the model cannot run at `values`.
std::vector<std::vector<double>> simulate_outputs(const FitProblem& problem,
                                                  const std::vector<double>& values,
                                                  const TimeWindow& window);
// The model outputs at the measurement's samples inside a window and their sensitivities to
// the fitted parameters `tracked` (indices into problem.parameters), from one run with forward
// sensitivities (CVODES): values[k][i], and sensitivities[k][t][i] = d values[k][i] / d p_t in
// the output's unit per SI unit of the parameter. Throws std::invalid_argument when the model
// does not allow sensitivities (ForwardSensitivities::unsupported_reason), else as
// simulate_outputs.
struct OutputSensitivities {
  std::vector<std::vector<double>> values;
  std::vector<std::vector<std::vector<double>>> sensitivities;
};
OutputSensitivities simulate_sensitivities(const FitProblem& problem,
                                           const std::vector<double>& values,
                                           const std::vector<std::size_t>& tracked,
                                           const TimeWindow& window);
// Why forward sensitivities cannot serve this problem's model, or "".
std::string sensitivities_unavailable(const FitProblem& problem);

// The measured values at the same samples, one vector per output.
std::vector<std::vector<double>> measured_outputs(const FitProblem& problem,
                                                  const TimeWindow& window);

// The indices of the measurement's samples inside `window`.
std::pair<std::size_t, std::size_t> samples_in(const MeasuredData& data, const TimeWindow& window);

// Why `window` cannot serve a fit: it holds fewer than `minimum` of the measurement's samples
// (`needed_for` says what needs them: "a fit of 2 parameters"); "" when it holds enough. A
// window inside a gap of the data holds none.
std::string window_samples_problem(const MeasuredData& data, const TimeWindow& window,
                                   std::size_t minimum, std::string_view needed_for);

}  // namespace tcpmsim::fit
