#include "sim/memory_run.h"

#include <H5Cpp.h>

#include <chrono>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "sim/io/hdf5_files.h"
#include "sim/io/hdf5_recorder.h"
#include "sim/run.h"

namespace tcpmsim {
namespace {

double seconds_since(std::chrono::steady_clock::time_point started) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
}

}  // namespace

MemoryRunSink::MemoryRunSink(MemoryRun& run) : run_(run) {}

void MemoryRunSink::record(double time, std::span<const double> signals) {
  run_.time.push_back(time);
  for (std::size_t series = 0; series < run_.series.size(); ++series)
    for (const int index : run_.series[series].signal_indices)
      run_.values[series].push_back(signals[static_cast<std::size_t>(index)]);
}

const RecordSeries* MemoryRun::find(const std::string& channel, std::size_t* index) const {
  for (std::size_t position = 0; position < series.size(); ++position) {
    if (series[position].group + "/" + series[position].name != channel) continue;
    if (index) *index = position;
    return &series[position];
  }
  return nullptr;
}

MemoryRun run_in_memory(const Scenario& scenario, const Integrator::Progress& progress,
                        double limit_bytes) {
  check_record_size(scenario, limit_bytes);
  const auto started = std::chrono::steady_clock::now();
  MemoryRun run;
  run.series = record_layout(*scenario.system);
  run.values.resize(run.series.size());
  MemoryRunSink sink(run);
  Context context = scenario.make_context();
  scenario.system->prepare(context);  // as run_scenario does before its record is planned
  try {
    run.statistics = integrate(scenario, context, sink, progress);
    run.status = "complete";
    run.time_reached = scenario.settings.duration;
  } catch (const RunEnded& ended) {
    run.statistics = ended.statistics();
    run.status = dynamic_cast<const RunInterrupted*>(&ended) ? "interrupted" : "failed";
    run.reason = ended.what();
    run.time_reached = ended.time();
  }
  run.wall_seconds = seconds_since(started);
  return run;
}

std::string save_record(const Scenario& scenario, const MemoryRun& run, const std::string& path) {
  Context context = scenario.make_context();
  return save_record(scenario, context, run, path);
}

std::string save_record(const Scenario& scenario, const Context& run_context, const MemoryRun& run,
                        const std::string& path) {
  Context context = run_context;      // its parameters, its run state afresh
  scenario.system->prepare(context);  // the inputs as the run had them
  return writing_record(path, [&] {
    Hdf5Recorder recorder(path, *scenario.system, context, record_metadata(scenario));
    std::vector<double> signals(static_cast<std::size_t>(scenario.system->signal_size()),
                                std::numeric_limits<double>::quiet_NaN());
    for (std::size_t sample = 0; sample < run.time.size(); ++sample) {
      for (std::size_t series = 0; series < run.series.size(); ++series) {
        const auto& indices = run.series[series].signal_indices;
        for (std::size_t column = 0; column < indices.size(); ++column)
          signals[static_cast<std::size_t>(indices[column])] =
              run.values[series][sample * indices.size() + column];
      }
      recorder.record(run.time[sample], signals);
    }
    if (run.status == "failed") return recorder.fail(run.reason, run.statistics);
    if (run.status == "interrupted")
      return recorder.interrupt(run.reason, run.time_reached, run.statistics);
    recorder.finish(run.statistics);
    return path;
  });
}

}  // namespace tcpmsim
