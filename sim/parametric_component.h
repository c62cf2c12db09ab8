#pragma once

#include <memory>
#include <utility>

#include "sim/component.h"
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
