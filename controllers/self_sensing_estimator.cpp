#include "controllers/self_sensing_estimator.h"

#include <cmath>
#include <limits>
#include <stdexcept>

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

SelfSensingEstimator::SelfSensingEstimator(std::string group,
                                           SelfSensingEstimatorParameters parameters, double period)
    : SampledComponent(std::move(group), "self_sensing_estimator", checked_period(period),
                       SamplingStage::estimator),
      parameters_(parameters),
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

std::unique_ptr<SelfSensingEstimator> SelfSensingEstimator::from_config(const std::string& group,
                                                                        const ConfigNode& node,
                                                                        double period) {
  node.declare({"inductance", "filters", "thermal", "mechanics", "calibration"});
  SelfSensingEstimatorParameters p;

  const ConfigNode inductance = node.at("inductance");
  inductance.declare({"lambda_l", "lambda_x", "lambda_0"});
  p.inductance.is_measure = true;
  p.inductance.lambda_l = inductance.quantity("lambda_l", "s*m", ValueCheck::positive());
  p.inductance.lambda_x = inductance.quantity("lambda_x", "m", ValueCheck::positive());
  p.inductance.lambda_0 = inductance.quantity("lambda_0", "s", ValueCheck::non_negative());

  if (const auto filters = node.find("filters")) {
    filters->declare({"moving_average", "median", "low_pass_cutoff"});
    p.moving_average_length = static_cast<int>(filters->integer_or(
        "moving_average", p.moving_average_length, ValueCheck::between(1, kMaximumWindow)));
    p.median_length = static_cast<int>(
        filters->integer_or("median", p.median_length, ValueCheck::between(1, kMaximumWindow)));
    p.low_pass_cutoff =
        filters->quantity_or("low_pass_cutoff", "Hz", p.low_pass_cutoff, ValueCheck::positive());
  }

  const ConfigNode thermal = node.at("thermal");
  thermal.declare({"kappa_P", "kappa_c", "initial_thermal_force"});
  p.heating_gain = thermal.quantity("kappa_P", "N/J", ValueCheck::positive());
  p.cooling_rate = thermal.quantity("kappa_c", "1/s", ValueCheck::positive());
  p.initial_thermal_force = thermal.quantity_or("initial_thermal_force", "N", 0.0);

  p.mechanics = SlsMechanics::parameters_from_config(node.at("mechanics"));

  if (const auto calibration = node.find("calibration")) {
    calibration->declare({"deflection_offset", "force_offset"});
    p.deflection_offset = calibration->quantity_or("deflection_offset", "m", 0.0);
    p.force_offset = calibration->quantity_or("force_offset", "N", 0.0);
  }
  return std::make_unique<SelfSensingEstimator>(group, p, period);
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

void SelfSensingEstimator::compute_outputs(const Evaluation& evaluation) const {
  set_output(evaluation, kDeflection, estimate_.deflection);
  set_output(evaluation, kVelocity, estimate_.velocity);
  set_output(evaluation, kForce, estimate_.force);
  set_output(evaluation, kThermalForce, estimate_.thermal_force);
  set_output(evaluation, kRawDeflection, estimate_.raw_deflection);
}

void SelfSensingEstimator::sample(const Evaluation& evaluation, long index) {
  if (!started_ || index != last_index_ + 1) restart();
  last_index_ = index;
  process(input(evaluation, kInductanceMeasure), input(evaluation, kPowerCommand));
}

double SelfSensingEstimator::model_deflection(double inductance_measure) const {
  return parameters_.inductance.deflection(inductance_measure,
                                           parameters_.inductance.reference_temperature);  // (7.4)
}

const SelfSensingEstimate& SelfSensingEstimator::process(double inductance_measure,
                                                         double power_command) {
  if (!std::isfinite(power_command)) {
    throw std::domain_error(group() + "/self_sensing_estimator: the power command is not finite");
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
    if (filtered > parameters_.inductance.lambda_0) {
      model_raw_deflection_ = model_deflection(filtered);
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
    velocity_ = (model_deflection_ - previous) / period();
    sls_.advance(model_deflection_ + parameters_.deflection_offset, velocity_);
  }
  publish();
  return estimate_;
}

void SelfSensingEstimator::publish() {
  estimate_.thermal_force = thermal_.value();
  if (!has_deflection_) {
    estimate_.deflection = estimate_.velocity = estimate_.force = estimate_.raw_deflection =
        kUnknown;
    return;
  }
  estimate_.deflection = model_deflection_ + parameters_.deflection_offset;
  estimate_.raw_deflection = model_raw_deflection_ + parameters_.deflection_offset;
  estimate_.velocity = velocity_;
  estimate_.force = sls_.value() + thermal_.value() + parameters_.mechanics.force_offset +
                    parameters_.force_offset;  // (7.5)
}

void SelfSensingEstimator::restart() {
  moving_average_.reset();
  median_.reset();
  low_pass_.reset();
  thermal_.reset(parameters_.initial_thermal_force);
  started_ = false;
  has_deflection_ = false;
  last_index_ = 0;
  model_raw_deflection_ = model_deflection_ = velocity_ = 0.0;
  rejected_measurements_ = out_of_domain_samples_ = 0;
  publish();
}

void SelfSensingEstimator::set_deflection_offset(double offset) {
  if (!std::isfinite(offset)) throw std::invalid_argument("deflection offset must be finite");
  parameters_.deflection_offset = offset;
  publish();
}

void SelfSensingEstimator::set_force_offset(double offset) {
  if (!std::isfinite(offset)) throw std::invalid_argument("force offset must be finite");
  parameters_.force_offset = offset;
  publish();
}

}  // namespace tcpmsim
