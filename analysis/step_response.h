#pragma once

#include <cstddef>
#include <span>
#include <vector>

// Step responses of any channel against any reference: the rise times of the thesis' control
// tasks (7.3.6) and the metrics of a step-response study (rise, settling, overshoot,
// steady-state error). Used by the control tasks, the sweeps' metrics and `tcpmsim analyze`.
namespace tcpmsim {

// ---- Rise times of a step sequence --------------------------------------------------------

// Rise time of one step: from the instant the response first reaches y0 + lower (r - y0) to the
// instant it first reaches y0 + upper (r - y0), where y0 is the response at the step and r the
// new reference; crossings are interpolated linearly between samples. The default 10 %-90 %
// gives tau ln 9 for a first-order response. lower = 0 measures from the step itself, and
// {0, 1} is "time until the response reaches the reference".
//
// A step whose response does not reach the upper level before the next step (or the end of the
// data) is reported with rise_time equal to its hold, the time it was given, and reached =
// false. That is how the thesis' outliers "at 20 s" arise: a response that never got there is
// charged the whole 20 s hold, independent of where its lower crossing was.
struct RiseTimeDefinition {
  double lower = 0.1;  // fractions of the step, 0 <= lower < upper <= 1
  double upper = 0.9;
};

struct StepRise {
  std::size_t index = 0;    // the first sample carrying the new reference
  double step_time = 0.0;   // t at that sample [s]
  double hold = 0.0;        // until the next step; the last until one sample past the end
  double start = 0.0;       // y0, the response at the step
  double target = 0.0;      // the new reference
  double lower_time = 0.0;  // when the lower level was reached [s]; NaN if never
  double upper_time = 0.0;  // when the upper level was reached [s]; NaN if never
  double rise_time = 0.0;   // upper_time - lower_time, or `hold` if not reached [s]
  bool reached = false;
};

// A step is any change of the reference between consecutive samples by more than `threshold`
// (give the step task's stretch of the record, not the sweep). The step instant is the first
// sample with the new value: put samples on the step instants (the control-task steps fall on
// the controller's 20 Hz grid) or accept up to one sample interval of timing error.
std::vector<StepRise> step_rise_times(std::span<const double> time,
                                      std::span<const double> reference,
                                      std::span<const double> response,
                                      const RiseTimeDefinition& definition = {},
                                      double threshold = 0.0);

// ---- Step-response metrics ----------------------------------------------------------------

// Each step of the reference (a change between consecutive samples by more than `threshold`)
// starts a segment that lasts until the next step (or the end). Within it, y0 is the response
// at the step and the final value y_f the mean response over the last `final_fraction` of the
// segment (at least one sample), so that the metrics hold for a response in other units than
// its reference (power in, force out) and for one that never reaches the reference.
// A step's hold counts as settled when it lasts this many time constants (e^-5: 0.7 %).
inline constexpr double kSettledTimeConstants = 5.0;

struct StepMetricsOptions {
  RiseTimeDefinition rise;      // of the step y_f - y0: 10 %-90 % by default
  double settling_band = 0.02;  // settled within +-2 % of |y_f - y0| around y_f
  double final_fraction = 0.1;  // of the segment, averaged for y_f
  double threshold = 0.0;       // of the reference's change, for a step
};

struct StepMetrics {
  std::size_t index = 0;            // the first sample carrying the new reference
  double step_time = 0.0;           // [s]
  double hold = 0.0;                // until the next step (the last: one sample past the end) [s]
  double reference = 0.0;           // the new reference
  double start = 0.0;               // y0
  double final_value = 0.0;         // y_f
  double rise_time = 0.0;           // between the lower and upper crossings of y0 + f (y_f - y0),
                                    // interpolated linearly; NaN if either is not reached
  double settling_time = 0.0;       // from the step until the response stays within the band
                                    // around y_f; NaN if it is outside at the segment's end
  double time_constant = 0.0;       // from the step until y0 + (1 - 1/e)(y_f - y0) is reached,
                                    // interpolated: tau of a first-order response; NaN if never
  bool settled = true;              // the hold lasts kSettledTimeConstants time constants, so
                                    // y_f is within e^-5 = 0.7 % of the end; if not, y_f, the
                                    // rise and the settling are biased (a longer hold is needed)
  double overshoot = 0.0;           // beyond y_f, as a fraction of |y_f - y0| (0: none)
  double steady_state_error = 0.0;  // reference - y_f, when both share units; else NaN
};

// Throws std::invalid_argument for series of unequal length, non-finite values, time not
// increasing, or a reference that changes at more than a quarter of its samples (not a step
// reference: raise the threshold, or analyse its frequency response).
std::vector<StepMetrics> step_metrics(std::span<const double> time,
                                      std::span<const double> reference,
                                      std::span<const double> response, bool same_units,
                                      const StepMetricsOptions& options = {});

// The largest excursion of `values` beyond `final_value`, away from `start`, as a fraction of
// |final_value - start|; 0 when there is none, NaN when the response does not move.
double overshoot_fraction(std::span<const double> values, double start, double final_value);

}  // namespace tcpmsim
