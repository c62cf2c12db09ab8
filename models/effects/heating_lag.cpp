#include "models/effects/heating_lag.h"

#include "models/typical_values.h"

namespace tcpmsim {

HeatingLag::HeatingLag(std::string group, HeatingLagParameters defaults,
                       ParameterBindings<HeatingLagParameters> bindings)
    : ParametricComponent(std::move(group), "heating_lag", defaults, std::move(bindings)) {}

std::unique_ptr<HeatingLag> HeatingLag::from_config(const std::string& group,
                                                    const ConfigNode& node) {
  using P = HeatingLagParameters;
  node.declare({"type", "name", "share", "time_constant"});
  P p;
  ParameterBindings<P> bind;
  bind.quantity(node, "share", "1", ValueCheck::fraction(), p, bind.member(&P::share));
  bind.quantity(node, "time_constant", "s", typical::time_constant(ValueCheck::positive()), p,
                bind.member(&P::time_constant));
  return std::make_unique<HeatingLag>(group, p, std::move(bind));
}

void HeatingLag::initialize(const Evaluation& evaluation, std::span<double> own_state) const {
  own_state[0] = input(evaluation, kPower);
}

void HeatingLag::compute_outputs(const Evaluation& evaluation) const {
  const double lagged = state(evaluation, 0);
  set_output(
      evaluation, kHeatLoss,
      heating_lag::held_power(run_parameters(evaluation), input(evaluation, kPower), lagged));
  set_output(evaluation, kLaggedPower, lagged);
}

void HeatingLag::compute_derivatives(const Evaluation& evaluation, double* derivatives) const {
  const auto& p = run_parameters(evaluation);
  set_derivative(derivatives, 0,
                 (input(evaluation, kPower) - state(evaluation, 0)) / p.time_constant);
}

}  // namespace tcpmsim
