// tcpmsim command line: run and validate scenarios.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <thread>

#include <fcntl.h>
#include <unistd.h>

#include "analysis/analyze_command.h"
#include "analysis/coil_fit_command.h"
#include "analysis/control_tasks_command.h"
#include "analysis/provenance.h"
#include "analysis/spring_forces_command.h"
#include "cli/export_fmu.h"
#include "cli/interrupt.h"
#include "cli/progress.h"
#include "identification/bench_measurement.h"
#include "identification/discovery_report.h"
#include "identification/discovery_runs.h"
#include "identification/effect_catalogue.h"
#include "identification/fit_report.h"
#include "identification/joint_refit.h"
#include "kinds/standard_kinds.h"
#include "sim/config/config_error.h"
#include "sim/io/hdf5_files.h"
#include "sim/io/record_recovery.h"
#include "sim/kind_listing.h"
#include "sim/run.h"
#include "sweep/batch_run.h"
#include "sweep/sweep_executor.h"
#include "sweep/sweep_mpi.h"
#include "sweep/sweep_table.h"
#include "tcpmsim/version.h"

namespace {

// Exit codes, documented in the README.
enum ExitCode : int {
  kSuccess = 0,
  kSimulationFailed = 1,
  kUsageError = 2,
  kConfigError = 3,
  kOutputError = 4,
  kInternalError = 5,
  // discover's verdicts other than a named effect (0): the base model fits to the noise floor,
  // or it misses by more than the noise and no candidate explains it.
  kVerdictNone = 10,
  kVerdictUnexplained = 11,
};

struct Options {
  std::string config;
  std::string output;
  std::vector<std::string> overrides;
  bool quiet = false;
  bool strict = false;  // run, validate: warnings (implausible values) are errors
  bool markdown = false;
  bool discover_families = false;  // kinds: only discover's families
  tcpmsim::analysis::CoilFitOptions coil_fit;
  tcpmsim::SpringForcesOptions spring_forces;
  tcpmsim::ControlTasksOptions control_tasks;
  tcpmsim::AnalyzeOptions analyze;
  std::string invocation;  // the command line, written into every file
  tcpmsim::sweep::SweepOptions sweep;
  std::vector<std::string> configs;  // run: one or more scenario files
  std::string output_directory = "results";
  int jobs = 1;
  // run: --max-output-size
  std::uint64_t max_output_bytes = static_cast<std::uint64_t>(tcpmsim::kDefaultRecordLimit);
  std::string recover_output;  // recover: -o
  std::string data;            // fit: the measurement, in place of the fit file's
  std::string fit_directory;   // fit: where its outputs go
  std::string bench;           // measure: the bench file
  int fit_jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  tcpmsim::fit::DiscoverRequest discover;  // discover
  bool plots = true;
  int max_effects = 1;  // discover: effects sought, one a run
  tcpmsim::cli::ExportFmuOptions export_fmu;
};

// Prints the scenario's warnings (values outside their typical range) to stderr; with --strict
// they are errors, and the command ends with the configuration error's code before any work.
bool warnings_stop(const tcpmsim::Scenario& scenario, const Options& options) {
  for (const auto& warning : scenario.warnings) std::cerr << warning << "\n";
  if (!options.strict || scenario.warnings.empty()) return false;
  std::cerr << "tcpmsim: --strict: " << scenario.warnings.size()
            << (scenario.warnings.size() == 1 ? " warning is an error\n"
                                              : " warnings are errors\n");
  return true;
}

tcpmsim::Scenario load(const Options& options) {
  return tcpmsim::load_scenario(options.config, options.overrides,
                                std::make_shared<tcpmsim::UnitSystem>());
}

int validate(const Options& options) {
  tcpmsim::Scenario scenario = load(options);
  if (warnings_stop(scenario, options)) return kConfigError;
  std::cout << options.config << ": valid scenario '" << scenario.settings.name << "', "
            << scenario.settings.duration << " s, " << scenario.system->state_size() << " states, "
            << std::count_if(scenario.system->channels().begin(), scenario.system->channels().end(),
                             [](const auto& channel) { return channel.recorded; })
            << " output channels\n";
  const tcpmsim::RecordSize record = tcpmsim::estimate_record_size(scenario);
  std::cout << "  record: " << record.samples << " samples x " << record.columns
            << " columns, about " << tcpmsim::byte_text(record.bytes()) << " uncompressed\n";
  for (const auto& state : scenario.system->states()) {
    std::cout << "  state  " << state.name << " [" << state.unit << "]\n";
  }
  for (const auto& channel : scenario.system->channels()) {
    if (!channel.recorded) continue;  // a port between components, not in the record
    std::cout << "  output /" << channel.group << "/" << channel.name << " [" << channel.unit
              << "]\n";
  }
  // The values a run takes: those --set gave the context, and the derived ones from them.
  tcpmsim::Context context = scenario.make_context();
  scenario.system->prepare(context);
  for (std::size_t index = 0; index < scenario.system->parameters().size(); ++index) {
    const auto& parameter = scenario.system->parameters()[index];
    const auto& declared = parameter.declaration;
    std::cout << "  parameter " << declared.path << " = "
              << context.parameter(static_cast<int>(index))
              << (declared.unit == "1" ? "" : " " + declared.unit);
    if (!parameter.derived_from.empty())
      std::cout << " (derived: " << parameter.derived_from << ")";
    std::cout << "\n";
  }
  return kSuccess;
}

// Several scenario files: a batch on the sweeps' run pool (sweep/batch_run.h).
int run_batch(const Options& options) {
  if (!options.output.empty()) {
    std::cerr << "tcpmsim: -o names one record; with several scenarios use --output-dir\n";
    return kUsageError;
  }
  std::vector<tcpmsim::sweep::BatchRun> runs;
  {
    tcpmsim::BatchProgress progress(stderr, "batch");
    runs = tcpmsim::sweep::run_batch(
        {options.configs, options.overrides, options.output_directory, options.jobs,
         static_cast<double>(options.max_output_bytes), options.invocation},
        std::make_shared<tcpmsim::UnitSystem>(), [&](std::size_t done, std::size_t total) {
          if (!options.quiet) progress.update(done, total);
        });
  }
  int failed = 0;
  for (const auto& run : runs) {
    if (run.outcome.succeeded) {
      if (!options.quiet)
        std::cout << "wrote " << run.outcome.output_path << " (" << run.config
                  << "): " << run.outcome.statistics.steps << " steps, " << run.outcome.wall_seconds
                  << " s wall\n";
    } else {
      ++failed;
      std::cerr << "tcpmsim: " << run.config << ": simulation failed: " << run.outcome.failure
                << "\ntcpmsim: the record up to the failure is in " << run.outcome.output_path
                << "\n";
    }
  }
  return failed > 0 ? kSimulationFailed : kSuccess;
}

// Refuses an output that is one of the command's own input files, which writing would replace.
void check_not_an_input(const std::string& output, const std::vector<std::string>& inputs) {
  for (const auto& input : inputs) {
    std::error_code error;
    if (std::filesystem::equivalent(output, input, error))
      throw tcpmsim::UsageError("-o " + output + " is " + input +
                                ", an input of this command: writing would replace it");
  }
}

int run(const Options& options) {
  if (options.configs.size() > 1) return run_batch(options);
  tcpmsim::Scenario scenario = tcpmsim::load_scenario(options.configs.front(), options.overrides,
                                                      std::make_shared<tcpmsim::UnitSystem>());
  if (warnings_stop(scenario, options)) return kConfigError;
  scenario.invocation = options.invocation;
  tcpmsim::check_record_size(scenario, static_cast<double>(options.max_output_bytes));
  const std::string output =
      options.output.empty() ? "results/" + scenario.settings.name + ".h5" : options.output;
  check_not_an_input(output, options.configs);
  // Nobody sets an external input in a run of its own: say what it holds.
  for (const auto& input : scenario.system->external_inputs()) {
    if (options.quiet) break;
    std::cerr << "tcpmsim: note: " << input.name
              << " is an external input (a master sets it step by step: tcpmsim.Simulator, an "
                 "FMU); this run holds its initial value\n";
  }
  tcpmsim::RunOutcome outcome;
  {
    const tcpmsim::InterruptGuard interrupts;
    tcpmsim::ProgressLine progress(stderr, scenario.settings.duration);
    auto report = [&](double time, long steps) {
      tcpmsim::InterruptGuard::stop_if_received();
      if (!options.quiet) progress.update(time, steps);
    };
    outcome = tcpmsim::run_scenario(scenario, output, report);
  }
  const auto& stats = outcome.statistics;
  if (outcome.interrupted) {
    std::cerr << "tcpmsim: " << outcome.failure << " at t = " << outcome.time_reached << " s\n"
              << "tcpmsim: the record up to there is in " << outcome.output_path << "\n";
    return 128 + tcpmsim::InterruptGuard::received();  // 130 (SIGINT) or 143 (SIGTERM)
  }
  if (!outcome.succeeded) {
    std::cerr << "tcpmsim: simulation failed: " << outcome.failure << "\n"
              << "tcpmsim: the record up to the failure is in " << outcome.output_path << "\n";
    return kSimulationFailed;
  }
  if (!options.quiet) {
    std::cout << "wrote " << outcome.output_path << ": " << stats.output_samples << " samples; "
              << stats.steps << " steps, " << stats.rhs_evaluations << " RHS evaluations, "
              << stats.jacobian_evaluations << " Jacobians, "
              << (stats.linear_iterations > 0
                      ? std::to_string(stats.linear_iterations) + " GMRES iterations, "
                      : std::string())
              << stats.error_test_failures << " error-test failures, "
              << stats.nonlinear_convergence_failures << " convergence failures, " << stats.segments
              << " segments; " << outcome.wall_seconds << " s wall\n";
  }
  return kSuccess;
}

// Every kind the registry holds, with the keys its examples read (sim/kind_listing.h).
int list_kinds(const Options& options) {
  if (options.discover_families) {
    for (const auto& family : tcpmsim::fit::effect_names()) std::cout << family << "\n";
    return kSuccess;
  }
  std::cout << tcpmsim::describe_kinds(tcpmsim::standard_kinds(),
                                       std::make_shared<tcpmsim::UnitSystem>(), options.markdown,
                                       tcpmsim::fit::describe_candidates);
  return kSuccess;
}

// Thesis ch. 2-3 on the measured coil-spring data (analysis/coil_fit_command.h).
int coil_fit(const Options& options) {
  tcpmsim::analysis::run_coil_fit(options.coil_fit, std::cout,
                                  std::make_shared<tcpmsim::UnitSystem>());
  return kSuccess;
}

// Thesis ch. 4: Table 4.2 and the modal checks (analysis/spring_forces_command.h).
int spring_forces(const Options& options) {
  tcpmsim::run_spring_forces_command(options.spring_forces, std::cout,
                                     std::make_shared<tcpmsim::UnitSystem>());
  return kSuccess;
}

// Thesis ch. 7: calibrated control tasks against section 7.4
// (analysis/control_tasks_command.h).
int control_tasks(const Options& options) {
  tcpmsim::run_control_tasks_command(options.control_tasks, std::cout,
                                     std::make_shared<tcpmsim::UnitSystem>());
  return kSuccess;
}

// Step metrics and frequency responses of any record (analysis/analyze_command.h).
int analyze(const Options& options) {
  try {
    tcpmsim::run_analyze_command(options.analyze, std::cout);
  } catch (const std::invalid_argument& error) {
    const std::string message = error.what();  // a record's path leads, else it is added
    throw tcpmsim::UsageError(message.rfind(options.analyze.record, 0) == 0
                                  ? message
                                  : options.analyze.record + ": " + message);
  }
  return kSuccess;
}

// A parameter study: the runs of a sweep file on threads, one HDF5 summary (sweep/).
int sweep(const Options& options) {
  auto units = std::make_shared<tcpmsim::UnitSystem>();
  const tcpmsim::sweep::SweepSpec spec =
      tcpmsim::sweep::load_sweep(options.config, options.overrides, units);
  tcpmsim::sweep::SweepOptions settings = options.sweep;
  if (settings.output.empty()) settings.output = "results/" + spec.name + ".h5";
  std::vector<std::string> inputs{options.config};
  for (const auto& scenario : spec.scenarios) inputs.push_back(scenario.file);
  check_not_an_input(settings.output, inputs);
  tcpmsim::sweep::SweepOutcome outcome;
  {
    tcpmsim::BatchProgress progress(stderr, "sweep");
    auto report = [&](std::size_t done, std::size_t total) {
      if (!options.quiet) progress.update(done, total);
    };
    // Started by mpirun (or srun): one rank of the job; rank 0 reports.
    outcome = tcpmsim::sweep::launched_by_mpi()
                  ? tcpmsim::sweep::run_sweep_mpi(spec, settings, units, report)
                  : tcpmsim::sweep::run_sweep(spec, settings, units, report);
  }
  if (!options.quiet && tcpmsim::sweep::launched_rank() == 0) {
    std::cout << tcpmsim::sweep::sweep_table(spec, outcome.output);
    std::cout << "wrote " << outcome.output << ": " << outcome.runs << " runs";
    if (outcome.resumed > 0) std::cout << " (" << outcome.resumed << " done before the resume)";
    std::cout << ", " << outcome.failed << " failed\n";
  }
  // Complete either way; a run that failed is in the summary with its message.
  return outcome.failed > 0 ? kSimulationFailed : kSuccess;
}

// A command's output directory, made before its work so that one that cannot be written is
// refused first (one that exists is tried with a file of its own, made and removed: a read-only
// directory or file system would otherwise fail only when the results are written, after
// minutes of fitting); whether it was made here (and may be removed again when the work fails).
bool make_output_directory(const std::string& directory) {
  const bool existed = std::filesystem::exists(directory);
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error) throw std::runtime_error("cannot write " + directory + ": " + error.message());
  const std::string probe =
      (std::filesystem::path(directory) / (".tcpmsim_write_check_" + std::to_string(::getpid())))
          .string();
  const int descriptor = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (descriptor < 0)
    throw std::runtime_error("cannot write into " + directory + ": " + std::strerror(errno));
  ::close(descriptor);
  std::filesystem::remove(probe, error);
  return !existed;
}

// Removes a directory this command made when its work failed before writing into it: an empty
// output directory would look like a result.
void remove_if_empty(const std::string& directory) {
  std::error_code ignored;
  if (std::filesystem::is_empty(directory, ignored)) std::filesystem::remove(directory, ignored);
}

// Output-error identification: a model's parameters from a measurement (identification/).
int fit(const Options& options) {
  auto units = std::make_shared<tcpmsim::UnitSystem>();
  const tcpmsim::fit::FitSpec spec = tcpmsim::fit::load_fit(options.config, options.overrides,
                                                            options.data, options.fit_jobs, units);
  const std::string directory =
      options.fit_directory.empty()
          ? "results/fit_" + std::filesystem::path(spec.model_file).stem().string()
          : options.fit_directory;
  const bool made = make_output_directory(directory);
  tcpmsim::fit::FitResult result;
  try {
    result = tcpmsim::fit::fit_model(spec.problem, spec.settings);
  } catch (const tcpmsim::fit::FitFailure& failure) {
    std::cerr << "tcpmsim: the fit failed: " << failure.what() << "\n";
    if (made) remove_if_empty(directory);
    return kSimulationFailed;
  }
  const auto written = tcpmsim::fit::write_fit_outputs(
      directory, spec, result,
      tcpmsim::file_provenance(options.invocation, {spec.file, spec.model_file}, {}, units));
  if (!options.quiet) {
    std::cout << tcpmsim::fit::fit_summary(spec, result);
    for (const auto& file : written) std::cout << "wrote " << file << "\n";
  }
  return kSuccess;
}

// The plotting script: the one TCPMSIM_PLOT_TOOL names (the wheel's console script sets it to
// the tcpmsim-plot installed beside it), else beside the program when installed
// (bin/tcpmsim-plot), else the source tree's tools/tcpmsim-plot.
std::string plot_tool() {
  if (const char* named = std::getenv("TCPMSIM_PLOT_TOOL"); named && *named) return named;
  std::error_code error;
  const auto program = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error) {
    const auto beside = program.parent_path() / "tcpmsim-plot";
    if (std::filesystem::is_regular_file(beside, error)) return beside.string();
  }
  return TCPMSIM_PLOT_TOOL;
}

// A discover run's files, its summary, and its plots, drawn by a child process: what this one
// printed goes out first, so that a pipe keeps the order. A picture that cannot be drawn is a
// warning: the analysis is written and stands without it.
void write_discover_run(const Options& options, const tcpmsim::fit::Discovery& discovery,
                        const std::string& directory,
                        const std::shared_ptr<const tcpmsim::UnitSystem>& units) {
  const auto& request = discovery.setup.request;
  const auto written = tcpmsim::fit::write_discovery(
      directory, discovery,
      tcpmsim::file_provenance(options.invocation, {request.model_file}, request.overrides, units));
  if (!options.quiet) {
    std::cout << tcpmsim::fit::discovery_summary(discovery);
    for (const auto& file : written) std::cout << "wrote " << file << "\n";
  }
  if (!options.plots) return;
  std::cout.flush();
  std::cerr.flush();
  const std::string command =
      "'" + plot_tool() + "' discovery '" + directory + "' -o '" + directory + "'";
  if (std::system(command.c_str()) != 0) {
    std::cerr << "tcpmsim: warning: the plots of " << directory << " could not be drawn ("
              << command << "); the analysis is complete without them (--no-plots leaves "
              << "them out)\n";
  } else if (!options.quiet) {
    std::cout << "wrote " << directory << "/residuals.png, " << directory << "/diagnostic.png\n";
  }
}

// After --max-effects named two or more effects: all of them refitted together with the base
// laws, into <out>/joint (fit.json, fitted.yaml, fit.h5). A refit that cannot be made is a
// warning: the runs' model stands.
std::optional<tcpmsim::fit::JointRefit> refit_named_effects(
    const Options& options, const tcpmsim::fit::DiscoverRequest& request,
    const std::vector<tcpmsim::fit::EffectRun>& runs, const std::string& directory,
    const std::shared_ptr<const tcpmsim::UnitSystem>& units) {
  if (!tcpmsim::fit::joint_refit_due(runs)) return std::nullopt;
  if (!options.quiet) {
    std::cout << "\nrefitting the named effects together with the base laws\n";
    std::cout.flush();
  }
  auto joint = tcpmsim::fit::refit_jointly(request, runs, directory, units);
  if (joint.failure.empty()) {
    try {
      tcpmsim::fit::write_fit_outputs(
          joint.directory, joint.spec, joint.result,
          tcpmsim::file_provenance(options.invocation, {joint.start_model}, {}, units));
    } catch (const std::exception& error) {
      joint.failure = std::string("its files: ") + error.what();
      joint.better = false;
    }
  }
  if (!joint.failure.empty()) {
    std::cerr << "tcpmsim: warning: the joint refit of the named effects failed: " << joint.failure
              << "; the runs' model stands\n";
  }
  return joint;
}

// The missing effect: a base model fitted, diagnosed, and refitted with each named effect; with
// --max-effects N, again from the model with it while that still misses the noise floor.
int discover(const Options& options) {
  auto units = std::make_shared<tcpmsim::UnitSystem>();
  tcpmsim::fit::DiscoverRequest request = options.discover;
  request.threads = options.fit_jobs;
  request.overrides = options.overrides;
  const tcpmsim::fit::DiscoverSetup setup = tcpmsim::fit::setup_discovery(request, units);
  const std::string& directory = options.fit_directory;
  tcpmsim::fit::check_outside_effect_runs(request, directory, options.max_effects);
  const bool made = make_output_directory(directory);
  if (!options.quiet)
    for (const auto& earlier : tcpmsim::fit::earlier_effect_runs(directory))
      std::cout << "removing " << earlier << " (an earlier discover with --max-effects)\n";
  std::vector<tcpmsim::fit::EffectRun> runs;
  try {
    runs = tcpmsim::fit::discover_effects(
        setup, options.max_effects, directory,
        [&](const tcpmsim::fit::Discovery& discovery, const std::string& run_directory) {
          write_discover_run(options, discovery, run_directory, units);
        },
        [&](int number, const std::string& run_directory, const std::string& model) {
          if (options.quiet) return;
          std::cout << "\nrun " << number << " of at most " << options.max_effects
                    << " (--max-effects): discover again from " << model << " into "
                    << run_directory << "\n";
          std::cout.flush();
        });
  } catch (const tcpmsim::fit::FitFailure& failure) {
    std::cerr << "tcpmsim: the base model's fit failed: " << failure.what() << "\n";
    if (made) remove_if_empty(directory);
    return kSimulationFailed;
  }
  if (runs.back().verdict == "failed")
    std::cerr << "tcpmsim: warning: run " << runs.back().number << " of discover (--max-effects) "
              << "failed: " << runs.back().failure << "; the runs before it stand\n";
  if (options.max_effects > 1) {
    const auto joint = refit_named_effects(options, request, runs, directory, units);
    const auto* refit = joint ? &*joint : nullptr;
    const std::string path = (std::filesystem::path(directory) / "effects.json").string();
    std::ofstream file(path);
    file << tcpmsim::fit::effect_runs_json(runs, options.max_effects, refit);
    if (!file) throw std::runtime_error("cannot write " + path);
    if (!options.quiet)
      std::cout << tcpmsim::fit::effect_runs_summary(runs, options.max_effects, refit) << "wrote "
                << path << "\n";
  }
  // The first run's verdict: an effect named (0), the base model at the noise floor, or a miss
  // no candidate explains. What later runs found is in effects.json.
  const std::string& first = runs.front().verdict;
  if (runs.front().named) return kSuccess;
  return first == "none" ? kVerdictNone : kVerdictUnexplained;
}

// A synthetic measurement: a scenario read by a bench's instruments, written as a CSV file.
int recover(const Options& options) {
  const tcpmsim::RecoveredRecord recovered =
      tcpmsim::recover_partial_record(options.config, options.recover_output);
  if (!options.quiet) {
    std::cout << "wrote " << recovered.path << ": " << recovered.samples
              << " samples, up to t = " << recovered.time_reached << " s (status interrupted)\n";
  }
  return kSuccess;
}

int measure(const Options& options) {
  auto units = std::make_shared<tcpmsim::UnitSystem>();
  const tcpmsim::Scenario scenario = load(options);
  const tcpmsim::fit::Bench bench = tcpmsim::fit::load_bench(options.bench, scenario, units);
  tcpmsim::check_record_size(scenario, tcpmsim::kDefaultRecordLimit);  // its samples, in memory
  const std::string output =
      options.output.empty() ? "results/" + scenario.settings.name + ".csv" : options.output;
  check_not_an_input(output, {options.config, options.bench});
  tcpmsim::prepare_output_file(output);  // before the run, as `run` checks its record's path
  const std::string partial = tcpmsim::partial_path(output);
  std::string measured;
  try {
    measured = tcpmsim::fit::measure(scenario, bench, *units);
  } catch (const tcpmsim::SolverFailure& failure) {
    std::filesystem::remove(partial);  // the empty file of the check: nothing was measured
    std::cerr << "tcpmsim: simulation failed: " << failure.what()
              << "\ntcpmsim: no measurement was written\n";
    return kSimulationFailed;
  } catch (...) {
    std::filesystem::remove(partial);
    throw;
  }
  {
    std::ofstream file(partial);
    if (!file) throw std::runtime_error("cannot write " + partial);
    file << measured;
    if (!file) throw std::runtime_error("cannot write " + partial);
  }
  std::filesystem::rename(partial, output);
  if (!options.quiet) std::cout << "wrote " << output << "\n";
  return kSuccess;
}

int report_errors(int (*command)(const Options&), const Options& options);

int export_fmu(const Options& options) {
  return tcpmsim::cli::export_fmu(options.export_fmu);
}

// Under an MPI launcher every rank meets the same bad input: rank 0 alone says so.
int guarded(int (*command)(const Options&), const Options& options) {
  if (tcpmsim::sweep::launched_rank() == 0) return report_errors(command, options);
  const int saved = dup(fileno(stderr));
  std::freopen("/dev/null", "w", stderr);
  const int code = report_errors(command, options);
  std::fflush(stderr);
  dup2(saved, fileno(stderr));
  close(saved);
  return code;
}

int report_errors(int (*command)(const Options&), const Options& options) {
  try {
    return command(options);
  } catch (const tcpmsim::ConfigError& error) {
    std::cerr << tcpmsim::printable(error.what()) << "\n";
    return kConfigError;
  } catch (const tcpmsim::UnitError& error) {
    std::cerr << "tcpmsim: " << tcpmsim::printable(error.what()) << "\n";
    return kConfigError;
  } catch (const tcpmsim::ParameterError& error) {
    std::cerr << "tcpmsim: error: " << tcpmsim::printable(error.what()) << "\n";
    return kConfigError;
  } catch (const tcpmsim::UsageError& error) {
    std::cerr << "tcpmsim: " << tcpmsim::printable(error.what()) << "\n";
    return kUsageError;
  } catch (const std::runtime_error& error) {
    std::cerr << "tcpmsim: " << tcpmsim::printable(error.what()) << "\n";
    return kOutputError;
  } catch (const std::exception& error) {
    std::cerr << "tcpmsim: internal error: " << tcpmsim::printable(error.what()) << "\n";
    return kInternalError;
  } catch (...) {  // a library's own exception type (HDF5's) that nothing turned into a message
    std::cerr << "tcpmsim: internal error: an unexpected exception\n";
    return kInternalError;
  }
}

void add_common(CLI::App& command, Options& options) {
  command.add_option("config", options.config, "Scenario file (YAML)")
      ->required()
      ->check(CLI::ExistingFile);
  command
      .add_option("--set", options.overrides,
                  "Override a value, e.g. --set 'muscle.mechanics.k1=12 N/m' (repeatable)")
      ->type_name("KEY.PATH=VALUE");
}

// A thesis analysis: a sub-command over a list of input files, writing one HDF5 file and
// printing its tables unless quiet.
struct AnalysisInputs {
  const char* name;
  const char* description;
  std::vector<std::string>& files;
};

CLI::App* add_analysis(CLI::App& app, const char* name, const char* description,
                       AnalysisInputs inputs, std::string& output, const char* default_output,
                       bool& quiet) {
  CLI::App* command = app.add_subcommand(name, description);
  command->add_option(inputs.name, inputs.files, inputs.description)
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("-o,--output", output,
                      std::string("Output file (default: ") + default_output + ")");
  command->add_flag("-q,--quiet", quiet, "No tables");
  return command;
}

// A time on the command line: a finite number of seconds (CLI11 reads "nan" and "inf" as numbers).
CLI::Validator finite_time() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double value = 0.0;
        if (CLI::detail::lexical_cast(text, value) && std::isfinite(value)) return "";
        return "expected a time in s, a finite number, got '" + text + "'";
      },
      "TIME");
}

// The command line as typed, each argument that needs it in single quotes: a file's provenance.
std::string invocation_text(int argc, char** argv) {
  std::string text;
  for (int k = 0; k < argc; ++k) {
    const std::string argument = argv[k];
    const bool plain =
        !argument.empty() && argument.find_first_not_of(
                                 "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                 "0123456789-_./=:,+@%") == std::string::npos;
    if (k > 0) text += ' ';
    if (plain) {
      text += argument;
      continue;
    }
    text += '\'';
    for (const char c : argument) text += c == '\'' ? std::string("'\\''") : std::string(1, c);
    text += '\'';
  }
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "tcpmsim: simulator of Joule-heated twisted and coiled polymer muscles and "
      "self-sensing coil actuators"};
  app.set_version_flag(
      "--version", std::string("tcpmsim ") + tcpmsim::kVersion + " (" + tcpmsim::kGitCommit + ")");
  app.require_subcommand(1);
  Options options;
  options.invocation = invocation_text(argc, argv);
  options.analyze.invocation = options.coil_fit.invocation = options.spring_forces.invocation =
      options.control_tasks.invocation = options.sweep.invocation = options.invocation;

  CLI::App* run_command =
      app.add_subcommand("run", "Simulate scenarios and write an HDF5 record of each");
  run_command
      ->add_option("config", options.configs,
                   "Scenario files (YAML); several run as a batch on --jobs threads")
      ->required()
      ->check(CLI::ExistingFile);
  run_command
      ->add_option("--set", options.overrides,
                   "Override a value (in every scenario), e.g. --set 'muscle.mechanics.k1=12 N/m' "
                   "(repeatable)")
      ->type_name("KEY.PATH=VALUE");
  run_command->add_option("-j,--jobs", options.jobs, "Scenarios in parallel (threads)")
      ->check(CLI::Range(1, 256));
  run_command->add_option("--output-dir", options.output_directory,
                          "Where several scenarios' records go (default: results)");
  run_command->add_option("-o,--output", options.output,
                          "Output file (default: results/<scenario name>.h5)");
  run_command->add_flag("-q,--quiet", options.quiet, "No progress line or summary");
  run_command->add_flag("--strict", options.strict,
                        "Values outside their typical range are errors, not warnings");
  run_command
      ->add_option("--max-output-size", options.max_output_bytes,
                   "Refuse a record larger than this before running, uncompressed (e.g. 500MB, "
                   "20GB; default 2GB)")
      ->transform(CLI::AsSizeValue(true));

  CLI::App* recover_command = app.add_subcommand(
      "recover", "Turn the <out>.partial of a killed run into <out stem>.interrupted.h5");
  recover_command->add_option("partial", options.config, "The .partial file")
      ->required()
      ->check(CLI::ExistingFile);
  recover_command->add_option("-o,--output", options.recover_output,
                              "The record (default: <out stem>.interrupted.h5)");
  recover_command->add_flag("-q,--quiet", options.quiet, "No summary");

  CLI::App* validate_command =
      app.add_subcommand("validate", "Check a scenario file and list its states and outputs");
  add_common(*validate_command, options);
  validate_command->add_flag("--strict", options.strict,
                             "Values outside their typical range are errors, not warnings");

  bool markdown = false;
  bool families = false;
  CLI::App* kinds_command = app.add_subcommand(
      "kinds", "List every kind of component and signal a scenario may name, with its keys");
  kinds_command->add_flag("--markdown", markdown, "Markdown tables (docs/reference/kinds.md)");
  kinds_command->add_flag("--discover-families", families,
                          "Only the effect families discover tries, one per line, in its order "
                          "(as the kinds declare them)");

  CLI::App* coil_fit_command =
      add_analysis(app, "coil-fit",
                   "Thesis Tables 2.2/2.3 and the ch. 3 comparison from measured coil-spring data",
                   {"springs", "Spring files (YAML)", options.coil_fit.spring_files},
                   options.coil_fit.output, "results/coil_fit.h5", options.coil_fit.quiet);
  coil_fit_command
      ->add_option("--data", options.coil_fit.data_directory,
                   "Directory of the sequence files <name>.csv (default: the one each spring "
                   "file names under 'data', from that file's directory: the thesis' data)")
      ->check(CLI::ExistingDirectory);

  CLI::App* spring_forces_command = add_analysis(
      app, "spring-forces",
      "Thesis Table 4.2: force sensing on an oscillating coil spring, and modal checks",
      {"configs", "Chapter-4 scenarios (YAML)", options.spring_forces.configs},
      options.spring_forces.output, "results/spring_forces.h5", options.spring_forces.quiet);
  spring_forces_command
      ->add_option("--window", options.spring_forces.window, "Analysed tail of each run [s]")
      ->check(CLI::PositiveNumber);
  spring_forces_command
      ->add_option("--threads", options.spring_forces.threads, "Simulations in parallel")
      ->check(CLI::Range(1, 64));

  CLI::App* control_tasks_command = add_analysis(
      app, "control-tasks",
      "Thesis ch. 7: calibrate, run the control tasks, compare with section 7.4",
      {"configs", "Control-task scenarios (YAML)", options.control_tasks.configs},
      options.control_tasks.output, "results/control_tasks.h5", options.control_tasks.quiet);
  control_tasks_command
      ->add_option("--set", options.control_tasks.settings.overrides,
                   "Override a value in every run, e.g. --set drive.fidelity=switched")
      ->type_name("KEY.PATH=VALUE");
  control_tasks_command->add_flag(
      "--no-calibration", [&](std::int64_t) { options.control_tasks.settings.calibrate = false; },
      "Skip the calibration runs of section 7.3.4");
  control_tasks_command
      ->add_option("--threads", options.control_tasks.settings.threads, "Tasks in parallel")
      ->check(CLI::Range(1, 64));

  auto& analysis = options.analyze;
  CLI::App* analyze_command = app.add_subcommand(
      "analyze", "Step metrics and frequency response (Bode, -3 dB) of any channel of a record");
  analyze_command
      ->add_option("record", analysis.record, "An HDF5 record (tcpmsim run, Result.save)")
      ->required()
      ->check(CLI::ExistingFile);
  analyze_command->add_option(
      "-o,--output", analysis.output,
      "Output file (default: results/<record stem>_<response>_analysis.h5, or _steps.h5 with "
      "--reference)");
  analyze_command->add_flag("-q,--quiet", analysis.quiet, "No tables");
  analyze_command->add_option("--response", analysis.request.output, "The channel analysed")
      ->required()
      ->type_name("GROUP/NAME");
  analyze_command
      ->add_option("--reference", analysis.request.reference,
                   "Step metrics against this channel (rise, settling, overshoot, steady-state "
                   "error per step)")
      ->type_name("GROUP/NAME");
  analyze_command
      ->add_option("--input", analysis.request.inputs,
                   "Frequency response from this input (repeat for several); default without "
                   "--reference: every prescribed input the window excites")
      ->type_name("GROUP/NAME");
  analyze_command->add_option("--from", analysis.request.from, "Window start [s]")
      ->check(finite_time());
  analyze_command->add_option("--to", analysis.request.to, "Window end [s]")->check(finite_time());
  analyze_command
      ->add_option("--method", analysis.request.method,
                   "auto (lines for multisines, else spectral), lines or spectral")
      ->check(CLI::IsMember({"auto", "lines", "spectral"}));
  analyze_command
      ->add_option("--segment", analysis.request.segment,
                   "Spectral estimate's segment length [s] (default: a quarter of the window)")
      ->check(CLI::PositiveNumber);
  analyze_command
      ->add_option("--rise", analysis.request.steps.rise.upper,
                   "Rise time from 1 - RISE to RISE of the step (default 0.9)")
      ->check(CLI::Range(0.5, 1.0))
      ->each([&](const std::string&) {
        analysis.request.steps.rise.lower = 1.0 - analysis.request.steps.rise.upper;
      });
  analyze_command
      ->add_option("--settling-band", analysis.request.steps.settling_band,
                   "Settled within this fraction of the step (default 0.02)")
      ->check(CLI::Range(1e-6, 0.5));

  CLI::App* sweep_command = app.add_subcommand(
      "sweep", "Run a parameter study from a sweep file: one HDF5 summary, optionally traces");
  sweep_command->add_option("sweep", options.config, "Sweep file (YAML)")
      ->required()
      ->check(CLI::ExistingFile);
  sweep_command
      ->add_option("--set", options.overrides,
                   "Override a value of the sweep file, e.g. --set store.traces=full")
      ->type_name("KEY.PATH=VALUE");
  sweep_command->add_option("-o,--output", options.sweep.output,
                            "Output file (default: results/<sweep name>.h5)");
  sweep_command->add_option("-j,--jobs", options.sweep.threads, "Runs in parallel (threads)")
      ->check(CLI::Range(1, 256));
  sweep_command->add_flag("--resume", options.sweep.resume,
                          "Finish an interrupted sweep: redo only the runs not done");
  sweep_command->add_flag("-q,--quiet", options.quiet, "No progress or summary");

  CLI::App* discover_command = app.add_subcommand(
      "discover",
      "Find the effect a model lacks: fit it, locate where it disagrees with the data, refit "
      "it with each named effect, rank them (BIC, validation error) and name the missing one");
  auto& request = options.discover;
  discover_command->add_option("--model", request.model_file, "Base model (scenario YAML)")
      ->required()
      ->check(CLI::ExistingFile);
  discover_command->add_option("--data", request.data_file, "The measurement (CSV or record)")
      ->required()
      ->check(CLI::ExistingFile);
  discover_command->add_option("--inputs", request.inputs, "Channels the model replays")
      ->required()
      ->delimiter(',');
  discover_command
      ->add_option("--outputs", request.outputs,
                   "Channels compared: force, or force=load.force to name the model output")
      ->required()
      ->delimiter(',');
  discover_command
      ->add_option("--validate-from", request.validate_from,
                   "Time [s] the validation window starts; the identification window ends there")
      ->required();
  discover_command->add_option("--out", options.fit_directory, "Output directory")->required();
  discover_command
      ->add_option("--parameters", request.parameters,
                   "Base-model parameters to fit (default: thermal, SLS and coil laws')")
      ->delimiter(',');
  discover_command
      ->add_option(
          "--effects", request.effects,
          "Candidates (default: every family; tcpmsim kinds --discover-families lists them)")
      ->delimiter(',');
  discover_command
      ->add_option("--max-order", request.max_order,
                   "Highest model order tried within a family (elements, branches; 0: all)")
      ->check(CLI::Range(0, 100));
  discover_command
      ->add_option("--noise", request.noise,
                   "Noise floor of an output, e.g. force=2 mN (default: estimated from the data)")
      ->delimiter(',');
  discover_command
      ->add_option("--floor-margin", request.floor_margin,
                   "`none` needs each base validation RMSE within this fraction above its floor")
      ->check(CLI::Range(0.0, 10.0));
  discover_command
      ->add_option(
          "--min-gap-closed", request.min_gap_closed,
          "Share of the gap above the noise floor a named effect must close: of the outputs "
          "the base model misses, or of all combined where it misses none")
      ->check(CLI::Range(0.0, 1.0));
  discover_command->add_option("--set", options.overrides, "Override a value of the model")
      ->type_name("KEY.PATH=VALUE");
  discover_command->add_option("--starts", request.starts, "Multistart points per fit")
      ->check(CLI::Range(0, 1000));
  discover_command->add_option("--seed", request.seed, "Seed of the multistart");
  discover_command
      ->add_option("--bic-threshold", request.bic_threshold,
                   "BIC decrease a significant effect must exceed")
      ->check(CLI::NonNegativeNumber);
  discover_command
      ->add_option("--min-signature", request.min_signature,
                   "Matched-filter z a significant effect's change to the outputs must reach "
                   "against the base model's validation residual")
      ->check(CLI::NonNegativeNumber);
  discover_command
      ->add_option("--alias-correlation", request.alias_correlation,
                   "Significant candidates within the BIC threshold of the best whose validation "
                   "changes correlate by at least this are aliases")
      ->check(CLI::Range(0.0, 1.0));
  discover_command->add_flag(
      "--despike-all", request.despike_all,
      "Replace spikes in every compared output, not only the coil's measure");
  discover_command
      ->add_option("--max-effects", options.max_effects,
                   "Effects sought, one a run: while the model with the named effect still "
                   "misses the noise floor, discover again from it (into <out>/effect2, ...); "
                   "two or more named are refitted together (into <out>/joint)")
      ->check(CLI::Range(1, 10));
  discover_command->add_option("-j,--jobs", options.fit_jobs, "Candidates fitted at once (threads)")
      ->check(CLI::Range(1, 256));
  discover_command->add_flag(
      "--no-plots", [&](std::int64_t) { options.plots = false; },
      "Leave out residuals.png and diagnostic.png");
  discover_command->add_flag("-q,--quiet", options.quiet, "No summary");

  CLI::App* measure_command = app.add_subcommand(
      "measure", "Run a scenario and read it with a bench's instruments: a measurement CSV");
  add_common(*measure_command, options);
  measure_command->add_option("--bench", options.bench, "Bench file (YAML): channels, noise")
      ->required()
      ->check(CLI::ExistingFile);
  measure_command->add_option("-o,--output", options.output,
                              "Output file (default: results/<scenario name>.csv)");
  measure_command->add_flag("-q,--quiet", options.quiet, "No summary");

  CLI::App* fit_command = app.add_subcommand(
      "fit", "Fit a model's parameters to a measurement (output error, Levenberg-Marquardt)");
  fit_command->add_option("fit", options.config, "Fit file (YAML)")
      ->required()
      ->check(CLI::ExistingFile);
  fit_command->add_option("--data", options.data, "The measurement (CSV or a tcpmsim record)")
      ->check(CLI::ExistingFile);
  fit_command->add_option("--set", options.overrides, "Override a value of the fit file")
      ->type_name("KEY.PATH=VALUE");
  fit_command->add_option("--out", options.fit_directory,
                          "Directory for fit.json, fitted.yaml, fit.h5 (default: "
                          "results/fit_<model>)");
  fit_command
      ->add_option("-j,--jobs", options.fit_jobs,
                   "Simulations in parallel (threads; default: the hardware's)")
      ->check(CLI::Range(1, 256));
  fit_command->add_flag("-q,--quiet", options.quiet, "No summary");

  CLI::App* export_fmu_command = tcpmsim::cli::add_export_fmu(app, options.export_fmu);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error);
    return code == 0 ? kSuccess : kUsageError;
  }
  if (run_command->parsed()) return guarded(run, options);
  if (recover_command->parsed()) return guarded(recover, options);
  if (kinds_command->parsed()) {
    options.markdown = markdown;
    options.discover_families = families;
    return guarded(list_kinds, options);
  }
  if (coil_fit_command->parsed()) return guarded(coil_fit, options);
  if (spring_forces_command->parsed()) return guarded(spring_forces, options);
  if (control_tasks_command->parsed()) return guarded(control_tasks, options);
  if (sweep_command->parsed()) return guarded(sweep, options);
  if (analyze_command->parsed()) return guarded(analyze, options);
  if (fit_command->parsed()) return guarded(fit, options);
  if (measure_command->parsed()) return guarded(measure, options);
  if (discover_command->parsed()) return guarded(discover, options);
  if (export_fmu_command->parsed()) return guarded(export_fmu, options);
  return guarded(validate, options);
}
