#pragma once

#include "sim/component.h"

namespace tcpmsim {

// A sampled-data component: it acts at t = k * period (from the start of the run), reading its
// inputs as they were just before the instant, and holds its outputs in between. The integrator
// stops at every sample instant.
class SampledComponent : public Component {
 public:
  SampledComponent(std::string group, std::string kind, double period, SamplingStage stage);

  double next_breakpoint_after(double t) const override;
  void at_breakpoint(const Evaluation& evaluation) final;
  SamplingStage sampling_stage() const override { return stage_; }
  double period() const { return period_; }

 protected:
  // Called at each sample instant with its index k; updates the held outputs and the discrete
  // state. Publishing the held outputs is compute_outputs' job.
  virtual void sample(const Evaluation& evaluation, long index) = 0;

 private:
  double period_;
  SamplingStage stage_;
};

}  // namespace tcpmsim
