#include "models/effects/heat_sink.h"

#include "models/typical_values.h"

namespace tcpmsim {

HeatSink::HeatSink(std::string group, HeatSinkParameters defaults,
                   ParameterBindings<HeatSinkParameters> bindings)
    : ParametricComponent(std::move(group), "heat_sink", defaults, std::move(bindings)) {}

std::unique_ptr<HeatSink> HeatSink::from_config(const std::string& group, const ConfigNode& node) {
  using P = HeatSinkParameters;
  node.declare({"type", "name", "conductance", "time_constant", "heat_capacity"});
  P p;
  ParameterBindings<P> bind;
  // Zero conductance is allowed: a body the polymer does not touch (discover's nested start).
  bind.quantity(node, "conductance", "W/K", typical::added_conductance(ValueCheck::non_negative()),
                p, bind.member(&P::conductance));
  if (node.has("time_constant") && node.has("heat_capacity"))
    node.at("heat_capacity")
        .fail("give heat_capacity or time_constant (= heat_capacity / conductance), not both");
  if (node.has("heat_capacity")) {
    bind.quantity(node, "heat_capacity", "J/K", typical::heat_capacity(ValueCheck::positive()), p,
                  bind.member(&P::heat_capacity));
  } else {
    bind.quantity(node, "time_constant", "s", typical::time_constant(ValueCheck::positive()), p,
                  bind.member(&P::time_constant));
  }
  return std::make_unique<HeatSink>(group, p, std::move(bind));
}

void HeatSink::initialize(const Evaluation& evaluation, std::span<double> own_state) const {
  own_state[0] = input(evaluation, kTemperature);  // caught up with the polymer
}

void HeatSink::compute_outputs(const Evaluation& evaluation) const {
  const double sink = state(evaluation, 0);
  set_output(
      evaluation, kHeatLoss,
      heat_sink::heat_loss(run_parameters(evaluation), input(evaluation, kTemperature), sink));
  set_output(evaluation, kSinkTemperature, sink);
}

void HeatSink::compute_derivatives(const Evaluation& evaluation, double* derivatives) const {
  set_derivative(derivatives, 0,
                 heat_sink::warming(run_parameters(evaluation), input(evaluation, kTemperature),
                                    state(evaluation, 0)));
}

}  // namespace tcpmsim
