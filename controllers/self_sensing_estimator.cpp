#include "controllers/self_sensing_estimator.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "models/sls_mechanics.h"
#include "models/typical_values.h"
#include "sim/context.h"

namespace tcpmsim {

namespace {
constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();

// Windows longer than this are surely typos (10^4 samples is 8 minutes at 20 Hz).
constexpr double kMaximumWindow = 10000;

double checked_period(double period) {
  if (!(period > 0.0) || !std::isfinite(period))
    throw std::invalid_argument("self-sensing estimator: the sample period must be positive");
  return period;
}
}  // namespace

SelfSensingEstimation::SelfSensingEstimation(const SelfSensingEstimatorParameters& parameters,
                                             double period)
    : parameters_(parameters),
      period_(checked_period(period)),
      moving_average_(parameters.moving_average_length),
      median_(parameters.median_length),
      low_pass_(parameters.low_pass_cutoff, period),
      thermal_(parameters.heating_gain, parameters.cooling_rate, period),
      sls_(parameters.mechanics, period) {
  if (parameters_.inductance.lambda_T != 0.0) {
    throw std::invalid_argument(
        "self-sensing estimator: (7.4) has no temperature term (lambda_T must be 0)");
  }
  restart();
}

// A run: its estimation, and the last sample's index to tell a new run from the next sample.
struct SelfSensingEstimator::Run final : RunState {
  Run(const SelfSensingEstimatorParameters& parameters, double period)
      : estimation(parameters, period) {}
  SelfSensingEstimation estimation;
  long last_index = 0;
};

SelfSensingEstimator::SelfSensingEstimator(std::string group,
                                           SelfSensingEstimatorParameters defaults, double period)
    : SelfSensingEstimator(std::move(group), defaults, period, {}) {}

SelfSensingEstimator::SelfSensingEstimator(
    std::string group, SelfSensingEstimatorParameters defaults, double period,
    ParameterBindings<SelfSensingEstimatorParameters> bindings)
    : SampledComponent(std::move(group), "self_sensing_estimator", checked_period(period),
                       SamplingStage::estimator),
      defaults_(defaults),
      bindings_(std::move(bindings)) {
  SelfSensingEstimation check(defaults_, period);  // throws for an impossible model
}

std::unique_ptr<SelfSensingEstimator> SelfSensingEstimator::from_config(
    const std::string& group, const ConfigNode& node, double period,
    std::function<double(double)> mutual_measure) {
  using P = SelfSensingEstimatorParameters;
  node.declare({"inductance", "filters", "thermal", "mechanics", "calibration"});
  P p;
  ParameterBindings<P> bind;

  const ConfigNode inductance = node.at("inductance");
  inductance.declare({"lambda_l", "lambda_x", "lambda_0"});
  p.inductance.is_measure = true;
  bind.quantity(inductance, "lambda_l", "s*m", ValueCheck::positive(), p,
                [](P& v) -> double& { return v.inductance.lambda_l; });
  bind.quantity(inductance, "lambda_x", "m", ValueCheck::positive(), p,
                [](P& v) -> double& { return v.inductance.lambda_x; });
  bind.quantity(inductance, "lambda_0", "s", ValueCheck::non_negative(), p,
                [](P& v) -> double& { return v.inductance.lambda_0; });

  if (const auto filters = node.find("filters")) {
    filters->declare({"moving_average", "median", "low_pass_cutoff"});
    p.moving_average_length = static_cast<int>(filters->integer_or(
        "moving_average", p.moving_average_length, ValueCheck::between(1, kMaximumWindow)));
    p.median_length = static_cast<int>(
        filters->integer_or("median", p.median_length, ValueCheck::between(1, kMaximumWindow)));
    bind.quantity_or(*filters, "low_pass_cutoff", "Hz", p.low_pass_cutoff, ValueCheck::positive(),
                     p, bind.member(&P::low_pass_cutoff));
  } else {
    bind.bind(node.parameter_path("filters.low_pass_cutoff"), "Hz", ValueCheck::positive(),
              bind.member(&P::low_pass_cutoff));
  }

  const ConfigNode thermal = node.at("thermal");
  thermal.declare({"kappa_P", "kappa_c", "initial_thermal_force"});
  bind.quantity(thermal, "kappa_P", "N/J", typical::heating_gain(ValueCheck::positive()), p,
                bind.member(&P::heating_gain));
  bind.quantity(thermal, "kappa_c", "1/s", typical::cooling_rate(ValueCheck::positive()), p,
                bind.member(&P::cooling_rate));
  bind.quantity_or(thermal, "initial_thermal_force", "N", 0.0, {}, p,
                   bind.member(&P::initial_thermal_force));

  ParameterBindings<SlsParameters> mechanics;
  p.mechanics = SlsMechanics::read(node.at("mechanics"), &mechanics);
  bind.nest(mechanics,
            std::function<SlsParameters&(P&)>([](P& v) -> SlsParameters& { return v.mechanics; }));

  if (const auto calibration = node.find("calibration")) {
    calibration->declare({"deflection_offset", "force_offset"});
    bind.quantity_or(*calibration, "deflection_offset", "m", 0.0, {}, p,
                     bind.member(&P::deflection_offset));
    bind.quantity_or(*calibration, "force_offset", "N", 0.0, {}, p, bind.member(&P::force_offset));
  } else {
    bind.bind(node.parameter_path("calibration.deflection_offset"), "m", {},
              bind.member(&P::deflection_offset));
    bind.bind(node.parameter_path("calibration.force_offset"), "N", {},
              bind.member(&P::force_offset));
  }
  p.mutual_measure = std::move(mutual_measure);
  return std::make_unique<SelfSensingEstimator>(group, p, period, std::move(bind));
}

std::vector<OutputDeclaration> SelfSensingEstimator::outputs() const {
  return {{"deflection", "m"},
          {"velocity", "m/s"},
          {"force", "N"},
          {"thermal_force", "N"},
          {"raw_deflection", "m"}};
}

std::vector<InputDeclaration> SelfSensingEstimator::inputs() const {
  return {{"inductance_measure", false, true}, {"power_command", false, true}};
}

std::vector<ParameterDeclaration> SelfSensingEstimator::parameters() const {
  return with_period(bindings_.declarations(defaults_));
}

std::unique_ptr<RunState> SelfSensingEstimator::create_run_state(const RunSetup& setup) const {
  return std::make_unique<Run>(bindings_.assign(defaults_, own_parameters(setup)),
                               setup.parameters[0]);
}

std::string SelfSensingEstimator::check_parameters(const RunSetup& setup) const {
  try {
    SelfSensingEstimation check(bindings_.assign(defaults_, own_parameters(setup)),
                                setup.parameters[0]);
  } catch (const std::exception& error) {
    return error.what();
  }
  return {};
}

void SelfSensingEstimator::compute_outputs(const Evaluation& evaluation) const {
  const SelfSensingEstimate& estimate = run_state<Run>(evaluation).estimation.estimate();
  set_output(evaluation, kDeflection, estimate.deflection);
  set_output(evaluation, kVelocity, estimate.velocity);
  set_output(evaluation, kForce, estimate.force);
  set_output(evaluation, kThermalForce, estimate.thermal_force);
  set_output(evaluation, kRawDeflection, estimate.raw_deflection);
}

void SelfSensingEstimator::sample(const Evaluation& evaluation, long index) const {
  Run& run = mutable_run_state<Run>(evaluation);
  if (!run.estimation.started() || index != run.last_index + 1) run.estimation.restart();
  run.last_index = index;
  run.estimation.process(input(evaluation, kInductanceMeasure), input(evaluation, kPowerCommand));
}

double SelfSensingEstimation::model_deflection(double inductance_measure) const {
  const InductanceLaw& law = parameters_.inductance;
  if (!parameters_.mutual_measure)
    return law.deflection(inductance_measure, law.reference_temperature);  // (7.4)
  return law.coupled_deflection(inductance_measure, law.reference_temperature,
                                parameters_.mutual_measure);
}

const SelfSensingEstimate& SelfSensingEstimation::process(double inductance_measure,
                                                          double power_command) {
  if (!std::isfinite(power_command)) {
    throw std::domain_error("self-sensing estimator: the power command is not finite");
  }
  // F_T: the first sample sets the initial value; later ones integrate the power held since the
  // previous sample (7.1).
  if (!started_) {
    thermal_.reset(parameters_.initial_thermal_force);
    started_ = true;
  } else {
    thermal_.advance(power_command);
  }

  // L* through the spike filters and (7.4).
  bool fresh = false;
  if (std::isfinite(inductance_measure) && inductance_measure > 0.0) {
    const double filtered = median_.push(moving_average_.push(inductance_measure));
    const double deflection = filtered > parameters_.inductance.lambda_0
                                  ? model_deflection(filtered)
                                  : std::numeric_limits<double>::quiet_NaN();
    if (std::isfinite(deflection)) {
      model_raw_deflection_ = deflection;
      fresh = true;
    } else {
      ++out_of_domain_samples_;
    }
  } else {
    ++rejected_measurements_;
  }

  // Low-pass, velocity and SLS run every sample once a deflection exists, on the held raw
  // deflection when this sample brought none.
  if (!has_deflection_ && fresh) {
    has_deflection_ = true;
    model_deflection_ = low_pass_.push(model_raw_deflection_);
    velocity_ = 0.0;
    sls_.reset(model_deflection_ + parameters_.deflection_offset);
  } else if (has_deflection_) {
    const double previous = model_deflection_;
    model_deflection_ = low_pass_.push(model_raw_deflection_);
    velocity_ = (model_deflection_ - previous) / period_;
    sls_.advance(model_deflection_ + parameters_.deflection_offset, velocity_);
  }
  publish();
  return estimate_;
}

void SelfSensingEstimation::publish() {
  estimate_.thermal_force = thermal_.value();
  if (!has_deflection_) {
    estimate_.deflection = estimate_.velocity = estimate_.force = estimate_.raw_deflection =
        kUnknown;
    return;
  }
  estimate_.deflection = model_deflection_ + parameters_.deflection_offset;
  estimate_.raw_deflection = model_raw_deflection_ + parameters_.deflection_offset;
  estimate_.velocity = velocity_;
  estimate_.force = sls::total_force(parameters_.mechanics, sls_.value(), thermal_.value()) +
                    parameters_.force_offset;  // (7.5)
}

void SelfSensingEstimation::restart() {
  moving_average_.reset();
  median_.reset();
  low_pass_.reset();
  thermal_.reset(parameters_.initial_thermal_force);
  started_ = false;
  has_deflection_ = false;
  model_raw_deflection_ = model_deflection_ = velocity_ = 0.0;
  rejected_measurements_ = out_of_domain_samples_ = 0;
  publish();
}

void SelfSensingEstimation::set_deflection_offset(double offset) {
  if (!std::isfinite(offset)) throw std::invalid_argument("deflection offset must be finite");
  parameters_.deflection_offset = offset;
  publish();
}

void SelfSensingEstimation::set_force_offset(double offset) {
  if (!std::isfinite(offset)) throw std::invalid_argument("force offset must be finite");
  parameters_.force_offset = offset;
  publish();
}

}  // namespace tcpmsim
