#pragma once

#include <functional>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "sim/component.h"
#include "sim/parameters.h"

namespace tcpmsim {

// What a signal is, in enough detail to rebuild it offline (written to /inputs in the HDF5).
struct SignalDescriptionPart;

struct SignalDescription {
  std::string type;
  std::vector<std::pair<std::string, double>> parameters;
  std::vector<std::pair<std::string, std::vector<double>>> arrays;
  std::vector<SignalDescriptionPart> parts;
  // Member by member, in the source, where the parts are complete.
  bool operator==(const SignalDescription&) const;
};

// A signal a composed signal is made of (a sequence's segment), by name.
struct SignalDescriptionPart {
  std::string name;
  SignalDescription description;
  bool operator==(const SignalDescriptionPart&) const = default;
};

class Signal;

// How a signal read from a scenario is made from its numeric parameters, so that a run context
// can have the same signal with other values (a power level, a step time, a sweep band) without
// reading the scenario again: its own parameters, the signals it is made of (a sequence's
// segments), and the function that makes it.
struct SignalRecipe {
  using Make = std::function<std::unique_ptr<Signal>(std::span<const double> own,
                                                     std::vector<std::unique_ptr<Signal>> parts)>;
  std::vector<ParameterDeclaration> parameters;
  std::vector<std::shared_ptr<const SignalRecipe>> parts;
  Make make;

  // Own parameters and the parts', depth first.
  std::size_t size() const;
  void collect(std::vector<ParameterDeclaration>& into) const;
  // The signal for `values` (size() of them), its recipe attached.
  std::unique_ptr<Signal> build(std::span<const double> values) const;
};

// A prescribed function of time: an excitation applied to a duty cycle, a power, an imposed
// deflection or force, or an ambient temperature. Values are SI and right-continuous.
class Signal {
 public:
  virtual ~Signal() = default;
  virtual double value(double time) const = 0;
  // d value / dt (right derivative). The default differentiates numerically; smooth signals
  // override it exactly.
  virtual double slope(double time) const;
  // The first time strictly after `time` where the signal or its slope jumps.
  virtual double next_breakpoint_after(double time) const;
  virtual SignalDescription describe() const = 0;
  // Smallest and largest value over [begin, end], for validating against physical limits.
  virtual std::pair<double, double> range(double begin, double end) const = 0;

  // The numeric parameters of a signal read from a scenario (none for one made in code).
  std::vector<ParameterDeclaration> parameters() const;
  // The same signal with other parameter values (as many as parameters()). Throws
  // std::invalid_argument if they do not make a signal (step times out of order).
  std::unique_ptr<Signal> with_parameters(std::span<const double> values) const;
  void set_recipe(std::shared_ptr<const SignalRecipe> recipe) { recipe_ = std::move(recipe); }
  const std::shared_ptr<const SignalRecipe>& recipe() const { return recipe_; }

 private:
  std::shared_ptr<const SignalRecipe> recipe_;
};

}  // namespace tcpmsim
