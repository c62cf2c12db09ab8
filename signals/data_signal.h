#pragma once

#include <memory>
#include <string_view>
#include <vector>

#include "sim/config/config_node.h"
#include "sim/signal.h"
#include "sim/signal_reading.h"

namespace tcpmsim {

// How a replayed channel runs between its samples.
enum class DataInterpolation { hold, linear };

// A measured channel replayed as a signal: the samples are its breakpoints, held (zero-order
// hold) or joined by straight lines (a sample where nothing jumps is none). Sample time `origin` of
// the data is the scenario's t = 0. Beyond the last sample the last value holds; before the first,
// the first.
class DataSignal final : public Signal {
 public:
  struct Samples {
    std::vector<double> times;   // the data's own, strictly increasing [s]
    std::vector<double> values;  // SI
  };
  DataSignal(std::shared_ptr<const Samples> samples, DataInterpolation interpolation,
             double origin);

  double value(double time) const override;
  double slope(double time) const override;
  double next_breakpoint_after(double time) const override;
  SignalDescription describe() const override;
  std::pair<double, double> range(double begin, double end) const override;

  // The scenario time the samples cover: to one sample interval past the last sample.
  double covered_until() const;

 private:
  // The index of the last sample at or before scenario time `time`, or -1: the sample a uniform
  // rate puts there, corrected by a few steps; a binary search where that does not find it.
  long sample_at(double time) const;

  std::shared_ptr<const Samples> samples_;
  std::vector<double> times_;  // the samples' times on the scenario's clock (data time - origin)
  // The samples where the value (hold) or the slope (linear) jumps: a sample that continues
  // the line or level before it is no breakpoint, so a long constant stretch costs no restarts.
  std::vector<double> breakpoints_;
  double samples_per_second_ = 0.0;  // (n - 1) / (last time - first time): the mean rate
  DataInterpolation interpolation_;
  double origin_;
};

// {type: data, file: run.csv, channel: power, interpolation: hold|linear, origin: 0 s}: a column
// of a measurement file (CSV with name[unit] headings, or a tcpmsim record) in `si_unit`. The
// file is found relative to the scenario file; the data must cover the scenario's duration.
std::unique_ptr<Signal> read_data_signal(const ConfigNode& node, std::string_view si_unit,
                                         const SignalContext& context);

}  // namespace tcpmsim
