#pragma once

#include <Eigen/Dense>
#include <memory>

#include "sim/parametric_component.h"
#include "sim/signal_reading.h"

namespace tcpmsim {

// A coil spring as N lumped winding masses (thesis ch. 4, Fig. 4.1), moving axially between
// two imposed end positions u1(t), u2(t). Element e joins node e-1 and node e, with the ends
// as nodes -1 and N: the two end elements have stiffness 2Nk and rest length l0/(2N), the
// N-1 inner ones Nk and l0/N, so the series stiffness is k and a statically stretched spring
// has uniform windings. (4.4)-(4.7):
//     (m/N) d2xi_i/dt2 = T_{i+1} - T_i,   T_e = k_e (S_e - s_e) + c_e dS_e/dt,
// with S_e the element length. F_i = T_0 (input end) and F_o = T_N (output end) are tensions.
// Material damping is stiffness-proportional, c_e = beta k_e with beta = 2 zeta_1 / omega_1,
// which damps the first clamped mode (omega_1 = pi sqrt(k/m), (4.3)) by zeta_1.
// States are interleaved (xi_0, v_0, xi_1, v_1, ...) so the Jacobian is banded.
struct CoilSpringParameters {
  int windings = 0;            // N
  double rest_length = 0.0;    // l0 [m]
  double mass = 0.0;           // m [kg]
  double stiffness = 0.0;      // k [N/m]
  double damping_ratio = 0.0;  // zeta_1
  enum class VelocityProfile { rest, uniform, linear };
  VelocityProfile initial_profile = VelocityProfile::rest;
  double initial_velocity = 0.0;  // uniform: every winding; linear: 0 at u1 rising to this at u2

  double first_mode_frequency() const;  // pi sqrt(k/m) [rad/s], (4.3)
  double element_stiffness(int element) const;
  double damping_time() const;  // beta [s]
};

class CoilSpringChain final : public Component {
 public:
  CoilSpringChain(std::string group, CoilSpringParameters defaults,
                  ParameterBindings<CoilSpringParameters> bindings,
                  std::unique_ptr<Signal> first_end, std::unique_ptr<Signal> second_end);
  static std::unique_ptr<CoilSpringChain> from_config(const std::string& group,
                                                      const ConfigNode& node,
                                                      const SignalContext& signals);

  std::vector<StateDeclaration> states() const override;
  std::vector<OutputDeclaration> outputs() const override;
  std::vector<SignalDeclaration> signals() const override;
  std::vector<ParameterDeclaration> parameters() const override;
  std::unique_ptr<RunState> create_run_state(const RunSetup& setup) const override;
  std::string check_parameters(const RunSetup& setup) const override;
  void initialize(const Evaluation& evaluation, std::span<double> own_state) const override;
  void compute_outputs(const Evaluation& evaluation) const override;
  void compute_derivatives(const Evaluation& evaluation, double* derivatives) const override;
  double next_breakpoint_after(const Evaluation& evaluation) const override;
  Dependencies derivative_dependencies(int state_index) const override;

  // The linear model's matrices for the windings as built, M xi'' + C xi' + K xi = forcing by
  // the ends: for modal and frequency-response analysis.
  Eigen::MatrixXd mass_matrix() const;
  Eigen::MatrixXd stiffness_matrix() const;
  double element_stiffness(int element) const { return defaults().element_stiffness(element); }
  double first_mode_frequency() const { return defaults().first_mode_frequency(); }
  double end_position(int end, double time) const;  // u1 (end 0) or u2 (end 1) as built [m]
  const CoilSpringParameters& defaults() const { return defaults_; }

 private:
  static constexpr int kMechanicalOutputs = 6;  // then one position per winding
  enum Output { kInputForce, kOutputForce, kFirstEnd, kSecondEnd, kDeflection, kDeflectionForce };
  double position(const Evaluation& evaluation, int winding) const {
    return state(evaluation, 2 * winding);
  }
  struct Run;
  double tension(const Evaluation& evaluation, const Run& run, int element) const;

  CoilSpringParameters defaults_;
  ParameterBindings<CoilSpringParameters> bindings_;
  std::unique_ptr<Signal> first_end_;
  std::unique_ptr<Signal> second_end_;
};

}  // namespace tcpmsim
