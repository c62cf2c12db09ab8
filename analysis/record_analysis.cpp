#include "analysis/record_analysis.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "sim/value_check.h"

namespace tcpmsim {
namespace {

// The samples of a 1-D channel, or a message naming what is wrong.
std::span<const double> series_of(const RecordChannels& record, const std::string& name,
                                  const char* role) {
  const auto& channel = record.channel(name);
  if (channel.columns != 1)
    throw std::invalid_argument(std::string(role) + " '" + name + "' has " +
                                std::to_string(channel.columns) +
                                " columns (a member set); analyse one muscle's channel");
  return channel.values;
}

struct Window {
  std::size_t begin = 0, end = 0;
  std::span<const double> of(std::span<const double> values) const {
    return values.subspan(begin, end - begin);
  }
};

// The window as it was asked for, by the command line's options: "--from 10 s --to 20 s", or
// "the whole record".
std::string window_options(double from, double to) {
  std::string text;
  if (std::isfinite(from)) text += "--from " + number_text(from) + " s";
  if (std::isfinite(to)) text += (text.empty() ? "--to " : " --to ") + number_text(to) + " s";
  return text.empty() ? "the whole record" : text;
}

// The samples in [from, to]; `asked` names the window in the message when it holds too few.
Window window_of(const std::vector<double>& time, double from, double to, const std::string& source,
                 const std::string& asked) {
  Window window;
  window.begin =
      static_cast<std::size_t>(std::lower_bound(time.begin(), time.end(), from) - time.begin());
  window.end =
      static_cast<std::size_t>(std::upper_bound(time.begin(), time.end(), to) - time.begin());
  if (window.end < window.begin + 2)
    throw std::invalid_argument(source + ": fewer than two samples in the window (" + asked + ")");
  return window;
}

bool varies(std::span<const double> values) {
  const auto [low, high] = std::minmax_element(values.begin(), values.end());
  return *high > *low;
}

// The multisine stretch of `input` that overlaps [from, to) most, or none.
const MultisineStretch* stretch_over(const RecordChannels& record, const std::string& input,
                                     double from, double to) {
  const MultisineStretch* best = nullptr;
  double overlap = 0.0;
  for (const auto& stretch : record.inputs.at(input)) {
    const double shared = std::min(to, stretch.end) - std::max(from, stretch.begin);
    if (shared > overlap) overlap = shared, best = &stretch;
  }
  return best;
}

std::string list_text(const std::vector<std::string>& names) {
  std::string text;
  for (const auto& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

void analyse_steps(const RecordChannels& record, const AnalysisRequest& request,
                   const Window& window, RecordAnalysis& analysis) {
  const auto reference = series_of(record, request.reference, "the reference");
  const auto output = series_of(record, request.output, "the output");
  analysis.reference = request.reference;
  analysis.reference_unit = record.channel(request.reference).unit;
  analysis.step_options = request.steps;
  analysis.steps = step_metrics(window.of(record.time), window.of(reference), window.of(output),
                                analysis.reference_unit == analysis.output_unit, request.steps);
  if (analysis.steps.empty())
    analysis.notes.push_back("the reference '" + request.reference +
                             "' does not step in the window: no step metrics");
}

// The inputs to estimate: those asked, or every prescribed input the window excites.
std::vector<std::string> estimated_inputs(const RecordChannels& record,
                                          const AnalysisRequest& request, const Window& window) {
  if (!request.inputs.empty()) {
    for (const auto& input : request.inputs)
      if (!varies(window.of(series_of(record, input, "the input"))))
        throw std::invalid_argument("the input '" + input + "' is constant in the window (" +
                                    window_options(request.from, request.to) +
                                    "): it excites nothing");
    return request.inputs;
  }
  std::vector<std::string> excited;
  for (const auto& [input, _] : record.inputs)
    if (input != request.output && varies(window.of(record.channel(input).values)))
      excited.push_back(input);
  if (excited.empty())
    throw std::invalid_argument(record.source + ": no prescribed input varies in the window (" +
                                window_options(request.from, request.to) +
                                "); name the input with --input");
  return excited;
}

// The smallest spacing between two distinct lines of the inputs (lines that coincide are
// shared, and reported as such); infinite with fewer than two.
double closest_lines(const std::vector<ExcitedInput>& excited) {
  std::vector<double> all;
  for (const auto& input : excited) all.insert(all.end(), input.lines.begin(), input.lines.end());
  std::sort(all.begin(), all.end());
  double closest = std::numeric_limits<double>::infinity();
  for (std::size_t k = 1; k < all.size(); ++k) {
    const double gap = all[k] - all[k - 1];
    if (gap > 1e-9 * all[k]) closest = std::min(closest, gap);
  }
  return closest;
}

void analyse_response(const RecordChannels& record, const AnalysisRequest& request, Window window,
                      RecordAnalysis& analysis) {
  const std::vector<std::string> inputs = estimated_inputs(record, request, window);
  const auto& time = record.time;
  // Multisine lines when every input is a multisine over (most of) the window: the window
  // shrinks to their common stretch.
  double from = time[window.begin], to = time[window.end - 1];
  double multisine_start = -std::numeric_limits<double>::infinity();
  bool lines = request.method != "spectral";
  for (const auto& input : inputs) {
    const MultisineStretch* stretch =
        record.inputs.count(input) ? stretch_over(record, input, from, to) : nullptr;
    if (stretch == nullptr) {
      if (request.method == "lines")
        throw std::invalid_argument("the input '" + input +
                                    "' is no multisine in the window: use --method spectral");
      lines = false;
      break;
    }
    from = std::max(from, stretch->begin);
    to = std::min(to, stretch->end);
    multisine_start = std::max(multisine_start, stretch->begin);
  }
  if (lines)
    window = window_of(
        time, from, std::nextafter(to, -1.0), record.source,
        "the multisine's stretch " + number_text(from) + " s to " + number_text(to) + " s");
  analysis.from = time[window.begin];
  analysis.to = time[window.end - 1];
  analysis.method = lines ? "lines" : "spectral";

  // Every other prescribed input that varies here takes part: its lines in the fit, or as an
  // input of the multi-input spectral estimate.
  std::vector<ExcitedInput> excited;
  std::vector<std::string> noise;
  const auto add = [&](const std::string& name) {
    ExcitedInput input{name, window.of(series_of(record, name, "the input")), {}};
    if (lines) {
      const MultisineStretch* stretch = record.inputs.count(name)
                                            ? stretch_over(record, name, analysis.from, analysis.to)
                                            : nullptr;
      if (stretch == nullptr) return false;
      input.lines = stretch->frequencies;
    }
    excited.push_back(input);
    return true;
  };
  const auto collect = [&] {
    excited.clear();
    noise.clear();
    for (const auto& input : inputs) add(input);
    for (const auto& [other, _] : record.inputs) {
      if (std::find(inputs.begin(), inputs.end(), other) != inputs.end() || other == request.output)
        continue;
      if (!varies(window.of(record.channel(other).values))) continue;
      if (!add(other)) noise.push_back(other);
    }
  };
  collect();
  // Lines closer than 1/T cannot be told apart in a window of T seconds (shorter than the
  // multisine's period): their least-squares fit is ill-posed and its numbers meaningless.
  if (lines) {
    const double duration = analysis.to - analysis.from;
    if (const double spacing = closest_lines(excited); spacing * duration < 1.0) {
      const std::string why = "the window of " + number_text(duration, 4) +
                              " s cannot tell the multisine's lines apart: they lie " +
                              number_text(spacing * 1e3, 4) + " mHz apart, which needs " +
                              number_text(1.0 / spacing, 4) + " s or more (a whole period)";
      if (request.method == "lines")
        throw std::invalid_argument(why + "; analyse a longer window, or --method spectral");
      analysis.notes.push_back(why + "; estimated by the spectral method instead");
      lines = false;
      analysis.method = "spectral";
      collect();
    }
  }
  // A window that opens with the multisine holds the response's start-up, which is no sum of
  // the lines: on the protocol of 7.3.5 it moved them by 3-7 % and 4-6 degrees.
  if (lines && analysis.from <= multisine_start + 0.5 * (time[1] - time[0]))
    analysis.notes.push_back(
        "the window opens where the multisine starts (" + number_text(multisine_start, 6) +
        " s): the response's transient there biases the lines; --from a few of the system's "
        "time constants later leaves it out");
  if (!noise.empty())
    analysis.notes.push_back(list_text(noise) +
                             " also varies in the window, not at lines: its effect on the output "
                             "counts as noise and widens the confidence band");
  if (excited.size() > inputs.size()) {
    std::vector<std::string> others;
    for (std::size_t k = inputs.size(); k < excited.size(); ++k) others.push_back(excited[k].name);
    analysis.notes.push_back(
        lines ? "the lines of " + list_text(others) + ", excited at the same time, are fitted too"
              : "multi-input estimate: " + list_text(inputs) + " told apart from " +
                    list_text(others) + ", excited at the same time");
  }
  const auto output = window.of(series_of(record, request.output, "the output"));
  const auto window_time = window.of(time);
  std::vector<std::vector<ResponseEstimate>> estimates;
  if (lines) {
    estimates = line_response(window_time, excited, output);
  } else {
    const double interval = (analysis.to - analysis.from) / double(window.end - window.begin - 1);
    const double segment =
        request.segment > 0.0 ? request.segment : (analysis.to - analysis.from) / 4.0;
    auto samples = static_cast<std::size_t>(std::lround(segment / interval));
    samples -= samples % 2;
    analysis.segment = double(samples) * interval;
    estimates = spectral_response(window_time, excited, output, samples);
  }
  for (std::size_t j = 0; j < inputs.size(); ++j) {
    InputResponse response;
    response.input = inputs[j];
    const std::string& input_unit = record.channel(inputs[j]).unit;
    response.unit = analysis.output_unit + "/" + input_unit;
    response.estimates = std::move(estimates[j]);
    response.reference_magnitude = 1.0;
    response.relative = input_unit != analysis.output_unit;
    if (response.relative) {
      for (const auto& estimate : response.estimates)
        if (std::isfinite(estimate.magnitude)) {
          response.reference_magnitude = estimate.magnitude;
          break;
        }
    }
    if (std::none_of(response.estimates.begin(), response.estimates.end(),
                     [](const ResponseEstimate& e) { return std::isfinite(e.magnitude); }))
      analysis.notes.push_back(inputs[j] +
                               ": no frequency where the estimate stands out of its confidence "
                               "band (inputs that move together, or no response)");
    response.bandwidth = estimate_bandwidth_3db(response.estimates, response.reference_magnitude);
    std::vector<std::string> overlapping;
    for (const auto& estimate : response.estimates)
      if (!estimate.overlap.empty())
        overlapping.push_back(number_text(estimate.frequency * 1e3, 4) + " mHz (" +
                              estimate.overlap + ")");
    if (!overlapping.empty())
      analysis.notes.push_back(inputs[j] +
                               ": lines shared with other inputs, not estimable "
                               "from this record: " +
                               list_text(overlapping));
    analysis.responses.push_back(std::move(response));
  }
}

std::string value_text(double value, int digits = 4) {
  return std::isfinite(value) ? number_text(value, digits) : "-";
}

// How a channel's values are printed: temperatures (K in records, SI) in degC as the plots
// show them; differences of them (the steady-state error) stay in K, which is the same size.
struct ShownUnit {
  std::string unit;
  double offset = 0.0;  // added to a value
};

ShownUnit shown_unit(const std::string& unit) {
  if (unit == "K") return {"degC", -273.15};
  return {unit, 0.0};
}

void report_steps(const RecordAnalysis& analysis, std::ostringstream& text) {
  const ShownUnit output = shown_unit(analysis.output_unit);
  const ShownUnit reference = shown_unit(analysis.reference_unit);
  const bool temperatures = output.offset != 0.0 || reference.offset != 0.0;
  text << "step response of " << analysis.output << " [" << output.unit << "] against "
       << analysis.reference << " [" << reference.unit << "]: " << analysis.steps.size()
       << " steps; rise " << analysis.step_options.rise.lower * 100 << "-"
       << analysis.step_options.rise.upper * 100 << " % of the step, settling into +-"
       << analysis.step_options.settling_band * 100 << " % of the step around the final value"
       << (temperatures ? "; temperatures in degC, their differences in K" : "") << "\n";
  text << "  step at [s]   reference   final value   rise [s]   settling [s]   overshoot [%]"
          "   steady-state error   time constant [s]\n";
  for (const auto& step : analysis.steps) {
    text << "  " << value_text(step.step_time, 6) << "   "
         << value_text(step.reference + reference.offset) << "   "
         << value_text(step.final_value + output.offset) << "   " << value_text(step.rise_time)
         << "   " << value_text(step.settling_time) << "   "
         << value_text(step.overshoot * 100.0, 3) << "   " << value_text(step.steady_state_error)
         << "   " << value_text(step.time_constant) << (step.settled ? "" : " (not settled)")
         << "\n";
  }
  for (const auto& step : analysis.steps) {
    if (step.settled) continue;
    text << "warning: the step at " << value_text(step.step_time, 6) << " s is held "
         << value_text(step.hold) << " s, "
         << (std::isfinite(step.time_constant)
                 ? value_text(step.hold / step.time_constant, 2) + " time constants of " +
                       value_text(step.time_constant) + " s"
                 : std::string("and never reaches 63 % of its final value"))
         << ": it has not settled (" << kSettledTimeConstants
         << " are needed), so its final value, rise and settling are biased; analyse a longer "
            "hold\n";
  }
}

void report_response(const InputResponse& response, const RecordAnalysis& analysis,
                     std::ostringstream& text) {
  text << "frequency response " << response.input << " -> " << analysis.output << " ["
       << response.unit << "], "
       << (analysis.method == "lines"
               ? "at the multisine's lines"
               : "H1 spectral estimate, segments of " + number_text(analysis.segment, 4) + " s")
       << ", " << number_text(analysis.from, 6) << "-" << number_text(analysis.to, 6) << " s\n";
  text << "  f [Hz]   |H|   |H| [dB]   phase [deg]   95 % radius   coherence\n";
  // At most about kRows rows, spaced evenly in log f; the file holds every frequency.
  constexpr std::size_t kRows = 30;
  const auto& all = response.estimates;
  std::vector<const ResponseEstimate*> shown;
  for (std::size_t k = 0; k < all.size(); ++k) {
    const bool spaced =
        all.size() <= kRows || k == 0 || k + 1 == all.size() ||
        std::floor(kRows * std::log(all[k].frequency / all.front().frequency) /
                   std::log(all.back().frequency / all.front().frequency)) >
            std::floor(kRows * std::log(all[k - 1].frequency / all.front().frequency) /
                       std::log(all.back().frequency / all.front().frequency));
    if (spaced) shown.push_back(&all[k]);
  }
  for (const auto* row : shown) {
    const auto& estimate = *row;
    text << "  " << value_text(estimate.frequency) << "   " << value_text(estimate.magnitude)
         << "   " << value_text(estimate.magnitude_db) << "   "
         << value_text(estimate.phase * 180.0 / 3.141592653589793) << "   "
         << value_text(estimate.radius_95, 3) << "   " << value_text(estimate.coherence, 3)
         << (estimate.overlap.empty() ? "" : "   shared with " + estimate.overlap) << "\n";
  }
  if (shown.size() < all.size())
    text << "  (" << shown.size() << " of " << all.size()
         << " frequencies, spaced in log f; the file holds them all)\n";
  text << "  -3 dB ("
       << (!response.relative ? std::string("against |H| = 1")
                              : "against |H| = " + number_text(response.reference_magnitude, 4) +
                                    " at the lowest frequency, which must lie in the pass band")
       << "): "
       << (response.bandwidth ? number_text(*response.bandwidth, 4) + " Hz" : "none in range")
       << "\n";
}

}  // namespace

std::string analysis_report(const RecordAnalysis& analysis) {
  std::ostringstream text;
  text << analysis.source << ": " << analysis.output << " over " << number_text(analysis.from, 6)
       << "-" << number_text(analysis.to, 6) << " s\n";
  if (!analysis.reference.empty()) report_steps(analysis, text);
  for (const auto& response : analysis.responses) report_response(response, analysis, text);
  for (const auto& note : analysis.notes) text << "note: " << note << "\n";
  return text.str();
}

RecordAnalysis analyze_record(const RecordChannels& record, const AnalysisRequest& request) {
  if (request.method != "auto" && request.method != "lines" && request.method != "spectral")
    throw std::invalid_argument("the method is auto, lines or spectral, not '" + request.method +
                                "'");
  RecordAnalysis analysis;
  analysis.source = record.source;
  analysis.output = request.output;
  series_of(record, request.output, "the output");
  analysis.output_unit = record.channel(request.output).unit;
  const Window window = window_of(record.time, request.from, request.to, record.source,
                                  window_options(request.from, request.to));
  analysis.from = record.time[window.begin];
  analysis.to = record.time[window.end - 1];
  if (!request.reference.empty()) analyse_steps(record, request, window, analysis);
  if (!request.inputs.empty() || request.reference.empty())
    analyse_response(record, request, window, analysis);
  return analysis;
}

}  // namespace tcpmsim
