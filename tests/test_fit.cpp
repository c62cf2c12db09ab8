// Output-error identification: the thesis' chapter-7 fit of the force model, recovered from data
// simulated under the chapter-7 protocol with load-cell noise.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numeric>

#include "identification/bench_measurement.h"
#include "identification/fit_report.h"
#include "sim/run.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {

std::filesystem::path fit_directory() {
  return process_directory("fit");
}

// A fit of `paths` (bounds: half to twice the model's value) of the base model to `data`.
fit::FitProblem base_problem(const std::string& data, const std::vector<std::string>& paths,
                             const std::vector<std::string>& overrides = {}) {
  std::vector<std::string> all = overrides;
  all.push_back("measurement.file=" + data);
  fit::FitProblem problem;
  problem.model = std::make_shared<const Scenario>(
      load_scenario(source_path("configs/discover/ch7_base.yaml"), all, shared_units()));
  problem.data = std::make_shared<const MeasuredData>(read_measured_data(data, *shared_units()));
  problem.outputs = {{"force", "load.force", "N", 1e-3}};
  const Context context = problem.model->make_context();
  for (const auto& path : paths) {
    const auto index = problem.model->system->parameter_index(path);
    const auto& unit =
        problem.model->system->parameters()[static_cast<std::size_t>(*index)].declaration.unit;
    problem.parameters.push_back(
        {path, unit, 0.5 * context.parameter(path), 2.0 * context.parameter(path)});
  }
  problem.identification = {0.0, 400.0};
  problem.validation = {400.0, 620.0};
  return problem;
}

// A bench measurement of the Table 7.2 muscle under the chapter-7 protocol: the protocol's
// power and deflection as the bench applies and records them at 16 Hz (the power held over each
// sample), and the muscle's force under those inputs read by the load cell (0.5 mN resolution)
// with normal noise (configs/discover/ch7_bench.yaml's instruments).
std::string protocol_measurement(double noise, std::uint64_t seed,
                                 const std::vector<std::string>& overrides = {}) {
  const std::string inputs = (fit_directory() / "protocol_inputs.h5").string();
  if (!std::filesystem::exists(inputs)) {
    const Scenario protocol =
        load_scenario(source_path("configs/discover/ch7_protocol.yaml"), {}, shared_units());
    REQUIRE(run_scenario(protocol, inputs).succeeded);
  }
  std::vector<std::string> truth_overrides = overrides;
  truth_overrides.push_back("measurement.file=" + inputs);
  const Scenario truth =
      load_scenario(source_path("configs/discover/ch7_base.yaml"), truth_overrides, shared_units());
  const auto bench_file = fit_directory() / "bench.yaml";
  std::ofstream(bench_file) << "seed: " << seed << R"(
channels:
  - {channel: power, output: drive.power, unit: W}
  - {channel: deflection, output: load.deflection, unit: m}
  - {channel: force, output: load.force, unit: N, resolution: 0.5 mN, noise: )"
                            << number(noise) << " N}\n";
  const fit::Bench bench = fit::load_bench(bench_file.string(), truth, shared_units());
  const std::string path =
      (fit_directory() / ("protocol_" + std::to_string(seed) + ".csv")).string();
  std::ofstream(path) << fit::measure(truth, bench, *shared_units());
  return path;
}

// Table 7.2's six force-model parameters (SI).
struct Table72 {
  const char* path;
  const char* unit;
  double value;
};
const std::vector<Table72> kTable72 = {{"muscle.thermal_force.kappa_P", "N/J", 7.2e-3},
                                       {"muscle.thermal_force.kappa_c", "1/s", 131.6e-3},
                                       {"muscle.mechanics.force_offset", "N", 106.9e-3},
                                       {"muscle.mechanics.k1", "N/m", 10.8},
                                       {"muscle.mechanics.k2", "N/m", 2.7},
                                       {"muscle.mechanics.damping", "N*s/m", 4.3}};

// The six parameters fitted to `data_path` (force noise `noise`) from 20 % away from the truth,
// within half to twice it; `overrides` go to the model.
fit::FitResult fit_table_7_2(const std::string& data_path, double noise,
                             std::vector<std::string> overrides = {}) {
  for (const std::string& start : std::vector<std::string>{
           "measurement.file=" + data_path, "muscle.thermal_force.kappa_P=8.64e-3 N/J",
           "muscle.thermal_force.kappa_c=0.105 1/s", "muscle.mechanics.force_offset=0.0855 N",
           "muscle.mechanics.k1=12.96e-3 N/mm", "muscle.mechanics.k2=2.16e-3 N/mm",
           "muscle.mechanics.damping=5.16e-3 N*s/mm"})
    overrides.push_back(start);
  fit::FitProblem problem;
  problem.model = std::make_shared<const Scenario>(
      load_scenario(source_path("configs/discover/ch7_base.yaml"), overrides, shared_units()));
  problem.data =
      std::make_shared<const MeasuredData>(read_measured_data(data_path, *shared_units()));
  problem.outputs = {{"force", "load.force", "N", noise}};
  for (const auto& parameter : kTable72) {
    problem.parameters.push_back(
        {parameter.path, parameter.unit, 0.5 * parameter.value, 2.0 * parameter.value});
  }
  problem.identification = {0.0, 400.0};
  problem.validation = {400.0, 620.0};
  fit::FitSettings settings;
  settings.starts = 0;
  settings.refine = 1;
  return fit::fit_model(problem, settings);
}

}  // namespace

TEST_CASE("The six force-model parameters of Table 7.2 are recovered from the chapter-7 protocol") {
  const double noise = 1e-3;  // N
  const fit::FitResult result = fit_table_7_2(protocol_measurement(noise, 7), noise);
  INFO(result.termination << "; " << result.iterations << " iterations, " << result.simulations
                          << " simulations");
  for (std::size_t j = 0; j < kTable72.size(); ++j) {
    const auto& estimate = result.estimates[j];
    INFO(estimate.path << " = " << estimate.value << " +- " << estimate.standard_error << ", truth "
                       << kTable72[j].value);
    CHECK(estimate.identifiable);
    CHECK(std::abs(estimate.value - kTable72[j].value) <= 3.0 * estimate.standard_error);
    CHECK(estimate.standard_error < 0.05 * kTable72[j].value);
  }
  CHECK(result.gradient == "forward sensitivities (CVODES)");
  CHECK(result.converged);  // by a tolerance, well within the iteration limit
  for (const auto& estimate : result.estimates) CHECK(estimate.at_bound == "");
  WARN("fit: " << result.iterations << " iterations, " << result.simulations << " simulations; "
               << "validation RMSE " << result.validation.rmse[0] * 1e3 << " mN, R2 "
               << result.validation.r2[0]);
  CHECK(result.identification.rmse[0] == Approx(noise).epsilon(0.1));
}

TEST_CASE(
    "A fit finds the same estimates whether its sensitivities are under error control or not") {
  // Outside CVODES' error test the sensitivities ride on the state's steps: the Jacobian that
  // steers Levenberg-Marquardt is a little less accurate, the cost it minimises the same.
  const double noise = 1e-3;  // N
  const std::string data = protocol_measurement(noise, 7);
  const fit::FitResult riding = fit_table_7_2(data, noise);
  const fit::FitResult controlled =
      fit_table_7_2(data, noise, {"solver.sensitivity_error_control=true"});
  REQUIRE(riding.converged);
  REQUIRE(controlled.converged);
  for (std::size_t j = 0; j < kTable72.size(); ++j) {
    const auto& a = riding.estimates[j];
    const auto& b = controlled.estimates[j];
    INFO(a.path << ": " << a.value << " +- " << a.standard_error << " against " << b.value << " +- "
                << b.standard_error);
    CHECK(std::abs(a.value - b.value) <= 1e-3 * b.standard_error);
    CHECK(a.standard_error == Approx(b.standard_error).epsilon(1e-3));
  }
}

TEST_CASE(
    "The outputs' sensitivities from CVODES agree with central differences of whole simulations") {
  const std::string data = protocol_measurement(1e-3, 3);
  const std::vector<std::string> paths = {
      "muscle.thermal_force.kappa_P",  "muscle.thermal_force.kappa_c",
      "muscle.mechanics.force_offset", "muscle.mechanics.k1",
      "muscle.mechanics.k2",           "muscle.mechanics.damping"};
  // Tight tolerances, so that the differences of whole runs are accurate enough to judge by.
  const fit::FitProblem problem = base_problem(data, paths, {"solver.rtol=1e-10"});
  REQUIRE(fit::sensitivities_unavailable(problem).empty());
  const Context context = problem.model->make_context();
  std::vector<double> values;
  for (const auto& path : paths) values.push_back(context.parameter(path));
  std::vector<std::size_t> tracked(paths.size());
  std::iota(tracked.begin(), tracked.end(), 0);
  const auto sensitivities =
      fit::simulate_sensitivities(problem, values, tracked, problem.identification);
  for (std::size_t j = 0; j < paths.size(); ++j) {
    // Central differences err by O(step^2) and by the runs' own errors over 2 step.
    const double step = 1e-3 * values[j];
    std::vector<double> up = values, down = values;
    up[j] += step;
    down[j] -= step;
    const auto high = fit::simulate_outputs(problem, up, problem.identification)[0];
    const auto low = fit::simulate_outputs(problem, down, problem.identification)[0];
    double largest = 0.0, worst = 0.0;
    for (std::size_t i = 0; i < high.size(); ++i) {
      const double difference = (high[i] - low[i]) / (2.0 * step);
      largest = std::max(largest, std::abs(difference));
      worst = std::max(worst, std::abs(sensitivities.sensitivities[0][j][i] - difference));
    }
    INFO(paths[j] << ": largest dF/dp " << largest << ", worst disagreement " << worst);
    CHECK(largest > 0.0);
    CHECK(worst <= 1e-5 * largest);
  }
  // GMRES solves the sensitivities' Newton systems as the state's: the same sensitivities, to
  // the accuracy asked of them above. (Differences of whole GMRES runs are no reference: the
  // number of Krylov iterations changes with p, which makes a run's output a slightly rough
  // function of p that differences over a 1e-3 step magnify.)
  const fit::FitProblem krylov =
      base_problem(data, paths, {"solver.rtol=1e-10", "solver.linear_solver=gmres"});
  const auto krylov_sensitivities =
      fit::simulate_sensitivities(krylov, values, tracked, problem.identification);
  for (std::size_t j = 0; j < paths.size(); ++j) {
    const auto& direct = sensitivities.sensitivities[0][j];
    const auto& iterated = krylov_sensitivities.sensitivities[0][j];
    REQUIRE(iterated.size() == direct.size());
    double largest = 0.0;
    for (double value : direct) largest = std::max(largest, std::abs(value));
    INFO(paths[j]);
    CHECK(max_abs_difference(iterated, direct) <= 1e-5 * largest);
  }
}

TEST_CASE("Fit settings that no fit can follow are refused before any simulation") {
  // A negative iteration limit once reached Ceres, which refused it and left a cost of -1 that
  // won the multistart (discover's retry from drawn starts).
  const std::string data = protocol_measurement(1e-3, 3);
  const fit::FitProblem problem = base_problem(data, {"muscle.mechanics.k1"});
  for (const auto& [name, change] :
       std::vector<std::pair<std::string, std::function<void(fit::FitSettings&)>>>{
           {"max_iterations", [](fit::FitSettings& s) { s.max_iterations = -14; }},
           {"starts", [](fit::FitSettings& s) { s.starts = -1; }},
           {"refine", [](fit::FitSettings& s) { s.refine = -1; }}}) {
    INFO(name);
    fit::FitSettings settings;
    change(settings);
    CHECK_THROWS_WITH(fit::fit_model(problem, settings),
                      Catch::Contains(name) && Catch::Contains("none may be negative"));
  }
}

TEST_CASE("Parameters the data cannot identify are named, never returned as numbers") {
  // At a constant deflection x the force is phi0 + k1 x + ...: the data fix only their sum. In
  // the reduced form (7.1), phi_T only converts F_T into a reported temperature.
  const std::string data = protocol_measurement(1e-3, 11, {"load.deflection=20 mm"});
  fit::FitProblem problem =
      base_problem(data,
                   {"muscle.mechanics.force_offset", "muscle.mechanics.k1",
                    "muscle.thermal_force.kappa_P", "muscle.thermal_force.force_per_kelvin"},
                   {"load.deflection=20 mm"});
  fit::FitSettings settings;
  settings.starts = 0;
  const fit::FitResult result = fit::fit_model(problem, settings);
  for (const auto& line : result.identifiability) INFO(line);
  CHECK(result.rank < 4);
  CHECK_FALSE(result.estimates[0].identifiable);
  CHECK_FALSE(result.estimates[1].identifiable);
  CHECK(result.estimates[2].identifiable);
  CHECK_FALSE(result.estimates[3].identifiable);
  CHECK(std::isnan(result.estimates[0].standard_error));
  CHECK(std::isnan(result.estimates[3].standard_error));
  CHECK(std::find(result.identifiability.begin(), result.identifiability.end(),
                  "muscle.thermal_force.force_per_kelvin does not change the outputs") !=
        result.identifiability.end());
  bool offset_and_stiffness_named = false;
  for (const auto& line : result.identifiability) {
    offset_and_stiffness_named = offset_and_stiffness_named ||
                                 (line.find("muscle.mechanics.force_offset") != std::string::npos &&
                                  line.find("muscle.mechanics.k1") != std::string::npos);
  }
  CHECK(offset_and_stiffness_named);
  // kappa_P is still fixed by the data, and well.
  CHECK(result.estimates[2].value == Approx(7.2e-3).epsilon(0.01));
}

TEST_CASE("An estimate on its bound, and a fit stopped at its iteration limit, say so") {
  // The data hold Table 7.2's k1 = 10.8 N/m; bounds of [5, 10] N/m keep the fit below it, so
  // k1 ends on its upper bound (and kappa_P, free inside its bounds, off them).
  const std::string data = protocol_measurement(1e-3, 3);
  fit::FitSpec spec;
  spec.model_file = "ch7_base.yaml";
  spec.data_file = data;
  // The first 120 s of the protocol's multisines are enough to show either, at a fifth of the
  // cost of the whole 620 s.
  const auto shortened = [&](std::vector<std::string> paths) {
    fit::FitProblem problem = base_problem(data, paths, {"scenario.duration=120 s"});
    problem.identification = {0.0, 100.0};
    problem.validation = {100.0, 120.0};
    return problem;
  };
  spec.problem = shortened({"muscle.mechanics.k1", "muscle.thermal_force.kappa_P"});
  spec.problem.parameters[0].lower = 5.0;
  spec.problem.parameters[0].upper = 10.0;
  spec.settings.starts = 0;
  spec.settings.start = {8.0, 7.2e-3};
  const fit::FitResult bounded = fit::fit_model(spec.problem, spec.settings);
  CHECK(bounded.estimates[0].value == 10.0);
  CHECK(bounded.estimates[0].at_bound == "upper");
  CHECK(bounded.estimates[1].at_bound == "");
  CHECK_THAT(fit::fit_summary(spec, bounded),
             Catch::Contains("at a bound: muscle.mechanics.k1 ended on its upper bound, 10 N/m; "
                             "the optimum may lie beyond it"));
  // A path longer than the column (an effect's parameter) widens it: the columns stay apart.
  fit::FitResult long_path = bounded;
  long_path.estimates[0].path = "muscle.effects[0].hysteresis.stiffness_of_a_long_name";
  CHECK_THAT(fit::fit_summary(spec, long_path),
             Catch::Contains("  muscle.effects[0].hysteresis.stiffness_of_a_long_name  8 "));
  CHECK_THAT(fit::fit_json(spec, bounded),
             Catch::Contains("\"at_bound\": \"upper\"") && Catch::Contains("\"at_bound\": null"));
  // One iteration from 20 % off is not enough: the fit says it did not converge.
  spec.problem = shortened({"muscle.mechanics.k1", "muscle.mechanics.k2"});
  spec.settings.start = {0.8 * 10.8, 1.2 * 2.7};
  spec.settings.max_iterations = 1;
  const fit::FitResult stopped = fit::fit_model(spec.problem, spec.settings);
  CHECK_FALSE(stopped.converged);
  CHECK(stopped.iterations <= 2);  // Ceres counts the start as its iteration 0
  CHECK_THAT(fit::fit_summary(spec, stopped),
             Catch::Contains("not converged: the fit stopped at its limit of 1 iterations"));
  CHECK_THAT(fit::fit_json(spec, stopped),
             Catch::Contains("\"converged\": false") && Catch::Contains("\"max_iterations\": 1"));
}

TEST_CASE("A parameter the summary calls not identified is not identifiable in the estimates") {
  // The deflection moves by 0.5 mm around 20 mm: force_offset and k1 x are told apart by the
  // step alone, so the two are correlated above 0.99 yet within the Jacobian's rank. Their
  // standard errors are numbers, large ones; the summary names the pair, and the estimates (and
  // fit.json) mark both, never "identifiable" beside a "not identified".
  const std::vector<std::string> hold = {
      "load.deflection={type: steps, initial: 20 mm, times: [150 s], values: [20.5 mm]}"};
  const std::string data = protocol_measurement(1e-3, 12, hold);
  fit::FitProblem problem = base_problem(
      data,
      {"muscle.mechanics.force_offset", "muscle.mechanics.k1", "muscle.thermal_force.kappa_P"},
      hold);
  fit::FitSettings settings;
  settings.starts = 0;
  const fit::FitResult result = fit::fit_model(problem, settings);
  for (const auto& line : result.identifiability) INFO(line);
  CHECK(result.rank == 3);
  CHECK_FALSE(result.estimates[0].identifiable);
  CHECK_FALSE(result.estimates[1].identifiable);
  CHECK(result.estimates[2].identifiable);
  CHECK(std::isfinite(result.estimates[1].standard_error));
  // Every parameter a "not identified" line names is marked, and every one marked is named.
  for (const auto& estimate : result.estimates) {
    bool named = false;
    for (const auto& line : result.identifiability)
      named = named || line.find(estimate.path) != std::string::npos;
    INFO(estimate.path);
    CHECK(named == !estimate.identifiable);
  }
}

namespace {

std::string fit_file_error(const std::string& text, const std::string& data) {
  const auto path = fit_directory() / "errors.yaml";
  std::ofstream(path) << text;
  try {
    fit::load_fit(path.string(), {}, data, 1, shared_units());
  } catch (const ConfigError& error) {
    return error.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("A fit file's mistakes are located at their keys") {
  const std::string data = protocol_measurement(1e-3, 3);
  const std::string model = source_path("configs/discover/ch7_base.yaml");
  const std::string file = (fit_directory() / "errors.yaml").string();  // as fit_file_error writes
  const std::string valid = "model: " + model + R"(
outputs: [{channel: force, output: load.force, noise: 1 mN}]
parameters: [{path: muscle.mechanics.k1, bounds: [5 N/m, 20 N/m]}]
identification: [0 s, 400 s]
)";
  CHECK(fit_file_error(valid, data) == "no error");
  CHECK(fit_file_error(valid + "max_iterations: 0\n", data)
            .starts_with(file + ":5:17: error: max_iterations: "));
  CHECK(fit_file_error(replaced(valid, "muscle.mechanics.k1", "muscle.mechanics.k3"), data) ==
        file +
            ":3:21: error: parameters[0].path: the model has no parameter 'muscle.mechanics.k3'");
  CHECK(fit_file_error(replaced(valid, "[5 N/m, 20 N/m]", "[11 N/m, 20 N/m]"), data) ==
        file +
            ":3:50: error: parameters[0].bounds: the model's value 10.8 N/m is "
            "outside the bounds");
  CHECK(fit_file_error(replaced(valid, "[5 N/m, 20 N/m]", "[5 N, 20 N]"), data) ==
        file +
            ":3:51: error: parameters[0].bounds[0]: wrong unit in '5 N': unit 'N' cannot be "
            "converted to 'N/m'; expected a stiffness (force/length), e.g. N/m or N/mm");
  CHECK(fit_file_error(replaced(valid, "output: load.force", "output: load.forse"), data) ==
        file +
            ":2:36: error: outputs[0].output: the model has no output 'load.forse' (outputs "
            "are named group.name, as in its record)");
  CHECK(fit_file_error(replaced(valid, "channel: force", "channel: forse"), data) ==
        file + ":2:21: error: outputs[0].channel: " + data +
            " has no channel 'forse' (did you mean 'force'?); its channels: time, power, "
            "deflection, force");
  CHECK(fit_file_error(replaced(valid, "[0 s, 400 s]", "[0 s, 700 s]"), data) ==
        file +
            ":4:17: error: identification: the window [0 s, 700 s] is not inside the data, "
            "which run from 0 s to 620 s");
  CHECK(fit_file_error(valid + "validation: [300 s, 620 s]\n", data) ==
        file +
            ":5:13: error: validation: the validation window overlaps the identification "
            "window [0 s, 400 s]; data the fit has seen cannot validate it");
  CHECK(fit_file_error(valid + "set: [output.rate=10 Hz]\n", data) ==
        file +
            ":1:8: error: model: the model records at 10 Hz, less often than the data are "
            "sampled (16 Hz); set its output.rate to at least that (set: [output.rate=16 Hz])");
  CHECK(fit_file_error(valid + "set: [muscle.mechanics.k1=-1 N/m]\n", data)
            .starts_with(file + ":5:7: error: set[0]: scenario 'model' does not take it"));
}

TEST_CASE("A fit's estimates are the same on one, two and three threads", "[thread]") {
  // The sensitivities are integrated in the same groups whatever the thread count, so the
  // threads change the fit's speed only.
  const std::string data = protocol_measurement(1e-3, 6);
  auto problem = base_problem(
      data, {"muscle.mechanics.k1", "muscle.thermal_force.kappa_c", "muscle.mechanics.damping"});
  problem.identification = {0.0, 120.0};
  problem.validation = {120.0, 160.0};
  fit::FitSettings settings;
  settings.starts = 2;
  settings.max_iterations = 4;
  std::vector<fit::FitResult> results;
  for (const int threads : {1, 2, 3}) {
    settings.threads = threads;
    results.push_back(fit::fit_model(problem, settings));
  }
  for (const auto& result : results) {
    CHECK(result.gradient == results[0].gradient);
    CHECK(result.cost == results[0].cost);
    for (std::size_t j = 0; j < result.estimates.size(); ++j)
      CHECK(result.estimates[j].value == results[0].estimates[j].value);
  }
}

TEST_CASE("A fit on two threads writes a report whose fitted scenario reruns to the fitted outputs",
          "[thread]") {
  const std::string data = protocol_measurement(1e-3, 5);
  const auto path = fit_directory() / "short.yaml";
  std::ofstream(path) << "model: " << source_path("configs/discover/ch7_base.yaml") << R"(
set: [muscle.mechanics.k1=12 mN/mm]
outputs: [{channel: force, output: load.force, noise: 1 mN}]
parameters: [{path: muscle.mechanics.k1, bounds: [5 N/m, 20 N/m]}]
identification: [0 s, 400 s]
validation: [400 s, 620 s]
multistart: {starts: 2}
)";
  const fit::FitSpec spec = fit::load_fit(path.string(), {}, data, 2, shared_units());
  const fit::FitResult result = fit::fit_model(spec.problem, spec.settings);
  CHECK(result.estimates[0].initial == 12.0);
  CHECK(result.estimates[0].value == Approx(10.8).margin(3 * result.estimates[0].standard_error));
  const auto out = fit_directory() / "out";
  fit::write_fit_outputs(out.string(), spec, result);
  std::string header;
  std::getline(std::ifstream(out / "fitted.yaml"), header);
  CHECK(header ==
        "# " + spec.model_file + " fitted to " + data + " by tcpmsim fit " + path.string());
  const Trace rerun = simulate(load_scenario((out / "fitted.yaml").string(), {}, shared_units()));
  const MeasuredData written = read_measured_data((out / "fit.h5").string(), *shared_units());
  REQUIRE(written.find("fitted.force") != nullptr);
  const auto& fitted = written.find("fitted.force")->values;
  REQUIRE(rerun.time.size() == fitted.size());
  // The estimate is written with 17 digits, so the rerun is the fitted model itself.
  CHECK(max_abs_difference(rerun["load/force"], fitted) <= 1e-12);
  CHECK(bitwise_equal(written.find("measured.force")->values,
                      spec.problem.data->find("force")->values));
}
