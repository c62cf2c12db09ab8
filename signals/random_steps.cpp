#include "signals/random_steps.h"

#include <algorithm>
#include <cmath>

namespace tcpmsim {

double switching_probability(const RandomStepsSettings& settings) {
  return 1.0 / (0.5 * settings.process_time_constant * settings.sample_rate);  // (7.14), corrected
}

std::unique_ptr<PiecewiseConstantSignal> make_random_steps(const RandomStepsSettings& settings,
                                                           RandomStream& stream) {
  const double span = settings.high - settings.low;
  const double probability = switching_probability(settings);
  const auto samples = static_cast<long>(std::floor(settings.duration * settings.sample_rate));
  double level = 0.5 * (settings.low + settings.high);
  std::vector<double> times, values;
  for (long k = 1; k < samples; ++k) {
    if (!stream.chance(probability)) continue;
    const double size = stream.uniform(0.0, settings.max_step_fraction * span);
    double direction = stream.chance(0.5) ? 1.0 : -1.0;
    const double candidate = level + direction * size;
    if (candidate > settings.high || candidate < settings.low) direction = -direction;
    level += direction * size;
    times.push_back(static_cast<double>(k) / settings.sample_rate);
    values.push_back(level);
  }
  double initial = 0.5 * (settings.low + settings.high);
  if (settings.scale_to_range && !values.empty()) {
    const double lowest = std::min(initial, *std::min_element(values.begin(), values.end()));
    const double highest = std::max(initial, *std::max_element(values.begin(), values.end()));
    if (highest > lowest) {
      const double gain = span / (highest - lowest);
      auto scale = [&](double v) { return settings.low + gain * (v - lowest); };
      initial = scale(initial);
      std::transform(values.begin(), values.end(), values.begin(), scale);
    }
  }
  SignalDescription description{"random_steps",
                                {{"low", settings.low},
                                 {"high", settings.high},
                                 {"process_time_constant", settings.process_time_constant},
                                 {"sample_rate", settings.sample_rate},
                                 {"max_step_fraction", settings.max_step_fraction},
                                 {"switching_probability", probability}},
                                {},
                                {}};
  return std::make_unique<PiecewiseConstantSignal>(initial, std::move(times), std::move(values),
                                                   std::move(description));
}

}  // namespace tcpmsim
