#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sim/context.h"
#include "sim/integrator.h"
#include "sim/memory_run.h"
#include "sim/scenario.h"

namespace tcpmsim {

// A run of a scenario that advances on request, for a controller that lives outside the system:
// a Python function (tcpmsim.Simulator), an FMU's master (tcpmsim export-fmu), a C++ loop.
//
//   StepSimulator simulator(scenario);           // at t = 0, the first instant half taken
//   while (simulator.time() < simulator.end_time()) {
//     const double force = simulator.output("estimator.force");
//     simulator.set_input("controller.power_command", my_law(force));
//     simulator.advance_to(simulator.time() + 0.05);
//   }
//   simulator.save("run.h5");                    // the record `tcpmsim run` would write
//
// Its inputs are the system's external inputs (a controller section of type external). Each
// call stops at the time asked for (a breakpoint of the run) with the instant there half taken:
// the instruments have measured and the estimators acted, so the outputs read are those a
// controller component would sample; an input set then is held from that instant on, and the
// controllers and actuators of the system act on it when the next call starts (System::
// begin_instant, end_instant). A loop that sets at the drive's sample instants what the
// built-in PID would command therefore reproduces the PID's run bit for bit.
//
// Between calls CVODE restarts (warm or cold as the scenario's solver says), as it does at any
// breakpoint of a run. The record is kept in memory, laid out as tcpmsim run's.
class StepSimulator {
 public:
  explicit StepSimulator(Scenario scenario);
  StepSimulator(const StepSimulator&) = delete;
  StepSimulator& operator=(const StepSimulator&) = delete;
  ~StepSimulator();

  const Scenario& scenario() const { return scenario_; }
  double time() const;
  double end_time() const { return scenario_.settings.duration; }
  bool finished() const { return time() >= end_time(); }

  // The external inputs, "group.name" with their units; the range an input may take in this run.
  const std::vector<ExternalInputInfo>& inputs() const;
  std::pair<double, double> input_range(std::string_view input) const;
  // Holds `value` (SI) on the input from now on. Throws std::invalid_argument for an unknown
  // input or a value outside its range, std::logic_error after the end.
  void set_input(std::string_view input, double value);
  double input(std::string_view input) const;  // the value held now

  // Integrates to `time` (at most end_time()). Throws std::invalid_argument for a time before
  // time() or after the end, SolverFailure when CVODE fails (the run then stays failed: reset).
  void advance_to(double time);
  // Advances by dt (> 0; at most to the end). Equal steps since a reset, or since the time
  // reached was a multiple of dt, land on the grid k dt exactly rather than on a sum of dt's, so
  // a master's samples fall on a sampled component's instants (a 20 Hz drive's).
  void step(double dt);

  // An output "group.name" (channels of a bundle's members: "b/m003/muscle.force") or a state
  // "group.state" at time(). Throws std::invalid_argument naming the unknown name.
  double output(std::string_view name) const;
  double state(std::string_view name) const;
  // Every output at time(), indexed as System::channels().
  const std::vector<double>& signals() const { return context_->signals(); }

  // Sets a parameter by path, in SI, for the runs that start at the next reset(); throws
  // ParameterError as Context::set_parameter does.
  void set_parameter(std::string_view path, double value);
  double parameter(std::string_view path) const { return context_->parameter(path); }
  // Starts again at t = 0 with the scenario's parameters and those set since.
  void reset();

  // The run so far, laid out as its HDF5 record; "complete" once time() reached the end,
  // "interrupted" (at time()) before it, "failed" after a solver failure.
  const MemoryRun& record() const;
  // Writes it as tcpmsim run writes its record; returns the path written (a run not at its end:
  // <stem>.interrupted.h5).
  std::string save(const std::string& path) const;

 private:
  int input_index(std::string_view input) const;
  void start();

  Scenario scenario_;
  std::vector<std::pair<std::string, double>> parameters_;  // set since construction
  std::unique_ptr<Context> context_;
  std::unique_ptr<MemoryRun> run_;
  std::unique_ptr<OutputSink> sink_;
  std::unique_ptr<Integrator> integrator_;
  std::vector<double> held_;  // per external input
  double grid_step_ = 0.0;    // step(): the dt of the grid, and the samples on it so far
  long grid_samples_ = -1;    // (-1: the time reached is off the grid)
  bool failed_ = false;
};

}  // namespace tcpmsim
