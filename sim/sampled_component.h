#pragma once

#include "sim/component.h"

namespace tcpmsim {

// A sampled-data component: it acts at t = k * period (from the start of the run), reading its
// inputs as they were just before the instant, and holds its outputs in between. The integrator
// stops at every sample instant. The period is the component's first parameter,
// "<group>.sample_period" (a controller's usually follows its drive's PWM frequency); a derived
// class appends its own parameters after it.
class SampledComponent : public Component {
 public:
  SampledComponent(std::string group, std::string kind, double period, SamplingStage stage);

  std::vector<ParameterDeclaration> parameters() const override;
  double next_breakpoint_after(const Evaluation& evaluation) const override;
  void at_breakpoint(const Evaluation& evaluation) const final;
  SamplingStage sampling_stage() const override { return stage_; }
  bool acts_discretely() const final { return true; }
  double period() const { return period_; }  // as built

 protected:
  // Called at each sample instant with its index k; updates the held outputs and the discrete
  // state (in the run state). Publishing the held outputs is compute_outputs' job.
  virtual void sample(const Evaluation& evaluation, long index) const = 0;
  double period(const Evaluation& evaluation) const { return parameter(evaluation, 0); }
  // The period followed by a derived class's own parameters: what its parameters() returns.
  std::vector<ParameterDeclaration> with_period(std::vector<ParameterDeclaration> own) const;
  // A run's own parameters after the period.
  static std::span<const double> own_parameters(const RunSetup& setup) {
    return setup.parameters.subspan(1);
  }

 private:
  double period_;
  SamplingStage stage_;
};

}  // namespace tcpmsim
