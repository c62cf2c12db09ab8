#include "models/sls_mechanics.h"
#include "models/typical_values.h"

#include <algorithm>

namespace tcpmsim {

SlsMechanics::SlsMechanics(std::string group, SlsParameters defaults,
                           ParameterBindings<SlsParameters> bindings)
    : ParametricComponent(std::move(group), "sls_mechanics", defaults, std::move(bindings)) {}

SlsParameters SlsMechanics::read(const ConfigNode& node,
                                 ParameterBindings<SlsParameters>* bindings) {
  using P = SlsParameters;
  node.declare({"k1", "k2", "damping", "force_offset"});
  P p;
  ParameterBindings<P> local;
  ParameterBindings<P>& bind = bindings ? *bindings : local;
  bind.quantity(node, "k1", "N/m", typical::stiffness(ValueCheck::positive()), p,
                bind.member(&P::k1));
  bind.quantity(node, "k2", "N/m", typical::added_stiffness(ValueCheck::non_negative()), p,
                bind.member(&P::k2));
  bind.quantity(node, "damping", "N*s/m", typical::damping(ValueCheck::positive()), p,
                bind.member(&P::damping));
  bind.quantity(node, "force_offset", "N", typical::force_offset({}), p,
                bind.member(&P::force_offset));
  return p;
}

std::unique_ptr<SlsMechanics> SlsMechanics::from_config(const std::string& group,
                                                        const ConfigNode& node) {
  ParameterBindings<SlsParameters> bindings;
  const SlsParameters p = read(node, &bindings);
  return std::make_unique<SlsMechanics>(group, p, std::move(bindings));
}

std::vector<OutputDeclaration> SlsMechanics::outputs() const {
  return {{"force", "N"},
          {"deflection", "m"},
          {"elastic_force", "N"},
          {"rest_deflection", "m", false, false},
          {"stiffness", "N/m", false, false},
          {"rest_stiffness", "N/m", false, false}};
}

std::vector<InputDeclaration> SlsMechanics::inputs() const {
  return {{"thermal_force", true},
          {"deflection", true, false, InputArity::optional},
          {"force", true, false, InputArity::optional},
          {"attached_stiffness", true, false, InputArity::many},
          {"attached_force", true, false, InputArity::many},
          {"attached_rest_stiffness", true, false, InputArity::many},
          {"attached_rest_force", true, false, InputArity::many},
          {"cable_deflection", true, false, InputArity::optional}};
}

std::string SlsMechanics::check_connections() const {
  const int held =
      source_count(kDeflection) + source_count(kForce) + source_count(kCableDeflection);
  if (held != 1)
    return "needs one of its deflection, its force or a cable's deflection imposed (connected), "
           "not " +
           std::string(held > 1 ? "several" : "none");
  const int terms = source_count(kAttachedStiffness);
  if (source_count(kAttachedForce) != terms || source_count(kAttachedRestStiffness) != terms ||
      source_count(kAttachedRestForce) != terms)
    return "has attached force terms without all four of their ports connected";
  return {};
}

// The deflection at which the muscle carries no force (7.5), at its present state.
double SlsMechanics::free_deflection(const Evaluation& evaluation) const {
  return sls::deflection_at_force(run_parameters(evaluation), 0.0, input(evaluation, kThermalForce),
                                  state(evaluation, 0), input_sum(evaluation, kAttachedStiffness),
                                  input_sum(evaluation, kAttachedForce));
}

double SlsMechanics::deflection(const Evaluation& evaluation) const {
  if (deflection_imposed()) return input(evaluation, kDeflection);
  if (held_by_cable())
    return std::max(input(evaluation, kCableDeflection), free_deflection(evaluation));
  return sls::deflection_at_force(run_parameters(evaluation), input(evaluation, kForce),
                                  input(evaluation, kThermalForce), state(evaluation, 0),
                                  input_sum(evaluation, kAttachedStiffness),
                                  input_sum(evaluation, kAttachedForce));
}

double SlsMechanics::rest_deflection(const Evaluation& evaluation) const {
  if (deflection_imposed()) return input(evaluation, kDeflection);
  const double force = held_by_cable() ? 0.0 : input(evaluation, kForce);
  const double rest = sls::rest_deflection(
      run_parameters(evaluation), force, input(evaluation, kThermalForce),
      input_sum(evaluation, kAttachedRestStiffness), input_sum(evaluation, kAttachedRestForce));
  // Held by a cable: at the cable's deflection if that leaves it taut at rest, else slack.
  return held_by_cable() ? std::max(input(evaluation, kCableDeflection), rest) : rest;
}

void SlsMechanics::initialize(const Evaluation& evaluation, std::span<double> own_state) const {
  own_state[0] = rest_deflection(evaluation);  // a rested muscle: the dashpot relaxed, x_d = x
}

void SlsMechanics::compute_outputs(const Evaluation& evaluation) const {
  const auto& p = run_parameters(evaluation);
  const double x = deflection(evaluation);
  const double elastic = sls::elastic_force(p, x, state(evaluation, 0));
  double force = sls::total_force(p, elastic, input(evaluation, kThermalForce));  // (7.5)
  if (has_attachments()) {
    force += input_sum(evaluation, kAttachedStiffness) * x + input_sum(evaluation, kAttachedForce);
  }
  // Slack: the muscle is longer than the cable's path, at its force-free deflection, and
  // carries nothing (not the rounding residue of (7.5) there); likewise once relaxed.
  const double rest = deflection_imposed() ? x : rest_deflection(evaluation);
  const bool slack = held_by_cable() && x > input(evaluation, kCableDeflection);
  const bool slack_at_rest = held_by_cable() && rest > input(evaluation, kCableDeflection);
  set_output(evaluation, kDeflectionOutput, x);
  set_output(evaluation, kElasticForce, elastic);
  set_output(evaluation, kForceOutput, slack ? 0.0 : force);
  // An imposed deflection is its own rest deflection; only an imposed force needs solving.
  set_output(evaluation, kRestDeflection, rest);
  set_output(evaluation, kStiffness,
             slack ? 0.0 : p.k1 + p.k2 + input_sum(evaluation, kAttachedStiffness));
  set_output(evaluation, kRestStiffness,
             slack_at_rest ? 0.0 : p.k1 + input_sum(evaluation, kAttachedRestStiffness));
}

void SlsMechanics::compute_derivatives(const Evaluation& evaluation, double* derivatives) const {
  set_derivative(
      derivatives, 0,
      sls::dashpot_rate(run_parameters(evaluation), deflection(evaluation), state(evaluation, 0)));
}

Dependencies SlsMechanics::derivative_dependencies(int) const {
  // With x imposed the dashpot does not see the thermal force; with F imposed, x (7.5) does.
  if (deflection_imposed()) return {{0}, {kDeflection}};
  if (held_by_cable())
    return {{0}, {kThermalForce, kCableDeflection, kAttachedStiffness, kAttachedForce}};
  return {{0}, {kThermalForce, kForce, kAttachedStiffness, kAttachedForce}};
}

}  // namespace tcpmsim
