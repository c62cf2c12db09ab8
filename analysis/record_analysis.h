#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "analysis/frequency_response.h"
#include "analysis/record_channels.h"
#include "analysis/step_response.h"

namespace tcpmsim {

// What `tcpmsim analyze` (and tcpmsim.analyze in Python) is asked: step metrics of `output`
// against `reference`, and/or the frequency response of `output` from `inputs`.
struct AnalysisRequest {
  std::string output;               // "muscle/force"
  std::string reference;            // step metrics against this channel; empty: none
  std::vector<std::string> inputs;  // frequency response; empty (and no reference): every
                                    // prescribed input the window excites
  double from = -std::numeric_limits<double>::infinity();  // the window [s]
  double to = std::numeric_limits<double>::infinity();
  std::string method = "auto";  // auto, lines, spectral
  double segment = 0.0;         // spectral: the segment length [s]; 0: a quarter of the window
  StepMetricsOptions steps;
};

// The frequency response of the output from one input.
struct InputResponse {
  std::string input;  // "drive/power"
  std::string unit;   // of H: output unit / input unit
  std::vector<ResponseEstimate> estimates;
  // The -3 dB point: against |H| = 1 when the input and the output share a unit (a loop that
  // tracks its input), else against the lowest frequency's |H| (a plant).
  std::optional<double> bandwidth;
  double reference_magnitude = 1.0;
  bool relative = false;  // reference_magnitude is the lowest frequency's |H|
};

struct RecordAnalysis {
  std::string source;
  std::string output, output_unit;
  double from = 0.0, to = 0.0;  // the window analysed [s]
  // Step metrics.
  std::string reference, reference_unit;
  StepMetricsOptions step_options;
  std::vector<StepMetrics> steps;
  // Frequency response.
  std::string method;  // "lines" (multisine) or "spectral" (H1)
  double segment = 0.0;
  std::vector<InputResponse> responses;
  std::vector<std::string> notes;  // what the reader must know (overlapping lines, inputs that
                                   // vary in the window but are not estimated)
};

// Throws std::invalid_argument with the reason for a request the record cannot serve (an
// unknown channel, a window without samples, an input that does not vary, lines asked of a
// non-multisine input).
RecordAnalysis analyze_record(const RecordChannels& record, const AnalysisRequest& request);

// The analysis as text for the terminal.
std::string analysis_report(const RecordAnalysis& analysis);

}  // namespace tcpmsim
