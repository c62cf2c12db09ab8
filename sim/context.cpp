#include "sim/context.h"

#include "sim/signal.h"

namespace tcpmsim {

Context::Context(const System& system)
    : system_(&system),
      signals_(static_cast<std::size_t>(system.signal_size()), 0.0),
      state_(static_cast<std::size_t>(system.state_size()), 0.0),
      run_states_(system.components().size()),
      rebuilt_signals_(system.signal_slots().size()) {
  parameters_.reserve(system.parameters().size());
  for (const auto& parameter : system.parameters())
    parameters_.push_back(parameter.declaration.value);
  for (const auto& slot : system.signal_slots()) prescribed_.push_back(slot.signal);
}

Context::Context(const Context& other) : Context(*other.system_) {
  parameters_ = other.parameters_;
}

double Context::parameter(std::string_view path) const {
  const auto index = system_->parameter_index(path);
  if (!index) throw ParameterError(std::string(path), "no such parameter");
  return parameter(*index);
}

void Context::set_parameter(std::string_view path, double value) {
  const auto index = system_->parameter_index(path);
  if (!index) throw ParameterError(std::string(path), "no such parameter");
  set_parameter(*index, value);
}

void Context::set_parameter(int index, double value) {
  const ParameterInfo& info = system_->parameters().at(static_cast<std::size_t>(index));
  if (!info.derived_from.empty()) {
    throw ParameterError(info.declaration.path,
                         "is derived (" + info.derived_from + "); set what it derives from");
  }
  if (std::string problem = parameter_problem(info.declaration, value); !problem.empty())
    throw ParameterError(info.declaration.path, problem);
  parameters_[static_cast<std::size_t>(index)] = value;
  prepared_ = false;
}

bool Context::parameters_changed() const {
  const auto& declared = system_->parameters();
  for (std::size_t p = 0; p < parameters_.size(); ++p) {
    if (parameters_[p] != declared[p].declaration.value) return true;
  }
  return false;
}

}  // namespace tcpmsim
