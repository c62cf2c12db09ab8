#include "analysis/analyze_command.h"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "sim/config/config_error.h"

namespace tcpmsim {
namespace {

// One value of each item: a dataset's column.
template <typename Item, typename Value>
std::vector<double> each(const std::vector<Item>& items, Value value) {
  std::vector<double> values;
  for (const auto& item : items) values.push_back(value(item));
  return values;
}

void write_steps(Hdf5Writer& file, const RecordAnalysis& analysis) {
  const auto& steps = analysis.steps;
  const std::string& y = analysis.output_unit;
  file.write("steps/step_time", each(steps, [](auto& s) { return s.step_time; }), "s");
  file.write("steps/hold", each(steps, [](auto& s) { return s.hold; }), "s");
  file.write("steps/reference", each(steps, [](auto& s) { return s.reference; }),
             analysis.reference_unit);
  file.write("steps/start", each(steps, [](auto& s) { return s.start; }), y);
  file.write("steps/final_value", each(steps, [](auto& s) { return s.final_value; }), y);
  file.write("steps/rise_time", each(steps, [](auto& s) { return s.rise_time; }), "s");
  file.write("steps/settling_time", each(steps, [](auto& s) { return s.settling_time; }), "s");
  file.write("steps/time_constant", each(steps, [](auto& s) { return s.time_constant; }), "s");
  file.write("steps/settled", each(steps, [](auto& s) { return s.settled ? 1.0 : 0.0; }), "1");
  file.write("steps/overshoot", each(steps, [](auto& s) { return s.overshoot; }), "1");
  file.write("steps/steady_state_error", each(steps, [](auto& s) { return s.steady_state_error; }),
             y);
  file.attribute("steps", "reference", analysis.reference);
  const auto& options = analysis.step_options;
  file.attribute("steps", "definition",
                 "rise " + std::to_string(options.rise.lower) + "-" +
                     std::to_string(options.rise.upper) + " of final - start; settled within " +
                     std::to_string(options.settling_band) +
                     " of |final - start|; final value: "
                     "the mean over the last " +
                     std::to_string(options.final_fraction) + " of each step's hold");
}

void write_response(Hdf5Writer& file, const InputResponse& response) {
  std::string name = response.input;
  for (char& c : name)
    if (c == '/') c = '.';
  const std::string path = "frequency_response/" + name, group = path + "/";
  const auto& e = response.estimates;
  file.write(group + "frequency", each(e, [](auto& x) { return x.frequency; }), "Hz");
  file.write(group + "magnitude", each(e, [](auto& x) { return x.magnitude_db; }), "dB");
  file.write(group + "magnitude_ratio", each(e, [](auto& x) { return x.magnitude; }),
             response.unit);
  file.write(group + "phase", each(e, [](auto& x) { return x.phase; }), "rad");
  file.write(group + "real", each(e, [](auto& x) { return x.response.real(); }), response.unit);
  file.write(group + "imag", each(e, [](auto& x) { return x.response.imag(); }), response.unit);
  file.write(group + "radius_95", each(e, [](auto& x) { return x.radius_95; }), response.unit);
  file.write(group + "coherence", each(e, [](auto& x) { return x.coherence; }), "1");
  file.write_scalar(group + "reference_magnitude", response.reference_magnitude, response.unit);
  if (response.bandwidth) file.write_scalar(group + "bandwidth", *response.bandwidth, "Hz");
  file.attribute(path, "input", response.input);
  file.attribute(path, "bandwidth_against",
                 response.relative ? "the lowest frequency's |H|" : "|H| = 1");
}

}  // namespace

void write_record_analysis(Hdf5Writer& file, const RecordAnalysis& analysis) {
  file.attribute("/", "record", analysis.source);
  file.attribute("/", "output", analysis.output);
  file.write_scalar("window/from", analysis.from, "s");
  file.write_scalar("window/to", analysis.to, "s");
  if (!analysis.reference.empty()) write_steps(file, analysis);
  for (const auto& response : analysis.responses) write_response(file, response);
  if (!analysis.responses.empty()) {
    file.attribute("frequency_response", "method", analysis.method);
    if (analysis.method == "spectral")
      file.write_scalar("frequency_response/segment", analysis.segment, "s");
  }
  if (!analysis.notes.empty()) file.write_strings("notes", analysis.notes);
}

std::string default_analysis_path(const std::string& record, const AnalysisRequest& request) {
  std::string response = request.output;
  std::replace(response.begin(), response.end(), '/', '_');
  return "results/" + std::filesystem::path(record).stem().string() + "_" + response +
         (request.reference.empty() ? "_analysis.h5" : "_steps.h5");
}

std::string run_analyze_command(const AnalyzeOptions& options, std::ostream& out) {
  RecordChannels record;
  try {
    record = read_record_channels(options.record);
  } catch (const ConfigError&) {
    throw;  // a file that cannot be read: a data-file error
  } catch (const std::runtime_error& error) {
    throw std::invalid_argument(error.what());  // the input is wrong, not the output
  }
  const RecordAnalysis analysis = analyze_record(record, options.request);
  const std::string output = options.output.empty()
                                 ? default_analysis_path(options.record, options.request)
                                 : options.output;
  Hdf5Writer file(output);
  write_record_analysis(file, analysis);
  file.provenance({options.invocation, {{record.config_file, record.config, record.seed}}});
  file.commit();
  if (!options.quiet) out << analysis_report(analysis) << "wrote " << output << "\n";
  return output;
}

}  // namespace tcpmsim
