#include "tests/support/test_support.h"

#include "sim/run.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include <unistd.h>

namespace tcpmsim::testing {

namespace {
const std::vector<double>& lookup(const std::map<std::string, std::vector<double>>& channels,
                                  const std::string& channel) {
  const auto found = channels.find(channel);
  if (found == channels.end()) throw std::out_of_range("no channel " + channel);
  return found->second;
}
}  // namespace

const std::vector<double>& Trace::operator[](const std::string& channel) const {
  return lookup(channels, channel);
}

std::shared_ptr<const UnitSystem> shared_units() {
  static const auto units = std::make_shared<const UnitSystem>();
  return units;
}

Scenario scenario_from_text(const std::string& yaml, const std::vector<std::string>& overrides) {
  return load_scenario_text(yaml, "test.yaml", overrides, shared_units());
}

std::string config_error(const std::string& yaml, const std::vector<std::string>& overrides) {
  try {
    scenario_from_text(yaml, overrides);
  } catch (const ConfigError& error) {
    return error.what();
  }
  return "no error";
}

double allowed(double rtol, double scale) {
  return 50.0 * rtol * scale;
}

SelfSensingEstimatorParameters thesis_estimator_parameters() {
  SelfSensingEstimatorParameters p;
  p.inductance.is_measure = true;
  p.inductance.lambda_l = 2.81e-9;  // 2.81 us*mm
  p.inductance.lambda_x = 28.8e-3;
  p.inductance.lambda_0 = 0.433e-6;
  p.heating_gain = 7.2e-3;
  p.cooling_rate = 131.6e-3;
  p.mechanics = {10.8, 2.7, 4.3, 106.9e-3};  // k1, k2 [N/m], c [N s/m], phi_0 [N]
  return p;
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  if (at == std::string::npos) throw std::logic_error("'" + from + "' is not in the text");
  return text.replace(at, from.size(), to);
}

Trace simulate(const Scenario& scenario) {
  MemorySink sink(*scenario.system);
  Trace trace;
  trace.statistics = integrate(scenario, sink);
  trace.time = std::move(sink.time);
  trace.channels = std::move(sink.channels);
  return trace;
}

Trace simulate(const Scenario& scenario, Context& context) {
  MemorySink sink(*scenario.system);
  Trace trace;
  trace.statistics = integrate(scenario, context, sink);
  trace.time = std::move(sink.time);
  trace.channels = std::move(sink.channels);
  return trace;
}

Trace simulate(const std::string& yaml, const std::vector<std::string>& overrides) {
  Scenario scenario = scenario_from_text(yaml, overrides);
  return simulate(scenario);
}

namespace {
const char* kHeader = R"(
scenario: {name: test, duration: 100 s, seed: 1}
output: {rate: 10 Hz}
solver: {rtol: 1.0e-8}
)";
const char* kRestOfMuscleAndLoad = R"(
  mechanics: {k1: 10 N/m, k2: 2.5 N/m, damping: 5 N*s/m, force_offset: 0.1 N}
  resistance: 10 ohm
  inductance: {quantity: measure, lambda_l: 2.81 mm, lambda_x: 28.8 mm, lambda_0: 0.433}
drive: {mode: power, power: 0 W}
load: {type: deflection, deflection: 20 mm}
)";
}  // namespace

std::string physical_muscle_yaml() {
  return std::string(kHeader) + R"(muscle:
  thermal:
    heat_capacity: 0.5 J/K
    conductance: 0.05 W/K
    ambient_temperature: 20 degC
  thermal_force: {form: physical, force_per_kelvin: 2 mN/K, reference_temperature: 20 degC})" +
         kRestOfMuscleAndLoad;
}

std::string reduced_muscle_yaml() {
  // kappa_P = phi_T / C = 0.002 / 0.5 = 4e-3 N/J, kappa_c = hA / C = 0.1 1/s
  return std::string(kHeader) + R"(muscle:
  thermal_force:
    form: reduced
    kappa_P: 4.0e-3 N/J
    kappa_c: 0.1 1/s
    ambient_temperature: 20 degC
    force_per_kelvin: 2 mN/K)" +
         kRestOfMuscleAndLoad;
}

std::string number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

double max_abs_difference(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) throw std::invalid_argument("traces differ in length");
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
  return worst;
}

bool bitwise_equal(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

std::string process_directory(const std::string& name) {
  const auto directory = std::filesystem::temp_directory_path() / "tcpmsim_tests" /
                         (name + "_" + std::to_string(getpid()));
  std::filesystem::create_directories(directory);
  return directory.string();
}

std::string protocol_record(const std::string& duration) {
  std::string stem = duration.empty() ? "ch7_protocol" : "ch7_protocol_" + duration;
  std::replace(stem.begin(), stem.end(), ' ', '_');
  const auto path = std::filesystem::path(process_directory("protocol")) / (stem + ".h5");
  if (!std::filesystem::exists(path)) {
    std::vector<std::string> overrides;
    if (!duration.empty()) overrides.push_back("scenario.duration=" + duration);
    const Scenario protocol =
        load_scenario(source_path("configs/discover/ch7_protocol.yaml"), overrides, shared_units());
    if (!run_scenario(protocol, path.string()).succeeded)
      throw std::runtime_error("the chapter-7 protocol did not run");
  }
  return path.string();
}

std::string source_path(const std::string& relative) {
  return std::string(TCPMSIM_SOURCE_DIR) + "/" + relative;
}

}  // namespace tcpmsim::testing
