#include "sim/component.h"

#include <numeric>
#include <stdexcept>

#include "sim/context.h"

namespace tcpmsim {

Component::Component(std::string group, std::string kind)
    : group_(std::move(group)), kind_(std::move(kind)) {}

std::string Component::check_connections() const {
  return {};
}

std::pair<double, double> Component::external_input_range(const Evaluation&, int) const {
  throw std::logic_error(group_ + " has no external input");
}

void Component::hold_external_input(const Evaluation&, int, double) const {
  throw std::logic_error(group_ + " has no external input");
}

std::unique_ptr<RunState> Component::create_run_state(const RunSetup&) const {
  return nullptr;
}

std::string Component::check_parameters(const RunSetup&) const {
  return {};
}

void Component::initialize(const Evaluation&, std::span<double> own_state) const {
  for (double& value : own_state) value = 0.0;
}

void Component::compute_outputs(const Evaluation&) const {}

void Component::compute_observations(const Evaluation&) const {}

void Component::compute_derivatives(const Evaluation&, double*) const {}

double Component::next_breakpoint_after(const Evaluation&) const {
  return kNoBreakpoint;
}

void Component::at_breakpoint(const Evaluation&) const {}

void Component::sense(const Evaluation&) const {}

void Component::adapt_tolerances(const Evaluation&, std::span<double>, std::span<double>) const {}

void Component::event_functions(const Evaluation&, double*) const {}

void Component::at_event(int, const Evaluation&) const {}

const Signal& Component::signal(const Context& context, int index) const {
  return context.signal(signal_offset_ + index);
}

namespace {
std::vector<int> all_indices(std::size_t count) {
  std::vector<int> indices(count);
  std::iota(indices.begin(), indices.end(), 0);
  return indices;
}
}  // namespace

Dependencies Component::derivative_dependencies(int) const {
  return {all_indices(states().size()), all_indices(inputs().size())};
}

Dependencies Component::output_dependencies(int) const {
  Dependencies dependencies{all_indices(states().size()), {}};
  const auto declared = inputs();
  for (std::size_t i = 0; i < declared.size(); ++i) {
    if (declared[i].direct_feedthrough) dependencies.inputs.push_back(static_cast<int>(i));
  }
  return dependencies;
}

}  // namespace tcpmsim
