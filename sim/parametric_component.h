#pragma once

#include <memory>
#include <utility>

#include "sim/component.h"
#include "sim/context.h"
#include "sim/parameter_bindings.h"

namespace tcpmsim {

// A component whose parameters are a struct P, bound to its declared parameters: each run gets
// P as its context sets it (run_parameters), built when the run starts. Components with
// discrete state as well derive from Component and keep P in their own run state.
template <typename P>
class ParametricComponent : public Component {
 public:
  ParametricComponent(std::string group, std::string kind, P defaults,
                      ParameterBindings<P> bindings)
      : Component(std::move(group), std::move(kind)),
        defaults_(std::move(defaults)),
        bindings_(std::move(bindings)) {}

  std::vector<ParameterDeclaration> parameters() const override {
    return bindings_.declarations(defaults_);
  }
  std::unique_ptr<RunState> create_run_state(const RunSetup& setup) const override {
    return std::make_unique<Run>(bindings_.assign(defaults_, setup.parameters));
  }
  // The parameters as built (a run context may change the bound ones).
  const P& defaults() const { return defaults_; }
  // P as `context` sets it, before a run starts (for a rule that derives a parameter of another
  // component from these).
  P parameters_in(const Context& context) const {
    const auto declared = bindings_.declarations(defaults_);
    std::vector<double> values;
    values.reserve(declared.size());
    for (const auto& parameter : declared) values.push_back(context.parameter(parameter.path));
    return bindings_.assign(defaults_, values);
  }

 protected:
  const P& run_parameters(const Evaluation& evaluation) const {
    return run_state<Run>(evaluation).parameters;
  }

 private:
  struct Run final : RunState {
    explicit Run(P values) : parameters(std::move(values)) {}
    P parameters;
  };
  P defaults_;
  ParameterBindings<P> bindings_;
};

}  // namespace tcpmsim
