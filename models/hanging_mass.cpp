#include "models/hanging_mass.h"

namespace tcpmsim {

HangingMass::HangingMass(std::string group, HangingMassParameters parameters)
    : Component(std::move(group), "hanging_mass"), parameters_(parameters) {}

void HangingMass::initialize(const Evaluation&, std::span<double> own_state) const {
  own_state[0] = parameters_.initial_deflection;
  own_state[1] = parameters_.initial_velocity;
}

void HangingMass::compute_outputs(const Evaluation& evaluation) const {
  set_output(evaluation, kDeflection, state(evaluation, 0));
  set_output(evaluation, kVelocity, state(evaluation, 1));
}

void HangingMass::compute_derivatives(const Evaluation& evaluation, double* derivatives) const {
  const double velocity = state(evaluation, 1);
  const double weight = parameters_.mass * parameters_.gravity;
  set_derivative(derivatives, 0, velocity);
  set_derivative(derivatives, 1,
                 (weight - input(evaluation, kMuscleForce) - parameters_.damping * velocity) /
                     parameters_.mass);
}

}  // namespace tcpmsim
