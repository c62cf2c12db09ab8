#pragma once

#include <limits>
#include <string>
#include <vector>

#include "sim/config/config_node.h"
#include "sim/context.h"
#include "sim/memory_record.h"
#include "sim/scenario.h"

namespace tcpmsim::sweep {

// A number computed from one run's record: what a sweep tabulates per run. Every kind reuses
// the analysis of the control tasks (analysis/control_tasks.h, analysis/statistics.h).
enum class MetricKind {
  final_value,  // the channel's last value in the window
  maximum,      // its largest value (peak force, peak temperature)
  minimum,
  mean,
  integral,       // its time integral (energy used, from a power channel)
  rise_time,      // 10-90 % (lower/upper) of a step: tracking `reference`, or open loop at `from`
  overshoot,      // beyond the final value, as a fraction of the step
  time_constant,  // of an exponential approach over the window
  bandwidth,      // -3 dB of `channel` against a stepped sine sweep `reference` (7.3.6)
  rmse,           // root mean square of `estimate` - `channel`
};

struct MetricSpec {
  std::string name;
  MetricKind kind = MetricKind::final_value;
  std::string scenario;   // which of the sweep's scenarios it reads
  std::string channel;    // "group/name": the response, the truth
  std::string reference;  // rise_time (optional), bandwidth
  std::string estimate;   // rmse
  double from = 0.0;      // the window [s]
  double to = std::numeric_limits<double>::infinity();
  bool held = false;   // integral: each sample's value holds until the next (sampled drives,
                       // steps on the output grid); else the trapezoidal rule
  double lower = 0.1;  // rise_time: fractions of the step
  double upper = 0.9;
  std::string unit;  // of the value
};

// The value, or NaN with the reason in `note` (a step never reached, no -3 dB crossing).
struct MetricValue {
  double value = std::numeric_limits<double>::quiet_NaN();
  std::string note;
};

// The kinds' names as a sweep file writes them.
const std::vector<std::string>& metric_kind_names();

// Reads one entry of a sweep's `metrics:` list, checking its channels against `scenario`'s
// recorded outputs and its window against the duration (ConfigError at the offending key).
MetricSpec read_metric(const ConfigNode& node, const std::string& scenario_name,
                       const Scenario& scenario);

MetricValue evaluate_metric(const MetricSpec& metric, const MemoryRecord& record,
                            const Context& context);

}  // namespace tcpmsim::sweep
