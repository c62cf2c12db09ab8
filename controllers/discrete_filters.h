#pragma once

#include <cstddef>
#include <vector>

namespace tcpmsim {

// Sample-by-sample filters for the self-sensing estimator (thesis 7.2.3, 7.3.1). Each keeps a
// fixed-size buffer allocated at construction, so pushing a sample never allocates.
//
// Start-up. The window filters work on the samples received so far until their window is
// full (a growing window, MATLAB's "shrink" end rule on a causal window). Nothing is invented
// before the first sample: no zero padding, which would pull an inductance measure towards 0
// and (7.4) towards a nonsensical deflection, and no repetition of the first sample, which
// would let a spike in the very first sample survive a whole half window.

// Mean of the last `length` samples.
class MovingAverage {
 public:
  explicit MovingAverage(int length);
  // Adds a sample and returns the mean of the window.
  double push(double value);
  void reset();
  int length() const { return static_cast<int>(window_.size()); }
  int count() const { return count_; }

 private:
  std::vector<double> window_;  // ring buffer
  int next_ = 0;                // where the next sample goes
  int count_ = 0;               // samples held, <= length
};

// Median of the last `length` samples. An even count (only while the window fills, or with an
// even length) gives the mean of the two middle values. A single outlier is rejected as soon as
// three samples exist; a full window of length N rejects bursts of up to (N - 1) / 2 samples.
class RunningMedian {
 public:
  explicit RunningMedian(int length);
  double push(double value);  // value must not be NaN (it has no place in an ordering)
  void reset();
  int length() const { return static_cast<int>(window_.size()); }
  int count() const { return count_; }

 private:
  std::vector<double> window_;  // ring buffer, arrival order
  std::vector<double> sorted_;  // the same samples in ascending order; first count_ valid
  int next_ = 0;
  int count_ = 0;
};

// First-order low-pass H(s) = 1 / (1 + s / (2 pi f_c)), discretised exactly (step invariance)
// for a sample period T:
//     y[k] = a y[k-1] + (1 - a) u[k],   a = exp(-2 pi f_c T).
// This is the continuous filter's exact response when u[k] is the input held over the interval
// (t_{k-1}, t_k] that ends at the sample: the Muscle Drive's L* at t_k is measured during the
// PWM period that just ended, so the newest sample is used without an extra period of delay.
// (Holding u[k] over [t_k, t_{k+1}) instead gives the same recursion one sample later; the
// magnitude responses are identical.) The discrete gain at f_c is
//     |H| = (1 - a) / sqrt(1 - 2 a cos(2 pi f_c T) + a^2) = (1 + (2 pi f_c T)^2 / 24 + ...) / sqrt
//     2,
// i.e. -3.0099 dB instead of -3.0103 dB at 0.111 Hz and 20 Hz. A cut-off of +infinity
// gives a = 0, a pass-through. The first sample initialises the output (y[0] = u[0]): the
// filter starts in steady state instead of rising from zero.
class FirstOrderLowPass {
 public:
  FirstOrderLowPass(double cutoff_frequency, double period);
  double push(double value);
  void reset() { started_ = false; }
  double pole() const { return pole_; }  // a
  // The discrete filter's gain at `frequency` [Hz] (closed form above).
  double gain(double frequency) const;

 private:
  double pole_;
  double period_;
  double output_ = 0.0;
  bool started_ = false;
};

}  // namespace tcpmsim
