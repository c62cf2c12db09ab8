#include "models/sls_mechanics.h"

namespace tcpmsim {

SlsMechanics::SlsMechanics(std::string group, SlsParameters parameters, Drive drive)
    : Component(std::move(group), "sls_mechanics"), parameters_(parameters), drive_(drive) {}

SlsParameters SlsMechanics::parameters_from_config(const ConfigNode& node) {
  node.declare({"k1", "k2", "damping", "force_offset"});
  SlsParameters p;
  p.k1 = node.quantity("k1", "N/m", ValueCheck::positive());
  p.k2 = node.quantity("k2", "N/m", ValueCheck::non_negative());
  p.damping = node.quantity("damping", "N*s/m", ValueCheck::positive());
  p.force_offset = node.quantity("force_offset", "N");
  return p;
}

std::vector<OutputDeclaration> SlsMechanics::outputs() const {
  return {{"force", "N"}, {"deflection", "m"}, {"elastic_force", "N"}};
}

std::vector<InputDeclaration> SlsMechanics::inputs() const {
  return {{"thermal_force", true}, {drive_ == Drive::deflection ? "deflection" : "force", true}};
}

double SlsMechanics::deflection(const Evaluation& evaluation) const {
  if (drive_ == Drive::deflection) return input(evaluation, kImposed);
  return sls::deflection_at_force(parameters_, input(evaluation, kImposed),
                                  input(evaluation, kThermalForce), state(evaluation, 0));
}

void SlsMechanics::initialize(const Evaluation& evaluation, std::span<double> own_state) const {
  // A rested muscle: the dashpot is relaxed, x_d = x.
  if (drive_ == Drive::deflection) {
    own_state[0] = input(evaluation, kImposed);
  } else {
    own_state[0] = sls::rest_deflection(parameters_, input(evaluation, kImposed),
                                        input(evaluation, kThermalForce));
  }
}

void SlsMechanics::compute_outputs(const Evaluation& evaluation) const {
  const double x = deflection(evaluation);
  const double elastic = sls::elastic_force(parameters_, x, state(evaluation, 0));
  set_output(evaluation, kDeflection, x);
  set_output(evaluation, kElasticForce, elastic);
  set_output(evaluation, kForce,
             sls::total_force(parameters_, elastic, input(evaluation, kThermalForce)));  // (7.5)
}

void SlsMechanics::compute_derivatives(const Evaluation& evaluation, double* derivatives) const {
  const double x = deflection(evaluation);
  set_derivative(derivatives, 0, sls::dashpot_rate(parameters_, x, state(evaluation, 0)));
}

}  // namespace tcpmsim

namespace tcpmsim {

Dependencies SlsMechanics::derivative_dependencies(int) const {
  // With x imposed the dashpot does not see the thermal force; with F imposed, x (7.5) does.
  if (drive_ == Drive::deflection) return {{0}, {kImposed}};
  return {{0}, {kThermalForce, kImposed}};
}

}  // namespace tcpmsim
