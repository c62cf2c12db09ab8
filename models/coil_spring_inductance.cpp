#include "models/coil_spring_inductance.h"

#include <cstdio>

#include "models/inductance/loop_mutual.h"

namespace tcpmsim {

namespace {
constexpr int kFitLengths = 25;
}

CoilSpringInductance::CoilSpringInductance(std::string group,
                                           CoilSpringInductanceParameters parameters)
    : Component(std::move(group), "coil_spring_inductance"),
      parameters_(parameters),
      evaluator_(parameters.coil_radius, inductance::wire_gmd(parameters.wire_diameter),
                 0.05 * parameters.wire_diameter, 2.0 * parameters.longest_length),
      positions_(static_cast<std::size_t>(parameters.windings)) {
  fit_ = fit_operating_range();
}

CoilSpringInductanceParameters CoilSpringInductance::parameters_from_config(const ConfigNode& node,
                                                                            int windings,
                                                                            double rest_length,
                                                                            double stiffness,
                                                                            double initial_length) {
  node.declare({"coil_radius", "wire_diameter", "operating_range", "preload_length"});
  CoilSpringInductanceParameters p;
  p.windings = windings;
  p.rest_length = rest_length;
  p.stiffness = stiffness;
  p.coil_radius = node.quantity("coil_radius", "m", ValueCheck::positive());
  p.wire_diameter = node.quantity("wire_diameter", "m", ValueCheck::positive());
  std::tie(p.shortest_length, p.longest_length) =
      node.interval("operating_range", "m", ValueCheck::positive());
  p.preload_length =
      node.quantity_or("preload_length", "m", initial_length, ValueCheck::positive());
  return p;
}

std::vector<OutputDeclaration> CoilSpringInductance::outputs() const {
  return {{"inductance", "H", true},
          {"inductance_deflection", "m", true},
          {"inductance_force", "N", true}};
}

std::vector<InputDeclaration> CoilSpringInductance::inputs() const {
  std::vector<InputDeclaration> declared;
  char name[32];
  for (int i = 0; i < parameters_.windings; ++i) {
    std::snprintf(name, sizeof name, "winding_%02d", i + 1);
    declared.push_back({name, true});
  }
  return declared;
}

double CoilSpringInductance::uniform_inductance(double length) const {
  // Rings at (i + 1/2) l / N: pitch l / N, all N rings (4.11) with uniform gaps (2.13).
  return evaluator_.inductance_uniform(parameters_.windings, length / parameters_.windings);
}

InverseLengthFit CoilSpringInductance::fit_operating_range() const {
  // Minimise sum (y_k - alpha L_k - beta)^2 with y = 1/l, subject to y_p = alpha L_p + beta:
  // beta = y_p - alpha L_p and alpha = sum dL dy / sum dL^2 about the preload point.
  const double preload_inductance = uniform_inductance(parameters_.preload_length);
  const double preload_inverse = 1.0 / parameters_.preload_length;
  double covariance = 0.0, variance = 0.0;
  for (int k = 0; k < kFitLengths; ++k) {
    const double length =
        parameters_.shortest_length +
        (parameters_.longest_length - parameters_.shortest_length) * k / (kFitLengths - 1);
    const double dL = uniform_inductance(length) - preload_inductance;
    covariance += dL * (1.0 / length - preload_inverse);
    variance += dL * dL;
  }
  InverseLengthFit fit;
  fit.alpha = covariance / variance;
  fit.beta = preload_inverse - fit.alpha * preload_inductance;
  return fit;
}

void CoilSpringInductance::compute_observations(const Evaluation& evaluation) const {
  for (int i = 0; i < parameters_.windings; ++i)
    positions_[static_cast<std::size_t>(i)] = input(evaluation, i);
  const double inductance = evaluator_.inductance(positions_);                  // (4.11)
  const double deflection = fit_.length(inductance) - parameters_.rest_length;  // (4.13)
  set_output(evaluation, kInductance, inductance);
  set_output(evaluation, kEstimatedDeflection, deflection);
  set_output(evaluation, kEstimatedForce, parameters_.stiffness * deflection);  // F_L
}

}  // namespace tcpmsim
