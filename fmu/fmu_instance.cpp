#include "fmu/fmu_instance.h"

#include <cmath>
#include <stdexcept>

#include "fmu/fmu_resources.h"
#include "sim/value_check.h"

namespace tcpmsim::fmu {
namespace {

const char* mode_name(int mode) {
  static const char* const kNames[] = {"instantiated", "initialization mode", "step mode",
                                       "failed (a step failed: fmi2Reset to start again)",
                                       "terminated"};
  return kNames[mode];
}

// The FMI calls that reach us name times the master computed: a communication point within
// this many seconds of the time reached is that time.
double time_slack(double time) {
  return 1e-9 * std::max(1.0, std::abs(time));
}

}  // namespace

FmuInstance::FmuInstance(std::string name, const fmi2CallbackFunctions& callbacks, bool logging)
    : name_(std::move(name)), callbacks_(callbacks), logging_(logging) {}

fmi2Status FmuInstance::report(fmi2Status status, const std::string& message) const {
  if (callbacks_.logger && (logging_ || status >= fmi2Warning)) {
    const char* category =
        status >= fmi2Error ? "logError" : (status == fmi2Warning ? "logWarning" : "logInfo");
    // The message as the format, its '%' doubled, and no arguments: importers that format it
    // (FMPy, Simulink) show the message, and those that print the format as it is (a ctypes
    // logger cannot read C varargs) show it too, a '%' doubled.
    std::string format;
    for (const char c : message) format += c == '%' ? std::string("%%") : std::string(1, c);
    callbacks_.logger(callbacks_.componentEnvironment, name_.c_str(), status, category,
                      format.c_str());
  }
  return status;
}

fmi2Status FmuInstance::unsupported(const char* function) const {
  return report(fmi2Error, std::string(function) +
                               ": not offered by this FMU (co-simulation without FMU states or "
                               "derivatives; see its modelDescription.xml)");
}

FmuInstance* FmuInstance::instantiate(fmi2String name, fmi2Type type, fmi2String guid,
                                      fmi2String resource_location,
                                      const fmi2CallbackFunctions* callbacks, fmi2Boolean logging) {
  if (!callbacks || !callbacks->logger) return nullptr;  // no way to say why
  std::unique_ptr<FmuInstance> instance(
      new FmuInstance(name ? name : "tcpmsim", *callbacks, logging != fmi2False));
  auto fail = [&](const std::string& message) {
    instance->report(fmi2Error, "fmi2Instantiate: " + message);
    return nullptr;
  };
  if (type != fmi2CoSimulation)
    return fail("this FMU offers co-simulation only (fmuType fmi2CoSimulation)");
  if (!resource_location) return fail("no fmuResourceLocation");
  const auto directory = path_of_uri(resource_location);
  if (!directory)
    return fail(std::string("fmuResourceLocation '") + resource_location +
                "' is not a file URI (file:///...)");
  try {
    instance->units_ = std::make_shared<UnitSystem>();
    FmuResources resources = read_fmu_resources(*directory, instance->units_);
    instance->interface_ = fmu_interface(resources.scenario, resources.settings.outputs,
                                         resources.settings.model_identifier);
    if (!guid || instance->interface_.guid != guid)
      return fail(std::string("fmuGUID ") + (guid ? guid : "(null)") + " is not this FMU's " +
                  instance->interface_.guid + " (a modelDescription.xml from another export?)");
    instance->simulator_ = std::make_unique<StepSimulator>(std::move(resources.scenario));
    instance->stop_time_ = instance->simulator_->end_time();
  } catch (const std::exception& error) {
    return fail(error.what());
  }
  return instance.release();
}

fmi2Status FmuInstance::refuse_in(const char* call, std::initializer_list<Mode> allowed) const {
  for (const Mode mode : allowed)
    if (mode == mode_) return fmi2OK;
  return report(fmi2Error, std::string(call) + ": not allowed when the instance is " +
                               mode_name(static_cast<int>(mode_)));
}

const FmuVariable* FmuInstance::variable(fmi2ValueReference reference) const {
  return interface_.find(reference);
}

fmi2Status FmuInstance::setup_experiment(bool tolerance_defined, double tolerance, double start,
                                         bool stop_defined, double stop) {
  if (refuse_in("fmi2SetupExperiment", {Mode::instantiated}) != fmi2OK) return fmi2Error;
  if (start != 0.0)
    return report(fmi2Error, "fmi2SetupExperiment: startTime " + number_text(start) +
                                 " s: a tcpmsim scenario starts at t = 0");
  if (stop_defined && stop > simulator_->end_time() + time_slack(stop))
    return report(fmi2Error, "fmi2SetupExperiment: stopTime " + number_text(stop) +
                                 " s is after the scenario's end, " +
                                 number_text(simulator_->end_time()) + " s");
  if (stop_defined) stop_time_ = stop;
  if (tolerance_defined)
    report(fmi2OK, "fmi2SetupExperiment: tolerance " + number_text(tolerance) +
                       " noted; the scenario's solver tolerance (" +
                       number_text(interface_.tolerance) + ") is used");
  return fmi2OK;
}

fmi2Status FmuInstance::enter_initialization() {
  if (refuse_in("fmi2EnterInitializationMode", {Mode::instantiated}) != fmi2OK) return fmi2Error;
  mode_ = Mode::initialization;
  return fmi2OK;
}

fmi2Status FmuInstance::exit_initialization() {
  if (refuse_in("fmi2ExitInitializationMode", {Mode::initialization}) != fmi2OK) return fmi2Error;
  if (!pending_parameters_.empty()) {
    // The parameters set before make a new run; the inputs set keep their values.
    std::vector<std::pair<std::string, double>> inputs;
    for (const auto& input : simulator_->inputs())
      inputs.emplace_back(input.name, simulator_->input(input.name));
    try {
      simulator_->reset();
      for (const auto& [input, value] : inputs) simulator_->set_input(input, value);
    } catch (const std::exception& error) {
      return report(fmi2Error, std::string("fmi2ExitInitializationMode: ") + error.what());
    }
    pending_parameters_.clear();
  }
  mode_ = Mode::stepping;
  return fmi2OK;
}

fmi2Status FmuInstance::terminate() {
  if (refuse_in("fmi2Terminate", {Mode::stepping, Mode::failed}) != fmi2OK) return fmi2Error;
  mode_ = Mode::terminated;
  return fmi2OK;
}

fmi2Status FmuInstance::reset() {
  try {  // as instantiated: the scenario's parameters, none set since
    simulator_ = std::make_unique<StepSimulator>(simulator_->scenario());
  } catch (const std::exception& error) {
    return report(fmi2Error, std::string("fmi2Reset: ") + error.what());
  }
  pending_parameters_.clear();
  stop_time_ = simulator_->end_time();
  mode_ = Mode::instantiated;
  return fmi2OK;
}

fmi2Status FmuInstance::get_real(const fmi2ValueReference references[], std::size_t count,
                                 fmi2Real values[]) {
  if (count > 0 && (!references || !values))
    return report(fmi2Error, "fmi2GetReal: null arrays for " + std::to_string(count) + " values");
  for (std::size_t k = 0; k < count; ++k) {
    const FmuVariable* found = variable(references[k]);
    if (!found)
      return report(fmi2Error, "fmi2GetReal: no variable has value reference " +
                                   std::to_string(references[k]));
    try {
      switch (found->causality) {
        case FmuVariable::Causality::input:
          values[k] = simulator_->input(found->target);
          break;
        case FmuVariable::Causality::output:
          values[k] = simulator_->output(found->target);
          break;
        case FmuVariable::Causality::parameter: {
          const auto pending = pending_parameters_.find(found->target);
          values[k] = pending != pending_parameters_.end() ? pending->second
                                                           : simulator_->parameter(found->target);
          break;
        }
      }
    } catch (const std::exception& error) {
      return report(fmi2Error, "fmi2GetReal: " + found->name + ": " + error.what());
    }
  }
  return fmi2OK;
}

fmi2Status FmuInstance::set_real(const fmi2ValueReference references[], std::size_t count,
                                 const fmi2Real values[]) {
  if (count > 0 && (!references || !values))
    return report(fmi2Error, "fmi2SetReal: null arrays for " + std::to_string(count) + " values");
  if (refuse_in("fmi2SetReal", {Mode::instantiated, Mode::initialization, Mode::stepping}) !=
      fmi2OK)
    return fmi2Error;
  for (std::size_t k = 0; k < count; ++k) {
    const FmuVariable* found = variable(references[k]);
    if (!found)
      return report(fmi2Error, "fmi2SetReal: no variable has value reference " +
                                   std::to_string(references[k]));
    try {
      switch (found->causality) {
        case FmuVariable::Causality::input:
          simulator_->set_input(found->target, values[k]);
          break;
        case FmuVariable::Causality::output:
          return report(fmi2Error, "fmi2SetReal: " + found->name + " is an output");
        case FmuVariable::Causality::parameter: {
          if (mode_ == Mode::stepping)
            return report(fmi2Error, "fmi2SetReal: " + found->name +
                                         " is a fixed parameter: set it before "
                                         "fmi2ExitInitializationMode");
          simulator_->set_parameter(found->target, values[k]);  // ParameterError if bad
          pending_parameters_[found->target] = values[k];
          break;
        }
      }
    } catch (const std::exception& error) {
      return report(fmi2Error, "fmi2SetReal: " + found->name + ": " + error.what());
    }
  }
  return fmi2OK;
}

fmi2Status FmuInstance::do_step(double current, double step) {
  if (refuse_in("fmi2DoStep", {Mode::stepping}) != fmi2OK) return fmi2Error;
  const double now = simulator_->time();
  if (std::abs(current - now) > time_slack(now))
    return report(fmi2Error, "fmi2DoStep: currentCommunicationPoint " + number_text(current, 17) +
                                 " s is not the instance's time " + number_text(now, 17) +
                                 " s (no step backwards or past a point, no FMU states)");
  if (!(step > 0.0))
    return report(fmi2Error, "fmi2DoStep: communicationStepSize " + number_text(step) +
                                 " s: expected a positive step");
  if (now + step > stop_time_ + time_slack(stop_time_))
    return report(fmi2Error, "fmi2DoStep: a step to " + number_text(now + step) +
                                 " s passes the stop time, " + number_text(stop_time_) + " s");
  try {
    simulator_->step(step);
  } catch (const RunEnded& failure) {
    mode_ = Mode::failed;
    return report(fmi2Error, std::string("fmi2DoStep: the solver failed: ") + failure.what());
  } catch (const std::exception& error) {
    return report(fmi2Error, std::string("fmi2DoStep: ") + error.what());
  }
  return fmi2OK;
}

fmi2Status FmuInstance::status(fmi2StatusKind kind, fmi2Status* value) {
  if (!value) return report(fmi2Error, "fmi2GetStatus: null value");
  if (kind != fmi2DoStepStatus)
    return report(fmi2Discard, "fmi2GetStatus: only fmi2DoStepStatus is answered");
  *value = mode_ == Mode::failed ? fmi2Error : fmi2OK;  // steps complete before DoStep returns
  return fmi2OK;
}

fmi2Status FmuInstance::real_status(fmi2StatusKind kind, fmi2Real* value) {
  if (!value) return report(fmi2Error, "fmi2GetRealStatus: null value");
  if (kind != fmi2LastSuccessfulTime)
    return report(fmi2Discard, "fmi2GetRealStatus: only fmi2LastSuccessfulTime is answered");
  *value = simulator_->time();
  return fmi2OK;
}

}  // namespace tcpmsim::fmu
