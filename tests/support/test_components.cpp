#include "tests/support/test_components.h"

namespace tcpmsim::testing {

SignalSource::SignalSource(std::string group, std::unique_ptr<Signal> signal)
    : Component(std::move(group), "source"), signal_(std::move(signal)) {}

std::vector<OutputDeclaration> SignalSource::outputs() const {
  return {{"value", "1"}};
}

std::vector<SignalDeclaration> SignalSource::signals() const {
  return {{"value", "1", signal_.get()}};
}

void SignalSource::compute_outputs(const Evaluation& evaluation) const {
  set_output(evaluation, 0, signal(evaluation, 0).value(evaluation.signal_time));
}

double SignalSource::next_breakpoint_after(const Evaluation& evaluation) const {
  return signal(evaluation, 0).next_breakpoint_after(evaluation.time);
}

DecayTimeSensor::DecayTimeSensor(InductanceLaw law)
    : Component("sensor", "decay_time"), law_(law) {}

std::vector<OutputDeclaration> DecayTimeSensor::outputs() const {
  return {{"inductance_measure", "s"}};
}

std::vector<InputDeclaration> DecayTimeSensor::inputs() const {
  return {{"deflection", true}};
}

void DecayTimeSensor::compute_outputs(const Evaluation& evaluation) const {
  set_output(evaluation, 0, law_(input(evaluation, 0), law_.reference_temperature));
}

}  // namespace tcpmsim::testing
