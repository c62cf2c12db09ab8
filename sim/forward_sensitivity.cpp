#include "sim/forward_sensitivity.h"

#include "sim/time_grid.h"
#include "sim/value_check.h"

#include <optional>
#include <stdexcept>
#include <string>

namespace tcpmsim {

namespace {

// A copy of `base` with parameter `index` moved by `shift` and prepared, or nothing when the
// parameter's range or a condition between parameters refuses the moved value.
std::optional<Context> moved_context(const Context& base, int index, double shift) {
  Context context(base);
  try {
    if (shift != 0.0) context.set_parameter(index, base.parameter(index) + shift);
    base.system().prepare(context);
  } catch (const ParameterError&) {
    return std::nullopt;
  }
  return context;
}

}  // namespace

std::string ForwardSensitivities::unsupported_reason(const System& system) {
  if (system.event_count() > 0) return "the model has zero-crossing events";
  for (const auto& component : system.components()) {
    if (component->acts_discretely()) {
      return "component " + component->group() + " (" + component->kind() +
             ") changes its state at sample instants or events";
    }
  }
  return "";
}

ForwardSensitivities::ForwardSensitivities(const Context& base, std::vector<int> parameters,
                                           std::vector<double> scales, double relative_step)
    : system_(base.system()), parameters_(std::move(parameters)), scales_(std::move(scales)) {
  if (const std::string reason = unsupported_reason(system_); !reason.empty())
    throw std::invalid_argument("no forward sensitivities: " + reason);
  if (scales_.size() != parameters_.size())
    throw std::invalid_argument("one scale per sensitivity parameter is needed");
  const auto size = static_cast<std::size_t>(system_.state_size());
  for (std::size_t j = 0; j < parameters_.size(); ++j) {
    const double step = relative_step * scales_[j];
    const int index = parameters_[j];
    auto high = moved_context(base, index, step);
    auto low = moved_context(base, index, -step);
    if (!high && !low) {
      throw ParameterError(
          system_.parameters()[static_cast<std::size_t>(index)].declaration.path,
          "cannot move by " + std::to_string(step) + " either way for its sensitivity");
    }
    Moved moved{{}, 0.0};
    moved.sides.push_back(high ? Side{std::move(*high), step}
                               : Side{*moved_context(base, index, 0.0), 0.0});
    moved.sides.push_back(low ? Side{std::move(*low), -step}
                              : Side{*moved_context(base, index, 0.0), 0.0});
    moved.span = moved.sides[0].shift - moved.sides[1].shift;
    moved_.push_back(std::move(moved));
  }
  moved_state_.assign(size, 0.0);
  high_.assign(size, 0.0);
  low_.assign(size, 0.0);
  output_sensitivities_.assign(
      parameters_.size(), std::vector<double>(static_cast<std::size_t>(system_.signal_size())));
}

const double* ForwardSensitivities::moved_state(const double* state, const double* sensitivity,
                                                double shift) {
  for (std::size_t i = 0; i < moved_state_.size(); ++i)
    moved_state_[i] = state[i] + shift * sensitivity[i];
  return moved_state_.data();
}

void ForwardSensitivities::initialize(double t0, std::span<double* const> sensitivities) {
  for (std::size_t j = 0; j < moved_.size(); ++j) {
    Side& high = moved_[j].sides[0];
    Side& low = moved_[j].sides[1];
    system_.initialize(high.context, t0, high_.data());
    system_.initialize(low.context, t0, low_.data());
    for (std::size_t i = 0; i < high_.size(); ++i)
      sensitivities[j][i] = (high_[i] - low_[i]) / moved_[j].span;
    system_.at_breakpoint(high.context, t0, t0, high_.data());
    system_.at_breakpoint(low.context, t0, t0, low_.data());
  }
}

void ForwardSensitivities::derivatives(int j, double t, double signal_time, const double* state,
                                       const double* sensitivity, double* result) {
  auto& moved = moved_[static_cast<std::size_t>(j)];
  system_.evaluate_derivatives(moved.sides[0].context, t, signal_time,
                               moved_state(state, sensitivity, moved.sides[0].shift), high_.data());
  system_.evaluate_derivatives(moved.sides[1].context, t, signal_time,
                               moved_state(state, sensitivity, moved.sides[1].shift), low_.data());
  for (std::size_t i = 0; i < high_.size(); ++i) result[i] = (high_[i] - low_[i]) / moved.span;
}

void ForwardSensitivities::outputs(int j, double t, double signal_time, const double* state,
                                   const double* sensitivity) {
  auto& moved = moved_[static_cast<std::size_t>(j)];
  Side& high = moved.sides[0];
  Side& low = moved.sides[1];
  system_.evaluate_outputs(high.context, t, signal_time,
                           moved_state(state, sensitivity, high.shift));
  system_.evaluate_outputs(low.context, t, signal_time, moved_state(state, sensitivity, low.shift));
  auto& result = output_sensitivities_[static_cast<std::size_t>(j)];
  const auto& high_signals = high.context.signals();
  const auto& low_signals = low.context.signals();
  for (std::size_t k = 0; k < result.size(); ++k)
    result[k] = (high_signals[k] - low_signals[k]) / moved.span;
}

void ForwardSensitivities::check_breakpoint(double time, double next) {
  for (std::size_t j = 0; j < moved_.size(); ++j) {
    for (auto& side : moved_[j].sides) {
      const double moved = system_.next_breakpoint_after(side.context, time);
      if (std::min(moved, next) < kNoBreakpoint && !same_instant(moved, next)) {
        throw std::invalid_argument(
            "no forward sensitivity to " +
            system_.parameters()[static_cast<std::size_t>(parameters_[j])].declaration.path +
            ": it moves the discontinuity at t = " + number_text(next) + " s");
      }
    }
  }
}

void ForwardSensitivities::at_breakpoint(double time, double left_limit, const double* state,
                                         std::span<const double* const> sensitivities) {
  for (std::size_t j = 0; j < moved_.size(); ++j) {
    for (auto& side : moved_[j].sides) {
      system_.at_breakpoint(side.context, time, left_limit,
                            moved_state(state, sensitivities[j], side.shift));
    }
  }
}

}  // namespace tcpmsim
