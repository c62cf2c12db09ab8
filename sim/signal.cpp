#include "sim/signal.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tcpmsim {

bool SignalDescription::operator==(const SignalDescription& other) const {
  return type == other.type && parameters == other.parameters && arrays == other.arrays &&
         parts == other.parts;
}

double Signal::slope(double time) const {
  // One-sided, so that a breakpoint at `time` is not straddled; second order.
  const double h = 1e-6 * std::max(1.0, std::abs(time));
  return (-3.0 * value(time) + 4.0 * value(time + h) - value(time + 2.0 * h)) / (2.0 * h);
}

double Signal::next_breakpoint_after(double) const {
  return kNoBreakpoint;
}

std::vector<ParameterDeclaration> Signal::parameters() const {
  std::vector<ParameterDeclaration> declared;
  if (recipe_) recipe_->collect(declared);
  return declared;
}

std::unique_ptr<Signal> Signal::with_parameters(std::span<const double> values) const {
  if (!recipe_) throw std::invalid_argument("this signal has no parameters");
  return recipe_->build(values);
}

std::size_t SignalRecipe::size() const {
  std::size_t count = parameters.size();
  for (const auto& part : parts) count += part->size();
  return count;
}

void SignalRecipe::collect(std::vector<ParameterDeclaration>& into) const {
  into.insert(into.end(), parameters.begin(), parameters.end());
  for (const auto& part : parts) part->collect(into);
}

std::unique_ptr<Signal> SignalRecipe::build(std::span<const double> values) const {
  if (values.size() != size()) throw std::invalid_argument("wrong number of signal parameters");
  const auto own = values.first(parameters.size());
  std::size_t next = parameters.size();
  auto recipe = std::make_shared<SignalRecipe>(*this);
  std::vector<std::unique_ptr<Signal>> built;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const std::size_t count = parts[k]->size();
    built.push_back(parts[k]->build(values.subspan(next, count)));
    recipe->parts[k] = built.back()->recipe();
    next += count;
  }
  for (std::size_t i = 0; i < own.size(); ++i) recipe->parameters[i].value = own[i];
  std::unique_ptr<Signal> signal = make(own, std::move(built));
  signal->set_recipe(std::move(recipe));
  return signal;
}

}  // namespace tcpmsim
