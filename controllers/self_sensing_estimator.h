#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "controllers/discrete_filters.h"
#include "models/laws/impedance.h"
#include "models/laws/sls.h"
#include "models/laws/thermal_force.h"
#include "sim/config/config_node.h"
#include "sim/parameter_bindings.h"
#include "sim/sampled_component.h"

namespace tcpmsim {

// The estimator's own model of the muscle (plant and model stay separate objects).
struct SelfSensingEstimatorParameters {
  // (7.3)/(7.4) in the Muscle Drive's decay time L* [s]: lambda_l [s m], lambda_x [m],
  // lambda_0 [s]; lambda_T = 0 (constantan, section 7.2.2).
  InductanceLaw inductance;
  int moving_average_length = 2;       // samples of L* (7.3.1)
  int median_length = 15;              // samples of the moving average (7.3.1)
  double low_pass_cutoff = 0.111;      // [Hz] on the deflection (7.2.3); +infinity: none
  double heating_gain = 0.0;           // kappa_P [N/J] (7.1)
  double cooling_rate = 0.0;           // kappa_c [1/s]
  double initial_thermal_force = 0.0;  // F_T at the first sample [N]
  SlsParameters mechanics;             // k1, k2, c and phi_0 (7.5), (7.6)
  double deflection_offset = 0.0;      // calibration (7.3.4), added to the deflection [m]
  double force_offset = 0.0;           // calibration (7.3.4), added to the force [N]
  // The magnetic coupling the estimator knows, in L* [s] as a function of the deflection (a
  // bundle member's n G M(x)): (7.4) is then solved for L* - coupling(x). Empty: none.
  std::function<double(double)> mutual_measure;
};

// The held estimates after one sample. Before the first usable L* the deflection, velocity and
// force are NaN (unknown); the thermal force is always known, from the commanded power.
struct SelfSensingEstimate {
  double deflection;      // x^ [m], low-passed and calibrated
  double velocity;        // dx^/dt [m/s], backward difference of the low-passed deflection
  double force;           // F^ = F_l + F_T + phi_0 + force offset (7.5) [N]
  double thermal_force;   // F_T^ [N]
  double raw_deflection;  // (7.4) of the median-filtered L*, calibrated, before the low-pass [m]
};

// One run of the estimator below as a value type: its filters, its discretised models and the
// estimate it holds. The component runs one per run context; tests and analyses run it on
// their own samples.
class SelfSensingEstimation {
 public:
  SelfSensingEstimation(const SelfSensingEstimatorParameters& parameters, double period);

  // One sample: the L* measured over the period that just ended and the power commanded at the
  // previous sample.
  const SelfSensingEstimate& process(double inductance_measure, double power_command);
  // Forgets everything but the parameters and offsets; the next sample is a first one.
  void restart();
  bool started() const { return started_; }

  const SelfSensingEstimate& estimate() const { return estimate_; }
  const SelfSensingEstimatorParameters& parameters() const { return parameters_; }
  double period() const { return period_; }
  void set_deflection_offset(double offset);
  void set_force_offset(double offset);
  // (7.4) of the estimator's own law, without filters or calibration; with a coupling model,
  // the deflection x at which law(x) + coupling(x) is the measure (fixed-point iteration: the
  // coupling changes with x a hundred times less than the law); NaN where the uncoupled measure
  // leaves (7.4)'s domain or no fixed point is found (counted as out of domain).
  double model_deflection(double inductance_measure) const;

  long rejected_measurements() const { return rejected_measurements_; }  // not finite or <= 0
  long out_of_domain_samples() const { return out_of_domain_samples_; }  // median <= lambda_0

 private:
  void publish();

  SelfSensingEstimatorParameters parameters_;
  double period_;
  MovingAverage moving_average_;
  RunningMedian median_;
  FirstOrderLowPass low_pass_;
  DiscreteThermalForce thermal_;
  DiscreteSls sls_;

  bool started_ = false;               // a first sample has been taken
  bool has_deflection_ = false;        // a usable L* has arrived since the start
  double model_raw_deflection_ = 0.0;  // (7.4), uncalibrated, held over bad samples
  double model_deflection_ = 0.0;      // low-passed, uncalibrated
  double velocity_ = 0.0;
  long rejected_measurements_ = 0;
  long out_of_domain_samples_ = 0;
  SelfSensingEstimate estimate_;
};

// Self-sensing of deflection and force (thesis 7.2.2-7.2.3, Fig. 7.2), sampled with the
// Muscle Drive's PWM period.
//
// Each sample:
//   L* -> 2-sample moving average -> 15-sample median  (spikes, 7.3.1)
//      -> (7.4) x = (lambda_l - lambda_x (L* - lambda_0)) / (L* - lambda_0)    raw deflection
//      -> first-order low-pass, 0.111 Hz (7.2.3)                               deflection
//      -> backward difference                                                   velocity
//   F^ = F_l(x^, v^) (7.6) + F_T(P) (7.1) + phi_0 (7.5), each discretised exactly (above).
//
// Inputs, read at the sample instant: "inductance_measure", the Muscle Drive's latest L*
// (measured during the PWM period that just ended), and "power_command", the power the
// controller commanded at the previous sample and held since.
//
// Start-up and bad samples. The first sample of a run (and any sample whose index does not
// follow the previous one, i.e. skipped samples) starts the estimator: F_T = initial_thermal_force;
// the window filters grow until full (see discrete_filters.h). An L* that is not finite or not
// positive is no measurement (the Muscle Drive reports 0 before its first off-phase): it is not fed
// to the moving average and median. A median output at or below lambda_0 lies outside (7.4)'s
// domain (the deflection would be infinite or below -lambda_x). In both cases the raw
// deflection holds its last value and the low-pass, velocity and SLS run on with it; before
// the first usable value they stay NaN, and the SLS starts relaxed at the first one.
// Both cases are counted.
//
// Calibration (7.3.4). The offsets are added to the deflection (raw and filtered, hence also
// to the force model's input) and to the force. The velocity is the difference of the
// uncalibrated deflection, so changing an offset never produces a velocity impulse; after a
// change of the deflection offset, F_l moves to the new deflection with the SLS's relaxation
// time c/k2. To calibrate, average true - estimate over the calibration window and add it to the
// current offset (calibration_offset in analysis/control_tasks.h).
class SelfSensingEstimator final : public SampledComponent {
 public:
  enum Input { kInductanceMeasure, kPowerCommand };
  enum Output { kDeflection, kVelocity, kForce, kThermalForce, kRawDeflection };

  // A fixed model (no parameters for a context to change but the sample period).
  SelfSensingEstimator(std::string group, SelfSensingEstimatorParameters defaults, double period);
  SelfSensingEstimator(std::string group, SelfSensingEstimatorParameters defaults, double period,
                       ParameterBindings<SelfSensingEstimatorParameters> bindings);
  // Keys: inductance {lambda_l, lambda_x, lambda_0}, filters {moving_average, median,
  // low_pass_cutoff} (optional, thesis defaults 2, 15, 0.111 Hz), thermal {kappa_P, kappa_c,
  // initial_thermal_force (optional, 0 N)}, mechanics {k1, k2, damping, force_offset},
  // calibration {deflection_offset, force_offset} (optional, 0). The low-pass cut-off and the
  // calibration offsets are parameters whether given or not.
  // `mutual_measure` is the coupling model, if the scenario gives one (built by the caller).
  static std::unique_ptr<SelfSensingEstimator> from_config(
      const std::string& group, const ConfigNode& node, double period,
      std::function<double(double)> mutual_measure = {});

  std::vector<OutputDeclaration> outputs() const override;
  std::vector<InputDeclaration> inputs() const override;
  std::vector<ParameterDeclaration> parameters() const override;
  std::unique_ptr<RunState> create_run_state(const RunSetup& setup) const override;
  std::string check_parameters(const RunSetup& setup) const override;
  void compute_outputs(const Evaluation& evaluation) const override;

  const SelfSensingEstimatorParameters& defaults() const { return defaults_; }

 protected:
  void sample(const Evaluation& evaluation, long index) const override;

 private:
  struct Run;
  SelfSensingEstimatorParameters defaults_;
  ParameterBindings<SelfSensingEstimatorParameters> bindings_;
};

}  // namespace tcpmsim
