#include "models/coil_spring_chain.h"

#include <cmath>
#include <cstdio>
#include <numbers>

namespace tcpmsim {

CoilSpringChain::CoilSpringChain(std::string group, CoilSpringParameters parameters,
                                 std::unique_ptr<Signal> first_end,
                                 std::unique_ptr<Signal> second_end)
    : Component(std::move(group), "coil_spring_chain"),
      parameters_(parameters),
      first_end_(std::move(first_end)),
      second_end_(std::move(second_end)) {
  damping_time_ = 2.0 * parameters_.damping_ratio / first_mode_frequency();
}

std::unique_ptr<CoilSpringChain> CoilSpringChain::from_config(const std::string& group,
                                                              const ConfigNode& node,
                                                              const SignalContext& signals) {
  CoilSpringParameters p;
  p.windings = static_cast<int>(node.integer("windings", ValueCheck::at_least(1)));
  p.rest_length = node.quantity("rest_length", "m", ValueCheck::positive());
  p.mass = node.quantity("mass", "kg", ValueCheck::positive());
  p.stiffness = node.quantity("stiffness", "N/m", ValueCheck::positive());
  p.damping_ratio = node.number_or("damping_ratio", 0.0, ValueCheck::non_negative());
  if (auto velocity = node.find("initial_velocity")) {
    velocity->declare({"profile", "value"});
    const std::string profile = velocity->choice("profile", {"uniform", "linear"});
    p.initial_profile = profile == "uniform" ? CoilSpringParameters::VelocityProfile::uniform
                                             : CoilSpringParameters::VelocityProfile::linear;
    p.initial_velocity = velocity->quantity("value", "m/s");
  }
  return std::make_unique<CoilSpringChain>(group, p,
                                           read_signal(node.at("first_end"), "m", signals),
                                           read_signal(node.at("second_end"), "m", signals));
}

double CoilSpringChain::first_mode_frequency() const {
  return std::numbers::pi * std::sqrt(parameters_.stiffness / parameters_.mass);  // (4.3)
}

double CoilSpringChain::element_stiffness(int element) const {
  const double n = parameters_.windings;
  const bool end = element == 0 || element == parameters_.windings;
  return (end ? 2.0 : 1.0) * n * parameters_.stiffness;  // (4.4)
}

std::vector<StateDeclaration> CoilSpringChain::states() const {
  std::vector<StateDeclaration> declared;
  char name[32];
  for (int i = 0; i < parameters_.windings; ++i) {
    std::snprintf(name, sizeof name, "winding_%02d", i + 1);
    declared.push_back({name, "m", 1e-12});
    std::snprintf(name, sizeof name, "winding_%02d_velocity", i + 1);
    declared.push_back({name, "m/s", 1e-9});
  }
  return declared;
}

std::vector<OutputDeclaration> CoilSpringChain::outputs() const {
  std::vector<OutputDeclaration> declared{{"input_force", "N"}, {"output_force", "N"},
                                          {"first_end", "m"},   {"second_end", "m"},
                                          {"deflection", "m"},  {"deflection_force", "N"}};
  char name[32];
  for (int i = 0; i < parameters_.windings; ++i) {
    std::snprintf(name, sizeof name, "winding_%02d", i + 1);
    declared.push_back({name, "m"});
  }
  return declared;
}

double CoilSpringChain::end_position(int end, double time) const {
  return (end == 0 ? first_end_ : second_end_)->value(time);
}

void CoilSpringChain::initialize(const Evaluation& evaluation, std::span<double> own_state) const {
  // Static equilibrium between the initial end positions: uniform windings.
  const double u1 = end_position(0, evaluation.signal_time),
               u2 = end_position(1, evaluation.signal_time);
  const int n = parameters_.windings;
  for (int i = 0; i < n; ++i) {
    const double fraction = (i + 0.5) / n;
    own_state[static_cast<std::size_t>(2 * i)] = u1 + fraction * (u2 - u1);
    double velocity = 0.0;
    if (parameters_.initial_profile == CoilSpringParameters::VelocityProfile::uniform) {
      velocity = parameters_.initial_velocity;
    } else if (parameters_.initial_profile == CoilSpringParameters::VelocityProfile::linear) {
      velocity = fraction * parameters_.initial_velocity;
    }
    own_state[static_cast<std::size_t>(2 * i + 1)] = velocity;
  }
}

double CoilSpringChain::tension(const Evaluation& evaluation, int element) const {
  const int n = parameters_.windings;
  const double t = evaluation.signal_time;
  const double left = element == 0 ? end_position(0, t) : position(evaluation, element - 1);
  const double right = element == n ? end_position(1, t) : position(evaluation, element);
  const double rest = (element == 0 || element == n ? 0.5 : 1.0) * parameters_.rest_length / n;
  const double stiffness = element_stiffness(element);
  double tension = stiffness * (right - left - rest);
  if (damping_time_ > 0.0) {
    const double left_speed =
        element == 0 ? first_end_->slope(t) : state(evaluation, 2 * element - 1);
    const double right_speed =
        element == n ? second_end_->slope(t) : state(evaluation, 2 * element + 1);
    tension += damping_time_ * stiffness * (right_speed - left_speed);
  }
  return tension;
}

void CoilSpringChain::compute_outputs(const Evaluation& evaluation) const {
  const double u1 = end_position(0, evaluation.signal_time),
               u2 = end_position(1, evaluation.signal_time);
  const double deflection = u2 - u1 - parameters_.rest_length;
  set_output(evaluation, kInputForce, tension(evaluation, 0));  // (4.7)
  set_output(evaluation, kOutputForce, tension(evaluation, parameters_.windings));
  set_output(evaluation, kFirstEnd, u1);
  set_output(evaluation, kSecondEnd, u2);
  set_output(evaluation, kDeflection, deflection);
  set_output(evaluation, kDeflectionForce, parameters_.stiffness * deflection);  // F_x
  for (int i = 0; i < parameters_.windings; ++i)
    set_output(evaluation, kMechanicalOutputs + i, position(evaluation, i));
}

void CoilSpringChain::compute_derivatives(const Evaluation& evaluation, double* derivatives) const {
  // (4.5)-(4.6); each element's tension is used by the two windings it joins.
  const double winding_mass = parameters_.mass / parameters_.windings;
  double left_tension = tension(evaluation, 0);
  for (int i = 0; i < parameters_.windings; ++i) {
    const double right_tension = tension(evaluation, i + 1);
    set_derivative(derivatives, 2 * i, state(evaluation, 2 * i + 1));
    set_derivative(derivatives, 2 * i + 1, (right_tension - left_tension) / winding_mass);
    left_tension = right_tension;
  }
}

Dependencies CoilSpringChain::derivative_dependencies(int state_index) const {
  const int winding = state_index / 2;
  if (state_index % 2 == 0) return {{state_index + 1}, {}};  // dxi/dt = v
  Dependencies dependencies;
  for (int neighbour = std::max(0, winding - 1);
       neighbour <= std::min(parameters_.windings - 1, winding + 1); ++neighbour) {
    dependencies.states.push_back(2 * neighbour);
    if (damping_time_ > 0.0 || neighbour == winding)
      dependencies.states.push_back(2 * neighbour + 1);
  }
  return dependencies;
}

double CoilSpringChain::next_breakpoint_after(double t) const {
  return std::min(first_end_->next_breakpoint_after(t), second_end_->next_breakpoint_after(t));
}

std::vector<Component::SignalRecord> CoilSpringChain::signal_records() const {
  return {{"first_end", "m", first_end_.get()}, {"second_end", "m", second_end_.get()}};
}

Eigen::MatrixXd CoilSpringChain::mass_matrix() const {
  const int n = parameters_.windings;
  return Eigen::MatrixXd::Identity(n, n) * (parameters_.mass / n);
}

Eigen::MatrixXd CoilSpringChain::stiffness_matrix() const {
  // K = S_xi^T diag(k_e) S_xi, from (4.4)-(4.5).
  const int n = parameters_.windings;
  Eigen::MatrixXd stiffness = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    stiffness(i, i) = element_stiffness(i) + element_stiffness(i + 1);
    if (i + 1 < n) stiffness(i, i + 1) = stiffness(i + 1, i) = -element_stiffness(i + 1);
  }
  return stiffness;
}

}  // namespace tcpmsim
