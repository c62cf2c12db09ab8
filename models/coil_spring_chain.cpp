#include "models/coil_spring_chain.h"

#include <cmath>
#include <cstdio>
#include <numbers>

namespace tcpmsim {

double CoilSpringParameters::first_mode_frequency() const {
  return std::numbers::pi * std::sqrt(stiffness / mass);  // (4.3)
}

double CoilSpringParameters::element_stiffness(int element) const {
  const double n = windings;
  const bool end = element == 0 || element == windings;
  return (end ? 2.0 : 1.0) * n * stiffness;  // (4.4)
}

double CoilSpringParameters::damping_time() const {
  return 2.0 * damping_ratio / first_mode_frequency();
}

// The parameters as a run has them, with beta worked out once.
struct CoilSpringChain::Run final : RunState {
  explicit Run(const CoilSpringParameters& values)
      : p(values), damping_time(values.damping_time()) {}
  CoilSpringParameters p;
  double damping_time;
};

CoilSpringChain::CoilSpringChain(std::string group, CoilSpringParameters defaults,
                                 ParameterBindings<CoilSpringParameters> bindings,
                                 std::unique_ptr<Signal> first_end,
                                 std::unique_ptr<Signal> second_end)
    : Component(std::move(group), "coil_spring_chain"),
      defaults_(defaults),
      bindings_(std::move(bindings)),
      first_end_(std::move(first_end)),
      second_end_(std::move(second_end)) {}

std::vector<ParameterDeclaration> CoilSpringChain::parameters() const {
  return bindings_.declarations(defaults_);
}

std::unique_ptr<RunState> CoilSpringChain::create_run_state(const RunSetup& setup) const {
  return std::make_unique<Run>(bindings_.assign(defaults_, setup.parameters));
}

std::string CoilSpringChain::check_parameters(const RunSetup& setup) const {
  // The Jacobian's pattern was fixed at assembly: material damping couples neighbouring
  // velocities only if the spring was built damped.
  if (defaults_.damping_ratio == 0.0 &&
      bindings_.assign(defaults_, setup.parameters).damping_ratio != 0.0) {
    return "damping_ratio: the spring was built undamped; give a damping ratio in the scenario "
           "to vary it";
  }
  return {};
}

std::unique_ptr<CoilSpringChain> CoilSpringChain::from_config(const std::string& group,
                                                              const ConfigNode& node,
                                                              const SignalContext& signals) {
  using P = CoilSpringParameters;
  P p;
  ParameterBindings<P> bind;
  p.windings = static_cast<int>(node.integer(
      "windings", ValueCheck::count(1e4,
                                    "each winding is two states of the stiff system, and the "
                                    "inductance sums every pair of windings")));
  bind.quantity(node, "rest_length", "m", ValueCheck::positive(), p, bind.member(&P::rest_length));
  bind.quantity(node, "mass", "kg", ValueCheck::positive(), p, bind.member(&P::mass));
  bind.quantity(node, "stiffness", "N/m", ValueCheck::positive(), p, bind.member(&P::stiffness));
  bind.quantity_or(node, "damping_ratio", "1", 0.0, ValueCheck::non_negative(), p,
                   bind.member(&P::damping_ratio));
  if (auto velocity = node.find("initial_velocity")) {
    velocity->declare({"profile", "value"});
    const std::string profile = velocity->choice("profile", {"uniform", "linear"});
    p.initial_profile =
        profile == "uniform" ? P::VelocityProfile::uniform : P::VelocityProfile::linear;
    bind.quantity(*velocity, "value", "m/s", {}, p, bind.member(&P::initial_velocity));
  }
  auto first = read_signal(node.at("first_end"), "m", signals);
  auto second = read_signal(node.at("second_end"), "m", signals);
  return std::make_unique<CoilSpringChain>(group, p, std::move(bind), std::move(first),
                                           std::move(second));
}

std::vector<StateDeclaration> CoilSpringChain::states() const {
  std::vector<StateDeclaration> declared;
  char name[32];
  for (int i = 0; i < defaults().windings; ++i) {
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
  for (int i = 0; i < defaults().windings; ++i) {
    std::snprintf(name, sizeof name, "winding_%02d", i + 1);
    declared.push_back({name, "m"});
  }
  return declared;
}

std::vector<SignalDeclaration> CoilSpringChain::signals() const {
  return {{"first_end", "m", first_end_.get()}, {"second_end", "m", second_end_.get()}};
}

double CoilSpringChain::end_position(int end, double time) const {
  return (end == 0 ? first_end_ : second_end_)->value(time);
}

void CoilSpringChain::initialize(const Evaluation& evaluation, std::span<double> own_state) const {
  // Static equilibrium between the initial end positions: uniform windings.
  const auto& p = run_state<Run>(evaluation).p;
  const double u1 = signal(evaluation, 0).value(evaluation.signal_time),
               u2 = signal(evaluation, 1).value(evaluation.signal_time);
  const int n = p.windings;
  for (int i = 0; i < n; ++i) {
    const double fraction = (i + 0.5) / n;
    own_state[static_cast<std::size_t>(2 * i)] = u1 + fraction * (u2 - u1);
    double velocity = 0.0;
    if (p.initial_profile == CoilSpringParameters::VelocityProfile::uniform) {
      velocity = p.initial_velocity;
    } else if (p.initial_profile == CoilSpringParameters::VelocityProfile::linear) {
      velocity = fraction * p.initial_velocity;
    }
    own_state[static_cast<std::size_t>(2 * i + 1)] = velocity;
  }
}

double CoilSpringChain::tension(const Evaluation& evaluation, const Run& run, int element) const {
  const CoilSpringParameters& p = run.p;
  const int n = p.windings;
  const double t = evaluation.signal_time;
  const Signal& first = signal(evaluation, 0);
  const Signal& second = signal(evaluation, 1);
  const double left = element == 0 ? first.value(t) : position(evaluation, element - 1);
  const double right = element == n ? second.value(t) : position(evaluation, element);
  const double rest = (element == 0 || element == n ? 0.5 : 1.0) * p.rest_length / n;
  const double stiffness = p.element_stiffness(element);
  double tension = stiffness * (right - left - rest);
  const double damping_time = run.damping_time;
  if (damping_time > 0.0) {
    const double left_speed = element == 0 ? first.slope(t) : state(evaluation, 2 * element - 1);
    const double right_speed = element == n ? second.slope(t) : state(evaluation, 2 * element + 1);
    tension += damping_time * stiffness * (right_speed - left_speed);
  }
  return tension;
}

void CoilSpringChain::compute_outputs(const Evaluation& evaluation) const {
  const Run& run = run_state<Run>(evaluation);
  const auto& p = run.p;
  const double u1 = signal(evaluation, 0).value(evaluation.signal_time),
               u2 = signal(evaluation, 1).value(evaluation.signal_time);
  const double deflection = u2 - u1 - p.rest_length;
  set_output(evaluation, kInputForce, tension(evaluation, run, 0));  // (4.7)
  set_output(evaluation, kOutputForce, tension(evaluation, run, p.windings));
  set_output(evaluation, kFirstEnd, u1);
  set_output(evaluation, kSecondEnd, u2);
  set_output(evaluation, kDeflection, deflection);
  set_output(evaluation, kDeflectionForce, p.stiffness * deflection);  // F_x
  for (int i = 0; i < p.windings; ++i)
    set_output(evaluation, kMechanicalOutputs + i, position(evaluation, i));
}

void CoilSpringChain::compute_derivatives(const Evaluation& evaluation, double* derivatives) const {
  // (4.5)-(4.6); each element's tension is used by the two windings it joins.
  const Run& run = run_state<Run>(evaluation);
  const auto& p = run.p;
  const double winding_mass = p.mass / p.windings;
  double left_tension = tension(evaluation, run, 0);
  for (int i = 0; i < p.windings; ++i) {
    const double right_tension = tension(evaluation, run, i + 1);
    set_derivative(derivatives, 2 * i, state(evaluation, 2 * i + 1));
    set_derivative(derivatives, 2 * i + 1, (right_tension - left_tension) / winding_mass);
    left_tension = right_tension;
  }
}

Dependencies CoilSpringChain::derivative_dependencies(int state_index) const {
  const int winding = state_index / 2;
  if (state_index % 2 == 0) return {{state_index + 1}, {}};  // dxi/dt = v
  Dependencies dependencies;
  const bool damped = defaults().damping_time() > 0.0;
  for (int neighbour = std::max(0, winding - 1);
       neighbour <= std::min(defaults().windings - 1, winding + 1); ++neighbour) {
    dependencies.states.push_back(2 * neighbour);
    if (damped || neighbour == winding) dependencies.states.push_back(2 * neighbour + 1);
  }
  return dependencies;
}

double CoilSpringChain::next_breakpoint_after(const Evaluation& evaluation) const {
  return std::min(signal(evaluation, 0).next_breakpoint_after(evaluation.time),
                  signal(evaluation, 1).next_breakpoint_after(evaluation.time));
}

Eigen::MatrixXd CoilSpringChain::mass_matrix() const {
  const int n = defaults().windings;
  return Eigen::MatrixXd::Identity(n, n) * (defaults().mass / n);
}

Eigen::MatrixXd CoilSpringChain::stiffness_matrix() const {
  // K = S_xi^T diag(k_e) S_xi, from (4.4)-(4.5).
  const int n = defaults().windings;
  Eigen::MatrixXd stiffness = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    stiffness(i, i) = element_stiffness(i) + element_stiffness(i + 1);
    if (i + 1 < n) stiffness(i, i + 1) = stiffness(i + 1, i) = -element_stiffness(i + 1);
  }
  return stiffness;
}

}  // namespace tcpmsim
