// tcpmsim analyze: step metrics and frequency responses of any record, against the analytic
// responses of the chapter-7 muscle at constant deflection, (7.1) with (7.5)-(7.6).
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>

#include "analysis/record_analysis.h"
#include "sim/memory_run.h"
#include "sim/run.h"
#include "sim/value_check.h"
#include "support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {

// Table 7.2.
constexpr double kKappaP = 7.2e-3, kKappaC = 131.6e-3;                   // N/J, 1/s
constexpr double kK1 = 10.8, kK2 = 2.7, kDamping = 4.3, kPhi0 = 0.1069;  // N/m, N/m, N s/m, N

std::complex<double> power_to_force(double frequency) {  // (7.1), (7.5) at constant x
  return kKappaP / (std::complex<double>(0.0, 2.0 * std::numbers::pi * frequency) + kKappaC);
}

std::complex<double> deflection_to_force(double frequency) {  // (7.5)-(7.6) at constant F_T
  const std::complex<double> s(0.0, 2.0 * std::numbers::pi * frequency);
  return ((kK1 + kK2) * s + kK1 * kK2 / kDamping) / (s + kK2 / kDamping);
}

// The record `tcpmsim run` writes for a shipped config, read back as analyze reads it.
RecordChannels recorded(const std::string& config) {
  const Scenario scenario = load_scenario(source_path(config), {}, shared_units());
  const std::string path =
      process_directory("record_analysis") + "/" + scenario.settings.name + ".h5";
  REQUIRE(run_scenario(scenario, path).succeeded);
  return read_record_channels(path);
}

const InputResponse& response_from(const RecordAnalysis& analysis, const std::string& input) {
  for (const auto& response : analysis.responses)
    if (response.input == input) return response;
  throw std::logic_error("no response from " + input);
}

// The fraction of estimates whose 95 % region holds the truth.
template <typename Truth>
double coverage(const InputResponse& response, Truth truth) {
  int inside = 0;
  for (const auto& estimate : response.estimates)
    inside += std::abs(estimate.response - truth(estimate.frequency)) <= estimate.radius_95;
  return double(inside) / double(response.estimates.size());
}

}  // namespace

TEST_CASE(
    "At a power multisine's lines at constant deflection, P -> F is kappa_P / (s + kappa_c) "
    "within the estimate's 95 % band",
    "[analyze]") {
  const RecordChannels record = recorded("configs/analysis/power_multisine.yaml");
  AnalysisRequest request;
  request.output = "load/force";  // the load cell: 0.5 mN resolution, the band's noise
  request.from = 100.0;           // after the thermal transient (1/kappa_c = 7.6 s)
  const RecordAnalysis analysis = analyze_record(record, request);
  REQUIRE(analysis.method == "lines");
  REQUIRE(analysis.responses.size() == 1);  // the deflection is held: only the power varies
  const InputResponse& response = response_from(analysis, "drive/power");
  CHECK(response.unit == "N/W");
  REQUIRE(response.estimates.size() == 12);
  for (const auto& estimate : response.estimates) {
    const std::complex<double> truth = power_to_force(estimate.frequency);
    INFO(estimate.frequency << " Hz: " << estimate.response << " against " << truth << ", radius "
                            << estimate.radius_95);
    CHECK(std::abs(estimate.response - truth) <= estimate.radius_95);
    // A band that says something: the quantisation noise allows 0.5 % at most.
    CHECK(estimate.radius_95 < 5e-3 * std::abs(truth));
    CHECK(estimate.overlap.empty());
  }
  // Phase: from -11 degrees at 4 mHz towards -90 (unwrapped, no jump).
  CHECK(response.estimates.back().phase == Approx(std::arg(power_to_force(0.2))).margin(0.01));
  // -3 dB against the lowest line's |H|: |H(f)| / |H(f_0)| = 1/sqrt 2 at
  // 2 pi f = sqrt(kappa_c^2 + 2 (2 pi f_0)^2), read off the straight segment between the lines
  // that bracket it (3.98 and 21.8 mHz), so within 2 %.
  const double omega0 = 2.0 * std::numbers::pi * response.estimates.front().frequency;
  const double expected =
      std::sqrt(kKappaC * kKappaC + 2.0 * omega0 * omega0) / (2.0 * std::numbers::pi);
  REQUIRE(response.bandwidth.has_value());
  CHECK(*response.bandwidth == Approx(expected).epsilon(0.02));
}

TEST_CASE("Steps of power at constant deflection give the first-order step metrics of (7.1)",
          "[analyze]") {
  const RecordChannels record = recorded("configs/analysis/power_steps.yaml");
  AnalysisRequest request;
  request.output = "muscle/force";
  request.reference = "drive/power";
  const RecordAnalysis analysis = analyze_record(record, request);
  CHECK(analysis.responses.empty());  // a reference alone asks for step metrics only
  REQUIRE(analysis.steps.size() == 4);
  const double powers[] = {2.5, 1.0, 3.0, 2.0};
  for (std::size_t k = 0; k < 4; ++k) {
    const StepMetrics& step = analysis.steps[k];
    INFO("step at " << step.step_time << " s");
    // F = phi0 + k1 x + (kappa_P / kappa_c) P once settled, (7.1), (7.5)-(7.6).
    CHECK(step.final_value ==
          Approx(kPhi0 + kK1 * 0.02 + kKappaP / kKappaC * powers[k]).epsilon(1e-6));
    // 10-90 %: ln 9 / kappa_c; 2 %: ln 50 / kappa_c; interpolation on the 16 Hz grid.
    CHECK(step.rise_time == Approx(std::log(9.0) / kKappaC).margin(0.01));
    CHECK(step.settling_time == Approx(std::log(50.0) / kKappaC).margin(0.01));
    CHECK(step.overshoot < 1e-4);                // a first-order lag does not overshoot
    CHECK(std::isnan(step.steady_state_error));  // force against power: no common unit
    // 63.2 % of the step after one time constant, 1 / kappa_c = 7.6 s; held 5 of them or more.
    CHECK(step.time_constant == Approx(1.0 / kKappaC).margin(0.01));
    CHECK(step.settled);
  }
}

TEST_CASE("A step held for fewer than five time constants is reported as not settled",
          "[analyze]") {
  // The power steps of the test above at a tenth of kappa_c: tau = 76 s, held 150 to 200 s.
  const Scenario scenario =
      load_scenario(source_path("configs/analysis/power_steps.yaml"),
                    {"muscle.thermal_force.kappa_c=13.16e-3 1/s"}, shared_units());
  const RecordAnalysis analysis =
      analyze_record(memory_record_channels(scenario, run_in_memory(scenario)), [] {
        AnalysisRequest request;
        request.output = "muscle/force";
        request.reference = "drive/power";
        return request;
      }());
  REQUIRE_FALSE(analysis.steps.empty());
  const StepMetrics& first = analysis.steps.front();
  CHECK_FALSE(first.settled);
  // Its final value falls short of the settled one, P kappa_P / kappa_c, by e^{-hold/tau} and
  // more: the rise time is short of tau ln 9.
  CHECK(first.rise_time < 0.95 * std::log(9.0) / 13.16e-3);
  const std::string report = analysis_report(analysis);
  CHECK_THAT(report, Catch::Contains("(not settled)") && Catch::Contains("warning: the step at") &&
                         Catch::Contains("it has not settled (5 are needed)"));
}

TEST_CASE(
    "An underdamped response's overshoot and steady-state error are the second-order "
    "system's",
    "[analyze]") {
  // y = 0.9 (1 - e^{-zeta w t} (cos w_d t + zeta / sqrt(1 - zeta^2) sin w_d t)) after a unit
  // reference step at t = 1 s: overshoot exp(-pi zeta / sqrt(1 - zeta^2)), error 0.1.
  const double zeta = 0.3, omega = 2.0, damped = omega * std::sqrt(1.0 - zeta * zeta);
  std::vector<double> time, reference, response;
  for (int k = 0; k <= 40000; ++k) {
    const double t = 1e-3 * k, after = t - 1.0;
    time.push_back(t);
    reference.push_back(t >= 1.0 ? 1.0 : 0.0);
    response.push_back(after <= 0.0 ? 0.0
                                    : 0.9 * (1.0 - std::exp(-zeta * omega * after) *
                                                       (std::cos(damped * after) +
                                                        zeta / std::sqrt(1.0 - zeta * zeta) *
                                                            std::sin(damped * after))));
  }
  const auto steps = step_metrics(time, reference, response, true);
  REQUIRE(steps.size() == 1);
  CHECK(steps[0].overshoot ==
        Approx(std::exp(-std::numbers::pi * zeta / std::sqrt(1.0 - zeta * zeta))).epsilon(1e-4));
  CHECK(steps[0].steady_state_error == Approx(0.1).epsilon(1e-6));
  // Settling into 2 %: the envelope e^{-zeta w t} sqrt(1/(1 - zeta^2)) crosses 0.02 at
  // about ln(50 / sqrt(1 - zeta^2)) / (zeta w); the oscillation settles at its last crossing
  // before that, so within one half period.
  const double envelope = std::log(50.0 / std::sqrt(1.0 - zeta * zeta)) / (zeta * omega);
  CHECK(steps[0].settling_time <= envelope);
  CHECK(steps[0].settling_time > envelope - std::numbers::pi / damped);
}

TEST_CASE(
    "Random steps on power and deflection at once are told apart by the multi-input "
    "estimate, each path within its jackknife band",
    "[analyze]") {
  const RecordChannels record = recorded("configs/analysis/random_steps_two_inputs.yaml");
  AnalysisRequest request;
  request.output = "load/force";
  request.from = 100.0;
  request.segment = 200.0;
  const RecordAnalysis analysis = analyze_record(record, request);
  REQUIRE(analysis.method == "spectral");
  REQUIRE(analysis.responses.size() == 2);
  const auto& power = response_from(analysis, "drive/power");
  const auto& deflection = response_from(analysis, "load/deflection");
  REQUIRE(power.estimates.size() > 50);
  REQUIRE(deflection.estimates.size() > 50);
  // A 95 % band holds the truth at about 95 % of the frequencies; a biased estimate or a band
  // too narrow (the coherence formula's, here) falls far below.
  CHECK(coverage(power, power_to_force) > 0.88);
  CHECK(coverage(deflection, deflection_to_force) > 0.88);
  // Where the thermal path is strong (below 0.1 Hz) the estimate is within 3 % of it.
  for (const auto& estimate : power.estimates)
    if (estimate.frequency < 0.1)
      CHECK(std::abs(estimate.response / power_to_force(estimate.frequency) - 1.0) < 0.03);
}

TEST_CASE("Lines both inputs excite are named, not estimated", "[analyze]") {
  // The identification protocol (7.3.5) puts 7 power and 11 deflection lines in one band: 3.98,
  // 41.7 and 79.4 mHz are in both. Its multisines last 200 s, too short to tell lines 2.5 mHz
  // apart (next test); here they last 600 s.
  const Scenario scenario =
      load_scenario(source_path("configs/ch7_identification.yaml"),
                    {"drive.power.segments[0].duration=600 s",
                     "load.deflection.segments[0].duration=600 s", "scenario.duration=800 s"},
                    shared_units());
  const RecordChannels record = memory_record_channels(scenario, run_in_memory(scenario));
  AnalysisRequest request;
  request.output = "load/force";
  request.inputs = {"drive/power"};
  request.from = 60.0;  // after the start-up transient (1/kappa_c = 7.6 s)
  const RecordAnalysis analysis = analyze_record(record, request);
  REQUIRE(analysis.method == "lines");
  CHECK(analysis.to < 600.0);  // the multisine's stretch, not the random steps after it
  const auto& power = response_from(analysis, "drive/power");
  REQUIRE(power.estimates.size() == 7);
  int shared = 0;
  for (const auto& estimate : power.estimates) {
    if (estimate.overlap.empty()) {
      // Resolved, the lines give (7.1) with (7.5): the deflection's own lines are fitted beside.
      CHECK(std::abs(estimate.response / power_to_force(estimate.frequency) - 1.0) < 0.005);
      continue;
    }
    ++shared;
    CHECK(estimate.overlap == "load/deflection");
    CHECK(std::isnan(estimate.magnitude));
  }
  CHECK(shared == 3);
  bool noted = false;
  for (const auto& note : analysis.notes)
    noted = noted || note.find("not estimable") != std::string::npos;
  CHECK(noted);
  // From the multisine's start, the transient is in the window, and the note says so.
  request.from = 0.0;
  bool transient = false;
  for (const auto& note : analyze_record(record, request).notes)
    transient = transient ||
                note.find("the response's transient there biases the lines") != std::string::npos;
  CHECK(transient);
}

TEST_CASE("A window too short to tell the lines apart is not fitted at them", "[analyze]") {
  // 200 s of the protocol's multisines: a power line and a deflection line 2.5 mHz apart need
  // 400 s. Fitted anyway, the power's lines came out 20-56 % off kappa_P / (s + kappa_c) with
  // 95 % radii of 2-10 %; the analysis says so and estimates spectrally, or refuses --method
  // lines.
  const RecordChannels record = recorded("configs/ch7_identification.yaml");
  AnalysisRequest request;
  request.output = "load/force";
  request.inputs = {"drive/power"};
  request.to = 200.0;
  const RecordAnalysis analysis = analyze_record(record, request);
  CHECK(analysis.method == "spectral");
  bool noted = false;
  for (const auto& note : analysis.notes)
    noted = noted || note.find(
                         "cannot tell the multisine's lines apart: they lie 2.515 mHz "
                         "apart, which needs 397.6 s or more") != std::string::npos;
  CHECK(noted);
  request.method = "lines";
  CHECK_THROWS_WITH(analyze_record(record, request),
                    Catch::Contains("cannot tell the multisine's lines apart") &&
                        Catch::Contains("--method spectral"));
}

TEST_CASE("A run in memory analyses as its record does", "[analyze]") {
  const Scenario scenario =
      load_scenario(source_path("configs/analysis/power_steps.yaml"), {}, shared_units());
  const MemoryRun run = run_in_memory(scenario);
  AnalysisRequest request;
  request.output = "muscle/force";
  request.reference = "drive/power";
  const auto in_memory = analyze_record(memory_record_channels(scenario, run), request);
  const auto from_file = analyze_record(recorded("configs/analysis/power_steps.yaml"), request);
  REQUIRE(in_memory.steps.size() == from_file.steps.size());
  for (std::size_t k = 0; k < in_memory.steps.size(); ++k) {
    CHECK(in_memory.steps[k].rise_time == from_file.steps[k].rise_time);
    CHECK(in_memory.steps[k].settling_time == from_file.steps[k].settling_time);
  }
  // The multisine stretches come from the signals' descriptions either way.
  const Scenario multisine =
      load_scenario(source_path("configs/analysis/power_multisine.yaml"), {}, shared_units());
  const auto channels = memory_record_channels(multisine, run_in_memory(multisine));
  REQUIRE(channels.inputs.at("drive/power").size() == 1);
  CHECK(channels.inputs.at("drive/power").front().frequencies.size() == 12);
}

TEST_CASE("analyze says what is wrong with a request", "[analyze]") {
  const RecordChannels record = recorded("configs/analysis/power_steps.yaml");
  AnalysisRequest request;
  request.output = "muscle/forse";
  CHECK_THROWS_WITH(analyze_record(record, request), Catch::Contains("no channel 'muscle/forse'") &&
                                                         Catch::Contains("muscle/force"));
  request.output = "muscle/force";
  request.inputs = {"load/deflection"};  // held at 20 mm
  CHECK_THROWS_WITH(analyze_record(record, request), Catch::Contains("is constant in the window"));
  request.inputs = {"drive/power"};
  request.method = "lines";
  CHECK_THROWS_WITH(analyze_record(record, request), Catch::Contains("no multisine"));
  request.method = "auto";
  request.from = 900.0;
  CHECK_THROWS_WITH(analyze_record(record, request), Catch::Contains("fewer than two samples"));
}

TEST_CASE("Two inputs that move together cannot be told apart, and analyze says so", "[analyze]") {
  RecordChannels record;
  record.source = "synthetic";
  std::uint64_t state = 12345;
  double level = 0.0, output = 0.0;
  for (int k = 0; k < 8000; ++k) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;  // an LCG's random steps
    if ((state >> 60) == 0) level = double(state >> 40) / double(1ULL << 24);
    output += 0.1 * (level - output);  // a first-order lag
    record.time.push_back(0.1 * k);
    record.channels["a/u"].values.push_back(level);
    record.channels["b/u"].values.push_back(2.0 * level);  // the same input, scaled
    record.channels["c/y"].values.push_back(output);
  }
  for (auto* name : {"a/u", "b/u", "c/y"}) record.channels[name].unit = "1";
  record.inputs["a/u"] = {};
  record.inputs["b/u"] = {};
  AnalysisRequest request;
  request.output = "c/y";
  const RecordAnalysis analysis = analyze_record(record, request);
  REQUIRE(analysis.method == "spectral");
  REQUIRE(analysis.responses.size() == 2);
  for (const auto& response : analysis.responses) CHECK(response.estimates.empty());
  int notes = 0;
  for (const auto& note : analysis.notes)
    notes += note.find("no frequency where the estimate stands out") != std::string::npos;
  CHECK(notes == 2);
}

TEST_CASE("A temperature's step is printed in degC, as the plots show it, and kept in K",
          "[analyze]") {
  // A 0.5 W step into C dT/dt = P - hA (T - T_amb), hA = 73 mW/K, T_amb = 23 degC: the
  // temperature settles at 23 degC + 0.5 / 0.073 K = 29.849 degC (302.999 K).
  const Scenario scenario =
      load_scenario(source_path("configs/sweeps/thermal_step.yaml"), {}, shared_units());
  AnalysisRequest request;
  request.output = "muscle/temperature";
  request.reference = "drive/power";
  const RecordAnalysis analysis =
      analyze_record(memory_record_channels(scenario, run_in_memory(scenario)), request);
  REQUIRE(analysis.steps.size() == 1);
  const double settled = 296.15 + 0.5 / 0.073;
  CHECK(analysis.steps[0].final_value == Approx(settled).epsilon(1e-9));  // SI in the analysis
  const std::string report = analysis_report(analysis);
  CHECK_THAT(report, Catch::Contains("step response of muscle/temperature [degC] against "
                                     "drive/power [W]") &&
                         Catch::Contains("temperatures in degC, their differences in K"));
  CHECK_THAT(report, Catch::Contains("   0.5   " + number_text(settled - 273.15, 4) + "   "));
  CHECK(number_text(settled - 273.15, 4) == "29.85");
}
