#include "sim/run.h"

#include <H5Cpp.h>

#include <chrono>
#include <cmath>
#include <filesystem>

#include "sim/config/config_error.h"
#include "sim/io/hdf5_files.h"
#include "sim/io/hdf5_recorder.h"
#include "sim/io/record_layout.h"
#include "sim/output_grid.h"
#include "sim/value_check.h"

namespace tcpmsim {

RecordSize estimate_record_size(const Scenario& scenario) {
  const ScenarioSettings& settings = scenario.settings;
  RecordSize size;
  size.samples = output_sample_count(std::max(0.0, settings.output_start), settings.duration,
                                     settings.output_interval);
  size.columns = 1.0;
  for (const auto& series : record_layout(*scenario.system))
    size.columns += static_cast<double>(series.signal_indices.size());
  return size;
}

std::string byte_text(double bytes) {
  static constexpr const char* kUnits[] = {"B", "kB", "MB", "GB", "TB", "PB"};
  int unit = 0;
  while (bytes >= 1000.0 && unit < 5) bytes /= 1000.0, ++unit;
  return number_text(bytes, 3) + " " + kUnits[unit];
}

void check_record_size(const Scenario& scenario, double limit_bytes) {
  const RecordSize size = estimate_record_size(scenario);
  if (size.bytes() <= limit_bytes) return;
  throw ConfigError(scenario.settings.output_rate_location, "output.rate",
                    "the record would hold " + number_text(size.samples, 4) + " samples x " +
                        number_text(size.columns, 4) + " columns = " + byte_text(size.bytes()) +
                        " (uncompressed), over the limit of " + byte_text(limit_bytes) +
                        "; lower output.rate, shorten the scenario, or raise the limit with "
                        "--max-output-size");
}

RecordMetadata record_metadata(const Scenario& scenario) {
  return {scenario.settings.name,
          scenario.source,
          scenario.resolved_yaml,
          scenario.settings.seed,
          scenario.solver.relative_tolerance,
          linear_solver_name(scenario.solver.linear_solver),
          scenario.settings.output_interval,
          scenario.settings.duration,
          scenario.settings.compression_level,
          scenario.invocation};
}

SolverStatistics integrate(const Scenario& scenario, Context& context, OutputSink& sink,
                           const Integrator::Progress& progress) {
  Integrator integrator(*scenario.system, context, scenario.solver);
  return integrator.run(0.0, scenario.settings.duration,
                        {scenario.settings.output_interval, scenario.settings.output_start}, sink,
                        progress);
}

SolverStatistics integrate(const Scenario& scenario, OutputSink& sink,
                           const Integrator::Progress& progress) {
  Context context = scenario.make_context();
  return integrate(scenario, context, sink, progress);
}

RunOutcome run_scenario(const Scenario& scenario, const std::string& output_path,
                        const Integrator::Progress& progress) {
  Context context = scenario.make_context();
  return run_scenario(scenario, context, output_path, progress);
}

RunOutcome run_scenario(const Scenario& scenario, Context& context, const std::string& output_path,
                        const Integrator::Progress& progress) {
  const auto started = std::chrono::steady_clock::now();
  scenario.system->prepare(context);  // the signals as this run has them, for the record

  const RecordMetadata metadata = record_metadata(scenario);
  RunOutcome outcome;
  writing_record(output_path, [&] {
    Hdf5Recorder recorder(output_path, *scenario.system, context, metadata);
    try {
      outcome.statistics = integrate(scenario, context, recorder, progress);
      recorder.finish(outcome.statistics);
      outcome.output_path = output_path;
      outcome.succeeded = true;
    } catch (const SolverFailure& failure) {
      outcome.statistics = failure.statistics();
      outcome.failure = failure.what();
      outcome.output_path = recorder.fail(failure.what(), failure.statistics());
    } catch (const RunInterrupted& interruption) {
      outcome.statistics = interruption.statistics();
      outcome.failure = interruption.what();
      outcome.interrupted = true;
      outcome.time_reached = interruption.time();
      outcome.output_path =
          recorder.interrupt(interruption.what(), interruption.time(), interruption.statistics());
    }
  });
  outcome.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return outcome;
}

}  // namespace tcpmsim
