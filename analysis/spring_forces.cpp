#include "analysis/spring_forces.h"

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

#include "kinds/standard_kinds.h"
#include "models/coil_spring_chain.h"
#include "models/coil_spring_inductance.h"
#include "sim/config/config_error.h"
#include "sim/io/hdf5_writer.h"
#include "sim/parallel_runs.h"
#include "sim/run.h"

namespace tcpmsim {

namespace {

// The four forces the analysis compares, F_i, F_o, F_L and F_x.
constexpr std::array<const char*, 4> kForces{"spring.input_force", "spring.output_force",
                                             "spring.inductance_force", "spring.deflection_force"};

// Keeps the four forces inside the analysis window only.
class ForceWindow final : public OutputSink {
 public:
  ForceWindow(const System& system, double start) : start_(start) {
    for (const char* name : kForces) {
      const int index = system.signal_index(name);
      if (index < 0) throw std::invalid_argument(std::string("the scenario has no output ") + name);
      indices_.push_back(index);
    }
  }
  void record(double time, std::span<const double> signals) override {
    if (time < start_) return;
    for (std::size_t k = 0; k < indices_.size(); ++k) {
      series[k].push_back(signals[static_cast<std::size_t>(indices_[k])]);
    }
  }
  std::array<std::vector<double>, 4> series;  // F_i, F_o, F_L, F_x

 private:
  double start_;
  std::vector<int> indices_;
};

ForceDifferences differences(const ForceWindow& window, double nominal) {
  ForceDifferences result{};
  const auto& reference = window.series[3];
  if (reference.empty()) throw std::invalid_argument("no samples in the analysis window");
  for (std::size_t sensor = 0; sensor < 3; ++sensor) {
    double squares = 0.0, largest = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < reference.size(); ++i) {
      const double difference = window.series[sensor][i] - reference[i];
      squares += difference * difference;
      largest = std::max(largest, difference);
    }
    result.rms[sensor] =
        100.0 * std::sqrt(squares / static_cast<double>(reference.size())) / nominal;
    result.maximum[sensor] = 100.0 * largest / nominal;
  }
  return result;
}

// Loading reads units through udunits2, whose calls take one process-wide lock: load on the
// caller's thread, integrate on the pool.
struct PreparedRun {
  Scenario scenario;
  double nominal_force = 0.0;
  double load_seconds = 0.0;
};

PreparedRun prepare(const std::string& config, double window,
                    std::shared_ptr<const UnitSystem> units) {
  const auto started = std::chrono::steady_clock::now();
  PreparedRun run{load_scenario(config, {}, std::move(units))};
  const auto& settings = run.scenario.settings;
  if (!(window > 0.0) || settings.duration - window < settings.output_start - 1e-12) {
    char problem[160];
    std::snprintf(problem, sizeof problem,
                  ": the analysis window (%g s) must lie within the recorded %g s to %g s", window,
                  settings.output_start, settings.duration);
    throw UsageError("--window: " + config + problem);
  }
  const auto* chain = run.scenario.system->find<const CoilSpringChain>();
  const auto* sensor = run.scenario.system->find<const CoilSpringInductance>();
  if (!chain || !sensor) {
    throw UsageError(
        "spring-forces takes coil-spring scenarios with an inductance sensor "
        "(configs/ch4/*.yaml); " +
        config + " is not one");
  }
  for (const char* name : kForces) {
    if (run.scenario.system->signal_index(name) < 0)
      throw UsageError(std::string("spring-forces reads the outputs of a coil spring named "
                                   "'spring' (") +
                       name + "); " + config + " names its spring otherwise");
  }
  run.nominal_force = chain->defaults().stiffness * (sensor->defaults().longest_length -
                                                     chain->defaults().rest_length);  // (4.14)
  run.load_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return run;
}

SpringForceRow integrate(PreparedRun& run, double window) {
  const auto started = std::chrono::steady_clock::now();
  Scenario& scenario = run.scenario;
  SpringForceRow row;
  row.scenario = scenario.settings.name;
  row.nominal_force = run.nominal_force;
  ForceWindow sink(*scenario.system, scenario.settings.duration - window);
  row.statistics = integrate(scenario, sink);
  row.simulated = differences(sink, row.nominal_force);
  row.thesis = thesis_table_4_2(row.scenario);
  row.wall_seconds =
      run.load_seconds +
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return row;
}

}  // namespace

std::optional<ForceDifferences> thesis_table_4_2(const std::string& scenario) {
  // Thesis Table 4.2: RMSD F_i, F_o, F_L | maximum F_i, F_o, F_L, in % of F_nom. The OCR of the
  // S_T half-resonance row lost its first value (marked NaN).
  static const std::map<std::string, std::array<double, 6>> table{
      {"ch4_st_heel_strike", {1.44, 1.44, 0.01, 3.11, 3.08, 0.00}},
      {"ch4_st_end_stop_max", {0.22, 0.23, 0.01, 0.46, 0.44, 0.01}},
      {"ch4_st_end_stop_min", {0.39, 0.39, 0.00, 0.85, 0.84, 0.00}},
      {"ch4_st_harmonic_half", {std::nan(""), 0.27, 0.00, 0.80, 0.42, 0.01}},
      {"ch4_st_harmonic_first", {8.93, 8.94, 0.34, 14.39, 14.21, 0.00}},
      {"ch4_sa_heel_strike", {1.67, 1.67, 0.01, 3.77, 3.78, -0.00}},
      {"ch4_sa_end_stop_max", {0.15, 0.15, 0.01, 0.46, 0.42, 0.01}},
      {"ch4_sa_end_stop_min", {0.27, 0.27, 0.00, 0.60, 0.61, -0.00}},
      {"ch4_sa_harmonic_half", {0.78, 0.57, 0.02, 1.69, 0.94, 0.04}},
      {"ch4_sa_harmonic_first", {58.32, 58.36, 7.73, 93.05, 96.41, 0.03}}};
  const auto found = table.find(scenario);
  if (found == table.end()) return std::nullopt;
  ForceDifferences published{};
  for (std::size_t k = 0; k < 3; ++k) {
    published.rms[k] = found->second[k];
    published.maximum[k] = found->second[k + 3];
  }
  return published;
}

std::vector<SpringForceRow> run_spring_forces(const std::vector<std::string>& configs,
                                              double window, int threads,
                                              std::shared_ptr<const UnitSystem> units) {
  std::vector<PreparedRun> runs;
  for (const auto& config : configs) runs.push_back(prepare(config, window, units));
  std::vector<SpringForceRow> rows(configs.size());
  run_in_parallel(configs, threads, [&](std::size_t k) { rows[k] = integrate(runs[k], window); });
  return rows;
}

std::string format_spring_force_table(const std::vector<SpringForceRow>& rows) {
  std::string text =
      "Forces relative to F_x = k x, % of F_nom (thesis Table 4.2 in brackets)\n"
      "scenario                RMSD F_i         RMSD F_o         RMSD F_L         max F_i          "
      "max F_o          max F_L\n";
  char cell[64];
  for (const auto& row : rows) {
    char name[32];
    std::snprintf(name, sizeof name, "%-22s",
                  row.scenario.c_str() + (row.scenario.rfind("ch4_", 0) == 0 ? 4 : 0));
    text += name;
    for (int kind = 0; kind < 2; ++kind) {
      for (std::size_t k = 0; k < 3; ++k) {
        const double value = kind == 0 ? row.simulated.rms[k] : row.simulated.maximum[k];
        const double published = !row.thesis ? std::nan("")
                                 : kind == 0 ? row.thesis->rms[k]
                                             : row.thesis->maximum[k];
        if (!std::isnan(published)) {
          std::snprintf(cell, sizeof cell, " %7.2f (%6.2f)", value, published);
        } else {
          std::snprintf(cell, sizeof cell, " %7.2f (   -  )", value);
        }
        text += cell;
      }
    }
    text += "\n";
  }
  return text;
}

void write_spring_force_table(const std::vector<SpringForceRow>& rows, const std::string& path,
                              const Provenance& provenance) {
  Hdf5Writer file(path);
  file.provenance(provenance);
  std::vector<std::string> names;
  for (const auto& row : rows) names.push_back(row.scenario);
  file.write_strings("scenario", names);
  auto write = [&](const std::string& name, auto pick, const char* units) {
    std::vector<double> values;
    for (const auto& row : rows) values.push_back(pick(row));
    file.write(name, values, units);
  };
  const char* sensors[] = {"input_force", "output_force", "inductance_force"};
  for (std::size_t k = 0; k < 3; ++k) {
    write(
        std::string("rmsd_") + sensors[k],
        [k](const SpringForceRow& r) { return r.simulated.rms[k]; }, "%");
    write(
        std::string("max_difference_") + sensors[k],
        [k](const SpringForceRow& r) { return r.simulated.maximum[k]; }, "%");
    write(
        std::string("thesis_rmsd_") + sensors[k],
        [k](const SpringForceRow& r) { return r.thesis ? r.thesis->rms[k] : std::nan(""); }, "%");
    write(
        std::string("thesis_max_difference_") + sensors[k],
        [k](const SpringForceRow& r) { return r.thesis ? r.thesis->maximum[k] : std::nan(""); },
        "%");
  }
  write(
      "nominal_force", [](const SpringForceRow& r) { return r.nominal_force; }, "N");
  file.commit();
}

}  // namespace tcpmsim
