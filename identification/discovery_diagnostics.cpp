#include "identification/discovery_diagnostics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

#include "identification/effect_catalogue.h"
#include "sim/not_a_number.h"
#include "sim/value_check.h"

namespace tcpmsim::fit {

namespace {

// The residual's bands: drift and warm-up, the protocol's slow and fast excitation, and the rest
// up to Nyquist.
std::vector<std::pair<double, double>> residual_bands(double dt) {
  const double nyquist = 0.5 / dt;
  return {{0.0, 0.01}, {0.01, 0.1}, {0.1, 1.0}, {1.0, nyquist + 1e-9}};
}

// Log-spaced bands from 0.005 Hz to Nyquist, four per decade, for the loop spectrum.
std::vector<std::pair<double, double>> loop_bands(double dt) {
  std::vector<std::pair<double, double>> bands;
  const double nyquist = 0.5 / dt;
  for (double lower = 0.005; lower < nyquist; lower *= std::pow(10.0, 0.25))
    bands.emplace_back(lower, std::min(nyquist, lower * std::pow(10.0, 0.25)));
  return bands;
}

// The measured channel's values at the samples [first, last), or empty.
std::vector<double> measured(const MeasuredData& data, const std::string& channel,
                             std::size_t first, std::size_t last) {
  const MeasuredChannel* found = data.find(channel);
  if (!found) return {};
  return {found->values.begin() + static_cast<long>(first),
          found->values.begin() + static_cast<long>(last)};
}

// Central differences (one-sided at the ends).
std::vector<double> rate_of(const std::vector<double>& time, const std::vector<double>& values) {
  std::vector<double> rate(values.size(), 0.0);
  for (std::size_t i = 0; i < values.size(); ++i) {
    const std::size_t a = i == 0 ? 0 : i - 1, b = std::min(values.size() - 1, i + 1);
    if (b > a) rate[i] = (values[b] - values[a]) / (time[b] - time[a]);
  }
  return rate;
}

std::vector<Feature> features(const FitProblem& problem, const std::vector<double>& values,
                              const std::vector<double>& time, std::size_t first, std::size_t last,
                              const MeasuredRoles& roles) {
  const MeasuredData& data = *problem.data;
  std::vector<Feature> result;
  const std::vector<double> power = measured(data, roles.power, first, last);
  if (!power.empty()) result.push_back({"power", power});
  const std::vector<double> temperature =
      model_temperature(problem, values, {time.front(), time.back()});
  double ambient = kNaN;
  if (!temperature.empty()) {
    ambient = *std::min_element(temperature.begin(), temperature.end());
    std::vector<double> rise;
    for (double t : temperature) rise.push_back(t - ambient);
    result.push_back({"temperature rise", rise});
  }
  const std::vector<double> deflection = measured(data, roles.deflection, first, last);
  if (!deflection.empty()) {
    result.push_back({"deflection", deflection});
    const std::vector<double> rate = rate_of(time, deflection);
    result.push_back({"deflection rate", rate});
    // Rate-independent memory: the direction of the last motion, held while the deflection
    // rests (a hysteretic force keeps its branch between moves).
    std::vector<double> direction;
    double last = 0.0;
    for (double v : rate) {
      if (v != 0.0) last = v > 0 ? 1.0 : -1.0;
      direction.push_back(last);
    }
    result.push_back({"last direction of motion", direction});
    const double mean =
        std::accumulate(deflection.begin(), deflection.end(), 0.0) / double(deflection.size());
    std::vector<double> square;
    for (double x : deflection) square.push_back((x - mean) * (x - mean));
    result.push_back({"deflection^2", square});
    if (!temperature.empty()) {
      std::vector<double> product;
      for (std::size_t i = 0; i < deflection.size(); ++i)
        product.push_back((temperature[i] - ambient) * deflection[i]);
      result.push_back({"temperature rise x deflection", product});
    }
  }
  return result;
}

std::string value_text(double value) {
  return number_text(value, 2);
}

}  // namespace

std::vector<double> model_temperature(const FitProblem& problem, const std::vector<double>& values,
                                      const TimeWindow& window) {
  const std::string output = only_muscle(*problem.model->system) + ".temperature";
  if (problem.model->system->signal_index(output) < 0) return {};
  FitProblem probe = problem;
  probe.outputs = {{"temperature", output, "K", 1.0}};
  return simulate_outputs(probe, values, window)[0];
}

double ResidualDiagnostics::feature(std::size_t output, const std::string& name) const {
  for (const auto& [feature_name, value] : outputs[output].features) {
    if (feature_name == name) return value;
  }
  return kNaN;
}

ResidualDiagnostics diagnose(const FitProblem& problem, const std::vector<double>& values,
                             const std::vector<std::string>& inputs, const MeasuredRoles& roles) {
  const auto [first, last] = samples_in(*problem.data, problem.validation);
  ResidualDiagnostics result;
  const auto& all_times = problem.data->time();
  result.time.assign(all_times.begin() + static_cast<long>(first),
                     all_times.begin() + static_cast<long>(last));
  if (result.time.size() < 16)
    throw std::invalid_argument("the validation window holds fewer than 16 samples");
  const double dt =
      (result.time.back() - result.time.front()) / static_cast<double>(result.time.size() - 1);
  result.bands = residual_bands(dt);
  result.bound = 1.96 / std::sqrt(static_cast<double>(result.time.size()));
  result.roles = roles;
  result.features = features(problem, values, result.time, first, last, roles);
  const auto simulated = simulate_outputs(problem, values, problem.validation);
  const auto measured_values = measured_outputs(problem, problem.validation);
  const std::vector<double> deflection = measured(*problem.data, roles.deflection, first, last);
  const int lags = std::min<int>(32, static_cast<int>(result.time.size() / 4));
  for (std::size_t k = 0; k < problem.outputs.size(); ++k) {
    OutputDiagnostics output;
    output.channel = problem.outputs[k].channel;
    for (std::size_t i = 0; i < simulated[k].size(); ++i)
      output.residual.push_back(measured_values[k][i] - simulated[k][i]);
    output.whiteness = ljung_box(output.residual, std::min(20, lags));
    output.drift = drift(result.time, output.residual);
    output.band_share = band_power(output.residual, dt, result.bands);
    for (const auto& input : inputs) {
      const std::vector<double> series = measured(*problem.data, input, first, last);
      if (!series.empty())
        output.inputs.emplace_back(input, cross_correlation(series, output.residual, lags));
    }
    for (const auto& feature : result.features)
      output.features.emplace_back(feature.name, correlation(feature.values, output.residual));
    if (!deflection.empty())
      output.loop = loop_spectrum(deflection, output.residual, dt, loop_bands(dt));
    result.outputs.push_back(std::move(output));
  }
  return result;
}

std::string signature_evidence(const std::string& effect, const ResidualDiagnostics& diagnostics,
                               const FitProblem& problem) {
  // The force's residual tells the mechanical and thermal effects; the coil output's, the
  // inductance's.
  std::size_t k = 0;
  for (std::size_t j = 0; j < problem.outputs.size(); ++j) {
    const bool coil = problem.outputs[j].output.find("inductance") != std::string::npos;
    if ((effect == "inductance_temperature") == coil) {
      k = j;
      break;
    }
  }
  const OutputDiagnostics& output = diagnostics.outputs[k];
  std::ostringstream out;
  out << output.channel << " residual: ";
  const auto corr = [&](const std::string& feature) {
    out << "corr(r, " << feature << ") = " << value_text(diagnostics.feature(k, feature));
  };
  const std::string white = " (white noise: |corr| < " + value_text(diagnostics.bound) + ")";
  if (effect == "slow_relaxation") {
    out << "drift t = " << value_text(output.drift.t_statistic) << ", "
        << value_text(100 * output.band_share[0]) << " % of its power below 0.01 Hz";
  } else if (effect == "hysteresis" || effect == "viscoelastic_relaxation") {
    corr(effect == "hysteresis" ? "last direction of motion" : "deflection rate");
    out << white;
    if (!output.loop.frequency.empty())
      out << "; loop area ~ f^" << value_text(output.loop.exponent)
          << " (rate-independent: f^0, viscous: f^1)";
  } else if (effect == "nonlinear_convection" || effect == "inductance_temperature") {
    corr("temperature rise");
    out << white;
  } else if (effect == "thermal_lag") {
    for (const auto& [input, cross] : output.inputs) {
      if (input != diagnostics.roles.power) continue;
      out << "cross-correlation with power peaks at " << value_text(cross.peak) << " at lag "
          << cross.peak_lag << " samples (white noise: |c| < " << value_text(cross.bound) << ")";
    }
  } else if (effect == "nonlinear_stiffness") {
    corr("deflection");
    out << ", ";
    corr("deflection^2");
    out << white;
  } else if (effect == "temperature_dependent_stiffness") {
    corr("temperature rise x deflection");
    out << white;
  } else if (effect == "ratchet") {
    out << "drift t = " << value_text(output.drift.t_statistic) << ", ";
    corr("temperature rise");
    out << white;
  } else if (effect == "heating_dependent_convection") {
    corr("power");
    out << ", ";
    corr("temperature rise");
    out << white;
  }
  return out.str();
}

std::vector<SignatureStrength> ranked_signatures(const ResidualDiagnostics& diagnostics,
                                                 std::size_t output) {
  const OutputDiagnostics& diagnosed = diagnostics.outputs[output];
  std::vector<SignatureStrength> ranked;
  for (const auto& [feature, value] : diagnosed.features) {
    if (std::isfinite(value) && diagnostics.bound > 0)
      ranked.push_back(
          {"corr(r, " + feature + ") = " + value_text(value), std::abs(value) / diagnostics.bound});
  }
  for (const auto& [input, cross] : diagnosed.inputs) {
    if (std::isfinite(cross.peak) && cross.bound > 0)
      ranked.push_back({"cross-correlation with " + input + " peaks at " + value_text(cross.peak) +
                            " at lag " + std::to_string(cross.peak_lag) + " samples",
                        std::abs(cross.peak) / cross.bound});
  }
  if (std::isfinite(diagnosed.drift.t_statistic))
    ranked.push_back({"drift t = " + value_text(diagnosed.drift.t_statistic),
                      std::abs(diagnosed.drift.t_statistic) / 1.96});
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](const auto& a, const auto& b) { return a.strength > b.strength; });
  return ranked;
}

}  // namespace tcpmsim::fit
