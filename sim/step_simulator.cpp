#include "sim/step_simulator.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "sim/config/config_error.h"
#include "sim/io/record_layout.h"
#include "sim/run.h"
#include "sim/value_check.h"

namespace tcpmsim {

StepSimulator::StepSimulator(Scenario scenario) : scenario_(std::move(scenario)) {
  check_record_size(scenario_, kDefaultRecordLimit);
  start();
}

StepSimulator::~StepSimulator() = default;

void StepSimulator::start() {
  // The new run is made whole before it replaces the old one: a reset that fails (parameters
  // that do not make a run) leaves the simulator as it was.
  auto context = std::make_unique<Context>(scenario_.make_context());
  for (const auto& [path, value] : parameters_) context->set_parameter(path, value);
  auto run = std::make_unique<MemoryRun>();
  run->series = record_layout(*scenario_.system);
  run->values.resize(run->series.size());
  auto sink = std::make_unique<MemoryRunSink>(*run);
  scenario_.system->prepare(*context);
  auto integrator = std::make_unique<Integrator>(*scenario_.system, *context, scenario_.solver);
  integrator->begin(0.0, end_time(),
                    {scenario_.settings.output_interval, scenario_.settings.output_start}, *sink,
                    Integrator::InstantSplit::held);
  // The integrator refers to the context and the sink: it goes first.
  integrator_ = std::move(integrator);
  sink_ = std::move(sink);
  run_ = std::move(run);
  context_ = std::move(context);
  failed_ = false;
  // What each holder starts with: its output of the same name (Component::external_inputs).
  held_.clear();
  for (const ExternalInputInfo& info : inputs()) held_.push_back(output(info.name));
}

double StepSimulator::time() const {
  return integrator_->time();
}

const std::vector<ExternalInputInfo>& StepSimulator::inputs() const {
  return scenario_.system->external_inputs();
}

int StepSimulator::input_index(std::string_view input) const {
  const auto& all = inputs();
  for (std::size_t i = 0; i < all.size(); ++i)
    if (all[i].name == input) return static_cast<int>(i);
  std::string known;
  for (const auto& info : all) known += (known.empty() ? "" : ", ") + info.name;
  throw std::invalid_argument("no external input '" + std::string(input) + "'" +
                              (known.empty() ? std::string(" (the scenario has none: give it a "
                                                           "controller of type external)")
                                             : "; the scenario's: " + known));
}

std::pair<double, double> StepSimulator::input_range(std::string_view input) const {
  return scenario_.system->external_input_range(*context_, input_index(input));
}

void StepSimulator::set_input(std::string_view input, double value) {
  const int index = input_index(input);
  if (failed_) throw std::logic_error("the run failed; reset() to start again");
  if (finished()) throw std::logic_error("the run has reached its end; reset() to start again");
  scenario_.system->hold_external_input(*context_, index, value);
  held_[static_cast<std::size_t>(index)] = value;
}

double StepSimulator::input(std::string_view input) const {
  return held_[static_cast<std::size_t>(input_index(input))];
}

void StepSimulator::step(double dt) {
  if (!(dt > 0.0)) throw std::invalid_argument("step: dt must be positive, got " + number_text(dt));
  const double now = time();
  if (dt != grid_step_ || now != static_cast<double>(grid_samples_) * grid_step_) {
    grid_step_ = dt;
    grid_samples_ = std::llround(now / dt);
    if (static_cast<double>(grid_samples_) * dt != now) grid_samples_ = -1;
  }
  const double target = grid_samples_ >= 0 ? static_cast<double>(grid_samples_ + 1) * dt : now + dt;
  advance_to(std::min(target, end_time()));
  if (grid_samples_ >= 0) ++grid_samples_;
}

void StepSimulator::advance_to(double time) {
  if (failed_) throw std::logic_error("the run failed; reset() to start again");
  const double now = integrator_->time();
  if (!(time >= now)) {
    throw std::invalid_argument("cannot advance to t = " + number_text(time) +
                                " s: the run is at t = " + number_text(now) + " s");
  }
  if (time > end_time() * (1.0 + 1e-12)) {
    throw std::invalid_argument("cannot advance to t = " + number_text(time) +
                                " s: the scenario ends at " + number_text(end_time()) + " s");
  }
  if (time == now) return;
  const auto started = std::chrono::steady_clock::now();
  try {
    integrator_->advance(std::min(time, end_time()));
  } catch (const RunEnded& ended) {
    failed_ = true;
    run_->status = "failed";
    run_->reason = ended.what();
    run_->time_reached = ended.time();
    run_->statistics = ended.statistics();
    throw;
  }
  run_->wall_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
}

double StepSimulator::output(std::string_view name) const {
  const int index = scenario_.system->signal_index(name);
  if (index < 0) throw std::invalid_argument("no output '" + std::string(name) + "'");
  return context_->signals()[static_cast<std::size_t>(index)];
}

double StepSimulator::state(std::string_view name) const {
  const auto& states = scenario_.system->states();
  for (std::size_t i = 0; i < states.size(); ++i)
    if (states[i].name == name) return context_->state()[i];
  throw std::invalid_argument("no state '" + std::string(name) + "'");
}

void StepSimulator::set_parameter(std::string_view path, double value) {
  Context check = scenario_.make_context();  // throws ParameterError for a bad path or value
  check.set_parameter(path, value);
  parameters_.emplace_back(std::string(path), value);
}

void StepSimulator::reset() {
  start();
}

const MemoryRun& StepSimulator::record() const {
  if (!failed_) {
    run_->statistics = integrator_->statistics();
    run_->time_reached = time();
    run_->status = finished() ? "complete" : "interrupted";
    run_->reason = finished() ? ""
                              : "stepped to t = " + number_text(time()) + " s of " +
                                    number_text(end_time()) + " s";
  }
  return *run_;
}

std::string StepSimulator::save(const std::string& path) const {
  if (std::filesystem::path(path).filename().empty())
    throw UsageError("save: expected a record's file name, got '" + path + "'");
  return save_record(scenario_, *context_, record(), path);
}

}  // namespace tcpmsim
