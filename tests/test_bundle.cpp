// Bundles of muscles in parallel: the packing's geometry, the wiring's current sharing, the
// packed convection and the energy balance, each against a case worked out by hand.
#include <catch2/catch.hpp>

#include <H5Cpp.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numeric>

#include "models/laws/bundle_circuit.h"
#include "models/laws/packing.h"
#include "sim/run.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {

constexpr double kAmbient = 296.15;      // 23 degC
constexpr double kR0 = 10.0;             // ohm at 23 degC
constexpr double kAlpha = 5.0e-3;        // 1/K, iron-like: hot muscles resist more
constexpr double kConductance = 2.0e-3;  // W/K, free air
constexpr double kCapacity = 0.01;       // J/K

// A bundle of `count` physical-form muscles (no radiation unless `radiation`) under `extra`
// keys of the bundle section (packing, thermal, electrical, spread), on an imposed 20 mm.
std::string bundle_yaml(int count, const std::string& extra, double duration = 400.0,
                        const std::string& thermal_extra = "") {
  return "scenario: {name: bundle, duration: " + number(duration) + R"( s, seed: 3}
output: {rate: 1 Hz}
solver: {rtol: 1.0e-9}
bundle:
  count: )" +
         std::to_string(count) +
         R"(
  muscle:
    thermal: {heat_capacity: 0.01 J/K, conductance: 2 mW/K, ambient_temperature: 23 degC)" +
         thermal_extra + R"(}
    thermal_force: {form: physical, force_per_kelvin: 4 mN/K, reference_temperature: 23 degC}
    mechanics: {k1: 10.8 N/m, k2: 2.7 N/m, damping: 4.3 N*s/m, force_offset: 0.1 N}
    resistance: {form: thermal, resistance: 10 ohm, temperature_coefficient: 5.0e-3 1/K, reference_temperature: 23 degC}
    inductance: {lambda_l: 107.4 uH*mm, lambda_x: 61 mm, lambda_0: 2.67 uH}
)" + extra +
         "load: {type: deflection, bundle: bundle, deflection: 20 mm}\n";
}

std::string member(int k, const std::string& channel) {
  return "bundle/m" + std::to_string(k) + channel;
}

// Two members' currents and resistances.
struct TwoMembers {
  const std::vector<double>& i0;
  const std::vector<double>& i1;
  const std::vector<double>& r0;
  const std::vector<double>& r1;
};
TwoMembers two_members(const Trace& trace) {
  return {trace[member(0, "/wire/current")], trace[member(1, "/wire/current")],
          trace[member(0, "/resistance")], trace[member(1, "/resistance")]};
}

}  // namespace

TEST_CASE("Hexagonal and square packings fill ring by ring, and only touching muscles neighbour") {
  const double pitch = 1.5e-3;
  const auto hexagon = packing::cross_section(PackingLayout::hexagonal, 19, pitch);
  REQUIRE(hexagon.centres.size() == 19);
  CHECK(hexagon.coordination() == 6);
  // The centre and the first ring of six are inner; the twelve of the second ring are not.
  for (std::size_t k = 0; k < 7; ++k) CHECK(hexagon.neighbours[k].size() == 6);
  int corners = 0, edges = 0;
  for (std::size_t k = 7; k < 19; ++k) {
    const double distance = std::hypot(hexagon.centres[k][0], hexagon.centres[k][1]);
    CHECK((std::abs(distance - 2 * pitch) < 1e-12 ||
           std::abs(distance - std::sqrt(3.0) * pitch) < 1e-12));
    (hexagon.neighbours[k].size() == 3 ? corners : edges) += 1;
    CHECK((hexagon.neighbours[k].size() == 3 || hexagon.neighbours[k].size() == 4));
  }
  CHECK(corners == 6);
  CHECK(edges == 6);
  // Neighbourhood is symmetric, and neighbours touch: exactly one pitch apart.
  for (std::size_t i = 0; i < hexagon.neighbours.size(); ++i) {
    for (const int j : hexagon.neighbours[i]) {
      const auto& back = hexagon.neighbours[static_cast<std::size_t>(j)];
      CHECK(std::count(back.begin(), back.end(), static_cast<int>(i)) == 1);
      const auto& a = hexagon.centres[i];
      const auto& b = hexagon.centres[static_cast<std::size_t>(j)];
      CHECK(std::hypot(a[0] - b[0], a[1] - b[1]) == Approx(pitch).epsilon(1e-12));
    }
  }

  const auto square = packing::cross_section(PackingLayout::square, 9, pitch);
  CHECK(square.coordination() == 4);
  std::vector<std::size_t> counts;
  for (const auto& list : square.neighbours) counts.push_back(list.size());
  std::sort(counts.begin(), counts.end());
  CHECK(counts == std::vector<std::size_t>{2, 2, 2, 2, 3, 3, 3, 3, 4});

  CHECK(packing::exposed_fraction(6, 6, 0.6) == Approx(0.4));
  CHECK(packing::exposed_fraction(0, 6, 0.6) == 1.0);
  CHECK(packing::exposed_fraction(2, 4, 0.5) == Approx(0.75));
}

TEST_CASE("Two identical muscles in series share one current, U / (R_s + R_1 + R_2)") {
  const auto trace = simulate(
      bundle_yaml(2,
                  "  packing: {layout: hexagonal, pitch: 1.5 mm}\n"
                  "  thermal: {shielding: 0}\n"
                  "  electrical: {wiring: series, voltage: 6 V, series_resistance: 0.5 ohm}\n",
                  100.0));
  const auto& [i0, i1, r0, r1] = two_members(trace);
  for (std::size_t s = 0; s < i0.size(); ++s) {
    CHECK(i0[s] == i1[s]);
    CHECK(i0[s] == Approx(6.0 / (0.5 + r0[s] + r1[s])).epsilon(1e-14));
    CHECK(trace["bundle/supply/current"][s] == i0[s]);
  }
  // They heat: the current falls as both resistances rise, equally.
  CHECK(r0.back() > kR0 * 1.05);
  CHECK(r0.back() == r1.back());
}

TEST_CASE("Muscles in parallel share the current in the inverse ratio of their resistances") {
  // A resistance spread makes the two unequal; heating moves both R(T).
  const auto trace = simulate(
      bundle_yaml(2,
                  "  packing: {layout: hexagonal, pitch: 1.5 mm}\n"
                  "  thermal: {shielding: 0}\n"
                  "  spread: {resistance.resistance: {distribution: uniform, relative: 0.3}}\n"
                  "  electrical: {wiring: parallel, current: 0.4 A}\n",
                  100.0));
  const auto& [i0, i1, r0, r1] = two_members(trace);
  REQUIRE(std::abs(r0.front() / r1.front() - 1.0) > 0.01);  // the spread made them differ
  for (std::size_t s = 0; s < i0.size(); ++s) {
    CHECK(i0[s] / i1[s] == Approx(r1[s] / r0[s]).epsilon(1e-13));
    CHECK(i0[s] + i1[s] == Approx(0.4).epsilon(1e-14));
    // Both see the bundle's voltage.
    CHECK(i0[s] * r0[s] == Approx(trace["bundle/supply/voltage"][s]).epsilon(1e-14));
  }
}

TEST_CASE("An inner muscle runs hotter than an outer one by the ratio of their conductances") {
  // Seven muscles, hexagonal: the centre is surrounded (6 neighbours), each outer one has 3.
  // Equal power, no contact conduction, no radiation, no fan: in steady state
  // dT_i = P / (hA f_i), f = 1 - shielding n / 6, so dT_centre / dT_outer = f_outer / f_centre.
  const double shielding = 0.6, power = 0.05;
  const auto trace = simulate(
      bundle_yaml(7,
                  "  packing: {layout: hexagonal, pitch: 1.5 mm}\n"
                  "  thermal: {shielding: 0.6}\n"
                  "  electrical: {wiring: individual, drive: {mode: power, power: 0.05 W}}\n"));
  const double f_centre = 1.0 - shielding, f_outer = 1.0 - shielding * 3.0 / 6.0;
  // To within the temperature's absolute tolerance, 1e-6 K (32 time constants have passed).
  const double rise_centre = trace[member(0, "/temperature")].back() - kAmbient;
  CHECK(rise_centre == Approx(power / (kConductance * f_centre)).margin(1e-6));
  for (int k = 1; k < 7; ++k) {
    const double rise = trace[member(k, "/temperature")].back() - kAmbient;
    CHECK(rise == Approx(power / (kConductance * f_outer)).margin(1e-6));
    CHECK(rise_centre / rise == Approx(f_outer / f_centre).epsilon(1e-6 / rise));
  }
  // The members' drives are recorded together.
  CHECK(trace[member(3, "/drive/power")].back() == power);
}

TEST_CASE("Contact conduction between neighbours moves heat and loses none") {
  const auto trace = simulate(
      bundle_yaml(7,
                  "  packing: {layout: hexagonal, pitch: 1.5 mm}\n"
                  "  thermal: {shielding: 0.6, contact_conductance: 1 mW/K}\n"
                  "  electrical: {wiring: individual, drive: {mode: power, power: 0.05 W}}\n"));
  const auto& centre = trace[member(0, "/packing/to_neighbours")];
  for (std::size_t s = 0; s < centre.size(); ++s) {
    double sum = 0.0, scale = 0.0;
    for (int k = 0; k < 7; ++k) {
      sum += trace[member(k, "/packing/to_neighbours")][s];
      scale += std::abs(trace[member(k, "/packing/to_neighbours")][s]);
    }
    CHECK(std::abs(sum) <= 1e-15 + 1e-14 * scale);
  }
  // The hot centre gives heat to its ring: 1 mW/K times the six differences.
  double differences = 0.0;
  for (int k = 1; k < 7; ++k)
    differences +=
        trace[member(0, "/temperature")].back() - trace[member(k, "/temperature")].back();
  CHECK(centre.back() > 0.0);
  CHECK(centre.back() == Approx(1.0e-3 * differences).epsilon(1e-12));
}

TEST_CASE("Over a whole bundle, electrical energy in equals stored heat plus losses") {
  // Parallel wiring behind a series resistance, a fan, contact conduction and radiation: every
  // path of heat at once. The supply integrates what its source gives and what R_s dissipates;
  // each thermal node integrates its heat in and out.
  const std::string yaml = bundle_yaml(
      7,
      "  packing: {layout: hexagonal, pitch: 1.5 mm}\n"
      "  thermal: {shielding: 0.5, contact_conductance: 1 mW/K, fan: {conductance: 3 mW/K, "
      "speed: {type: steps, initial: 0, times: [60 s], values: [0.8]}}}\n"
      "  spread: {thermal.heat_capacity: {distribution: normal, relative: 0.1}}\n"
      "  electrical: {wiring: parallel, voltage: {type: steps, initial: 1.5 V, times: [120 s], "
      "values: [0.8 V]}, series_resistance: 0.3 ohm, energy_accounting: true}\n",
      200.0, ", radiation: {emissivity: 0.9, area: 1 cm^2}, energy_accounting: true");
  // The shared supply couples every member's current to all resistances: a dense block, which
  // GMRES leaves to its iterations (the preconditioner holds each member alone).
  const std::string solver = GENERATE("dense", "gmres");
  const Scenario scenario = scenario_from_text(yaml, {"solver.linear_solver=" + solver});
  Context context = scenario.make_context();
  scenario.system->prepare(context);
  const auto trace = simulate(scenario);
  const double supplied = trace["bundle/supply/energy"].back();
  const double in_series_resistance = trace["bundle/supply/series_heat"].back();
  double stored = 0.0, lost = 0.0, heated = 0.0;
  for (int k = 0; k < 7; ++k) {
    const double capacity =
        context.parameter("bundle/m" + std::to_string(k) + ".thermal.heat_capacity");
    stored += capacity * (trace[member(k, "/temperature")].back() - kAmbient);
    lost += trace[member(k, "/heat_lost")].back();
    heated += trace[member(k, "/heat_in")].back();
  }
  CHECK(supplied > 10.0);  // J: a real heating programme, not a trivial balance
  CHECK(in_series_resistance > 0.01 * supplied);
  CHECK(heated + in_series_resistance == Approx(supplied).epsilon(1e-7));
  CHECK(stored + lost + in_series_resistance == Approx(supplied).epsilon(1e-7));
}

TEST_CASE(
    "A parallel bundle of iron heaters self-balances; in series at constant current it runs away") {
  // Two muscles whose convection differs by the spread. Equal power would heat them in the
  // ratio of their conductances; on a voltage source the hotter one draws less (R rises), on a
  // current source more. Steady states by hand, with R = R0 (1 + alpha dT):
  //   parallel, U:  G dT = U^2 / (R0 (1 + alpha dT))  ->  alpha G dT^2 + G dT - U^2 / R0 = 0,
  //   series, I:    G dT = I^2 R0 (1 + alpha dT)       ->  dT = I^2 R0 / (G - alpha I^2 R0),
  // which has no steady state once alpha I^2 R0 >= G: thermal runaway.
  const std::string spread =
      "  packing: {layout: hexagonal, pitch: 1.5 mm}\n"
      "  thermal: {shielding: 0}\n"
      "  spread: {thermal.conductance: {distribution: uniform, relative: 0.4}}\n";
  // Seed 2 draws conductances 30 % apart.
  const auto with_seed = [](const std::string& yaml) {
    return replaced(yaml, "seed: 3", "seed: 2");
  };
  const Scenario parallel_scenario = scenario_from_text(
      with_seed(bundle_yaml(2, spread + "  electrical: {wiring: parallel, voltage: 1 V}\n")));
  Context context = parallel_scenario.make_context();
  parallel_scenario.system->prepare(context);
  const double g0 = context.parameter("bundle/m0.thermal.conductance");
  const double g1 = context.parameter("bundle/m1.thermal.conductance");
  REQUIRE(std::abs(g0 / g1 - 1.0) > 0.2);

  const auto parallel = simulate(parallel_scenario);
  const double voltage = 1.0;
  for (int k = 0; k < 2; ++k) {
    const double g = k == 0 ? g0 : g1;
    const double rise =
        (-g + std::sqrt(g * g + 4.0 * kAlpha * g * voltage * voltage / kR0)) / (2.0 * kAlpha * g);
    CHECK(parallel[member(k, "/temperature")].back() - kAmbient == Approx(rise).epsilon(1e-8));
  }
  const double parallel_ratio = (parallel[member(0, "/temperature")].back() - kAmbient) /
                                (parallel[member(1, "/temperature")].back() - kAmbient);

  // The series current puts the better-cooled muscle at a steady state and the other past
  // the runaway threshold alpha I^2 R0 = G.
  const double g_low = std::min(g0, g1), g_high = std::max(g0, g1);
  const double current = std::sqrt(0.5 * (g_low + g_high) / (kAlpha * kR0));
  const auto series = simulate(with_seed(bundle_yaml(
      2, spread + "  electrical: {wiring: series, current: " + number(current) + " A}\n", 400.0)));
  const int stable = g0 > g1 ? 0 : 1;
  const double settled = current * current * kR0 / (g_high - kAlpha * current * current * kR0);
  CHECK(series[member(stable, "/temperature")].back() - kAmbient == Approx(settled).epsilon(1e-8));
  const auto& runaway = series[member(1 - stable, "/temperature")];
  // Past the threshold C dT' = I^2 R0 + (alpha I^2 R0 - G) dT grows without bound:
  // dT(t) = a (exp(r t) - 1), r = (alpha I^2 R0 - G) / C, a = I^2 R0 / (alpha I^2 R0 - G).
  // Checked over the first 10 s, while the muscle is still at temperatures it could survive.
  const double excess = kAlpha * current * current * kR0 - g_low;
  const double rate = excess / kCapacity, scale = current * current * kR0 / excess;
  for (std::size_t s = 1; s <= 10; ++s) {
    const double t = static_cast<double>(s);
    CHECK(runaway[s] - kAmbient == Approx(scale * std::expm1(rate * t)).epsilon(1e-6));
  }
  CHECK(runaway.back() - kAmbient > 10.0 * settled);

  // Equal power would give the ratio g_high / g_low either way; parallel narrows it.
  const double equal_power_ratio = g1 / g0;
  CHECK(std::abs(std::log(parallel_ratio)) < std::abs(std::log(equal_power_ratio)));
}

TEST_CASE("A bundle's parameter spread is seeded: the same seed gives the same bundle") {
  const std::string yaml =
      bundle_yaml(200,
                  "  packing: {layout: square, pitch: 1.5 mm}\n"
                  "  thermal: {shielding: 0.3}\n"
                  "  spread: {mechanics.k1: {distribution: normal, relative: 0.1}}\n"
                  "  electrical: {wiring: individual, drive: {mode: power, power: 0.05 W}}\n",
                  1.0);
  const auto factors = [](const Scenario& scenario) {
    Context context = scenario.make_context();
    scenario.system->prepare(context);
    std::vector<double> values;
    for (int k = 0; k < 200; ++k) {
      std::string id = std::to_string(k);
      id.insert(0, 3 - id.size(), '0');
      values.push_back(context.parameter("bundle/m" + id + ".mechanics.k1") / 10.8);
    }
    return values;
  };
  const auto first = factors(scenario_from_text(yaml));
  const auto again = factors(scenario_from_text(yaml));
  const auto other = factors(scenario_from_text(replaced(yaml, "seed: 3", "seed: 4")));
  CHECK(bitwise_equal(first, again));
  CHECK(!bitwise_equal(first, other));
  // No two members alike; the sample's mean and spread those of the distribution (N(1, 0.1)
  // truncated at 3 sigma: standard deviation 0.0986); bounds within 5 standard errors.
  const double mean = std::accumulate(first.begin(), first.end(), 0.0) / 200.0;
  double variance = 0.0;
  for (double f : first) variance += (f - mean) * (f - mean) / 199.0;
  CHECK(std::abs(mean - 1.0) < 5.0 * 0.1 / std::sqrt(200.0));
  CHECK(std::sqrt(variance) == Approx(0.0986).margin(5.0 * 0.0986 / std::sqrt(2.0 * 199.0)));
  CHECK(*std::min_element(first.begin(), first.end()) >= 0.7);
  CHECK(*std::max_element(first.begin(), first.end()) <= 1.3);
  auto sorted = first;
  std::sort(sorted.begin(), sorted.end());
  CHECK(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end());
}

TEST_CASE("A bundle records each output once, as a (time x member) matrix naming its members") {
  const Scenario scenario = scenario_from_text(
      bundle_yaml(12,
                  "  packing: {layout: square, pitch: 1.5 mm}\n"
                  "  thermal: {shielding: 0.3}\n"
                  "  spread: {mechanics.k1: {distribution: normal, relative: 0.1}}\n"
                  "  electrical: {wiring: individual, drive: {mode: power, power: 0.05 W}}\n",
                  10.0));
  const std::string path = (std::filesystem::temp_directory_path() / "tcpmsim_bundle.h5").string();
  run_scenario(scenario, path);
  H5::H5File file(path, H5F_ACC_RDONLY);
  H5::DataSet temperature = file.openDataSet("/bundle/temperature");
  hsize_t dims[2];
  REQUIRE(temperature.getSpace().getSimpleExtentNdims() == 2);
  temperature.getSpace().getSimpleExtentDims(dims);
  CHECK(dims[0] == 11);
  CHECK(dims[1] == 12);
  H5::Attribute members = temperature.openAttribute("members");
  CHECK(members.getSpace().getSimpleExtentNpoints() == 12);
  std::vector<char*> names(12);
  members.read(members.getStrType(), names.data());
  CHECK(std::string(names[0]) == "m00");
  CHECK(std::string(names[11]) == "m11");
  H5Dvlen_reclaim(members.getStrType().getId(), members.getSpace().getId(), H5P_DEFAULT,
                  names.data());
  CHECK(file.nameExists("/bundle/drive/power"));
  // The packing is kept beside the traces: a square of 12 from the centre out.
  std::vector<double> neighbours(12);
  file.openDataSet("/bundle/neighbours").read(neighbours.data(), H5::PredType::NATIVE_DOUBLE);
  const auto section = packing::cross_section(PackingLayout::square, 12, 1.5e-3);
  for (std::size_t k = 0; k < 12; ++k)
    CHECK(neighbours[k] == static_cast<double>(section.neighbours[k].size()));
  // So are the members' spread factors, which make their parameters.
  std::vector<double> factors(12);
  file.openDataSet("/bundle/spread.mechanics.k1").read(factors.data(), H5::PredType::NATIVE_DOUBLE);
  Context context = scenario.make_context();
  scenario.system->prepare(context);
  for (std::size_t k = 0; k < 12; ++k) {
    const std::string id = (k < 10 ? "m0" : "m") + std::to_string(k);
    CHECK(context.parameter("bundle/" + id + ".mechanics.k1") == 10.8 * factors[k]);
  }
  CHECK(!file.nameExists("/bundle/m00"));
  // The members' alike signals are described once.
  CHECK(file.nameExists("/inputs/bundle/drive.power"));
  file.close();
  std::filesystem::remove(path);
}

TEST_CASE("Bad bundle sections are refused with one clear message") {
  const std::string base = bundle_yaml(3,
                                       "  packing: {layout: hexagonal, pitch: 1.5 mm}\n"
                                       "  thermal: {shielding: 0.3}\n"
                                       "  electrical: {wiring: parallel, voltage: 1 V}\n",
                                       10.0);
  CHECK_THAT(config_error(replaced(base, "wiring: parallel, voltage: 1 V",
                                   "wiring: parallel, voltage: 1 V, current: 1 A")),
             Catch::Contains("exactly one of voltage, current or power"));
  // Issue 31: a hundred thousand members took minutes and 3 GB to build before any run.
  CHECK_THAT(config_error(base, {"bundle.count=100000"}),
             Catch::Contains("command line (--set bundle.count=100000): error: bundle.count: "
                             "expected an integer, a value in [1, 10000] (the limit: each member "
                             "is a muscle with its own components: half a millisecond and 30 kB "
                             "a member to build), got '100000'"));
  CHECK_THAT(config_error(replaced(base, "  thermal: {shielding: 0.3}\n",
                                   "  thermal: {shielding: 0.3}\n  spread: {mechanics.k9: "
                                   "{distribution: normal, relative: 0.1}}\n")),
             Catch::Contains("no numeric parameter 'mechanics.k9'"));
  CHECK_THAT(config_error(replaced(base, "  thermal: {shielding: 0.3}\n",
                                   "  thermal: {shielding: 0.3}\n  spread: {mechanics.k1: "
                                   "{distribution: normal, relative: 0.5}}\n")),
             Catch::Contains("relative"));
  CHECK_THAT(
      config_error(replaced(base, "wiring: parallel, voltage: 1 V",
                            "wiring: individual, drive: {muscle: m0, mode: power, power: 1 W}")),
      Catch::Contains("remove 'muscle'"));
  CHECK_THAT(config_error(
                 replaced(base, "voltage: 1 V", "voltage: 1 V, drive: {mode: power, power: 1 W}")),
             Catch::Contains("wiring: individual"));
  CHECK_THAT(config_error(replaced(base, "bundle: bundle,", "bundle: bundle, muscle: x,")),
             Catch::Contains("either 'bundle' or 'muscle'"));
  CHECK_THAT(config_error(replaced(base, "bundle: bundle,", "bundle: bundel,")),
             Catch::Contains("did you mean 'bundle'"));
  CHECK_THAT(config_error(replaced(base, "{shielding: 0.3}",
                                   "{shielding: 0.3, fan: {conductance: 1 mW/K, speed: 1.5}}")),
             Catch::Contains("fan speed between 0"));
  CHECK_THAT(config_error(replaced(base, "{shielding: 0.3}", "{shielding: 1.3}")),
             Catch::Contains("shielding"));
  CHECK_THAT(config_error(replaced(base, "count: 3", "count: 0")), Catch::Contains("count"));
  const std::string reduced =
      replaced(replaced(base,
                        "    thermal: {heat_capacity: 0.01 J/K, conductance: 2 mW/K, "
                        "ambient_temperature: 23 degC}\n",
                        ""),
               "{form: physical, force_per_kelvin: 4 mN/K, reference_temperature: 23 degC}",
               "{form: reduced, kappa_P: 7.2e-3 N/J, kappa_c: 131.6e-3 1/s, ambient_temperature: "
               "23 degC, force_per_kelvin: 4 mN/K}");
  CHECK_THAT(config_error(reduced), Catch::Contains("thermal node"));
}

TEST_CASE("A member whose signal a run changes has its own description under /inputs") {
  const Scenario scenario = scenario_from_text(
      bundle_yaml(3,
                  "  packing: {layout: square, pitch: 1.5 mm}\n"
                  "  thermal: {shielding: 0.3}\n"
                  "  electrical: {wiring: individual, drive: {mode: power, power: 0.05 W}}\n",
                  5.0));
  Context context = scenario.make_context();
  context.set_parameter("bundle/m1/drive.power", 0.2);
  const std::string path =
      (std::filesystem::temp_directory_path() / "tcpmsim_bundle_inputs.h5").string();
  run_scenario(scenario, context, path);
  H5::H5File file(path, H5F_ACC_RDONLY);
  CHECK(!file.nameExists("/inputs/bundle/drive.power"));
  for (const char* id : {"m0", "m1", "m2"})
    CHECK(file.nameExists("/inputs/bundle/" + std::string(id) + "/drive.power"));
  // The run used the changed power: the member's drive recorded it.
  std::vector<double> power(6 * 3);
  file.openDataSet("/bundle/drive/power").read(power.data(), H5::PredType::NATIVE_DOUBLE);
  CHECK(power[3 * 5 + 1] == 0.2);
  CHECK(power[3 * 5 + 0] == 0.05);
  // ...and heated with it: m1 and m2 sit alike (one neighbour each, no contact conduction), so
  // from the same start their rises stay in the ratio of their powers, 0.2 / 0.05.
  std::vector<double> temperature(6 * 3);
  file.openDataSet("/bundle/temperature").read(temperature.data(), H5::PredType::NATIVE_DOUBLE);
  CHECK((temperature[3 * 5 + 1] - kAmbient) / (temperature[3 * 5 + 2] - kAmbient) ==
        Approx(4.0).epsilon(1e-9));
  file.close();
  std::filesystem::remove(path);
}

TEST_CASE("Contact conduction and the fan set the steady state of a packed bundle") {
  // Seven muscles at equal power. By symmetry the ring is at one temperature, so with
  // x = T - T_amb and the forced conductance f G_f s on top of the free f hA:
  //   centre (6 neighbours):  P = f_c (hA + G_f s) x_c + 6 G_c (x_c - x_o)
  //   ring (centre + 2 ring): P = f_o (hA + G_f s) x_o + G_c (x_o - x_c)
  const double shielding = 0.6, contact = 1.0e-3, fan = 3.0e-3, speed = 0.5, power = 0.05;
  const auto trace = simulate(bundle_yaml(
      7,
      "  packing: {layout: hexagonal, pitch: 1.5 mm}\n"
      "  thermal: {shielding: 0.6, contact_conductance: 1 mW/K, fan: {conductance: 3 mW/K, "
      "speed: 0.5}}\n"
      "  electrical: {wiring: individual, drive: {mode: power, power: 0.05 W}}\n"));
  const double f_c = 1.0 - shielding, f_o = 1.0 - shielding * 3.0 / 6.0;
  const double a = f_c * (kConductance + fan * speed) + 6.0 * contact, b = -6.0 * contact;
  const double c = -contact, d = f_o * (kConductance + fan * speed) + contact;
  const double determinant = a * d - b * c;
  const double centre = power * (d - b) / determinant, ring = power * (a - c) / determinant;
  CHECK(trace[member(0, "/temperature")].back() - kAmbient == Approx(centre).margin(1e-6));
  CHECK(trace[member(0, "/packing/to_fan")].back() ==
        Approx(f_c * fan * speed * centre).epsilon(1e-6));
  for (int k = 1; k < 7; ++k)
    CHECK(trace[member(k, "/temperature")].back() - kAmbient == Approx(ring).margin(1e-6));
  // Without the contact, the centre would be f_o / f_c = 1.75 times as warm; it spreads its
  // heat into the ring.
  CHECK(centre / ring < 0.95 * f_o / f_c);
}

TEST_CASE("A --set of the bundle's muscle section reaches every member") {
  const std::string yaml = bundle_yaml(3,
                                       "  packing: {layout: square, pitch: 1.5 mm}\n"
                                       "  thermal: {shielding: 0.3}\n"
                                       "  electrical: {wiring: parallel, voltage: 1 V}\n",
                                       5.0);
  const Scenario scenario = load_scenario_text(
      yaml, "bundle.yaml", {"bundle.muscle.mechanics.k1=30 N/m"}, shared_units());
  Context context = scenario.make_context();
  scenario.system->prepare(context);
  for (const char* id : {"m0", "m1", "m2"})
    CHECK(context.parameter("bundle/" + std::string(id) + ".mechanics.k1") == 30.0);
}

TEST_CASE("A one-member bundle is still recorded as a (time x member) matrix") {
  const Scenario scenario = scenario_from_text(
      bundle_yaml(1,
                  "  packing: {layout: square, pitch: 1.5 mm}\n"
                  "  thermal: {shielding: 0.3}\n"
                  "  electrical: {wiring: individual, drive: {mode: power, power: 0.05 W}}\n",
                  5.0));
  const std::string path =
      (std::filesystem::temp_directory_path() / "tcpmsim_bundle_1.h5").string();
  run_scenario(scenario, path);
  H5::H5File file(path, H5F_ACC_RDONLY);
  CHECK(file.openDataSet("/bundle/temperature").getSpace().getSimpleExtentNdims() == 2);
  file.close();
  std::filesystem::remove(path);
}

TEST_CASE("A run cannot give a bundle's supply a negative power or its fan a speed above 1") {
  const Scenario scenario = scenario_from_text(
      bundle_yaml(2,
                  "  packing: {layout: square, pitch: 1.5 mm}\n"
                  "  thermal: {shielding: 0.3, fan: {conductance: 1 mW/K, speed: 0.5}}\n"
                  "  electrical: {wiring: parallel, power: 0.2 W}\n",
                  5.0));
  Context negative = scenario.make_context();
  negative.set_parameter("bundle.electrical.power", -0.1);
  CHECK_THROWS_WITH(scenario.system->prepare(negative), Catch::Contains("at or above 0 W"));
  Context fast = scenario.make_context();
  fast.set_parameter("bundle.thermal.fan.speed", 1.5);
  CHECK_THROWS_WITH(scenario.system->prepare(fast), Catch::Contains("fan speed between 0"));
  // Assembled without contact conduction, its members are not coupled: a run cannot add it.
  Context touching = scenario.make_context();
  touching.set_parameter("bundle.thermal.contact_conductance", 1e-3);
  CHECK_THROWS_WITH(scenario.system->prepare(touching),
                    Catch::Contains("assembled without contact conduction"));
}

TEST_CASE("Without contact conduction the members' temperatures stay out of each other's rows") {
  const auto pattern_size = [](const std::string& thermal) {
    return scenario_from_text(
               bundle_yaml(7,
                           "  packing: {layout: hexagonal, pitch: 1.5 mm}\n  thermal: " + thermal +
                               "\n  electrical: {wiring: individual, drive: {mode: power, "
                               "power: 0.05 W}}\n",
                           5.0))
        .system->jacobian_pattern()
        .non_zeros();
  };
  // Two states per member; with contact each temperature row reads its neighbours' as well:
  // 12 touching pairs of the hexagon of seven, both ways.
  CHECK(pattern_size("{shielding: 0.6, contact_conductance: 0 W/K}") -
            pattern_size("{shielding: 0.6}") ==
        24);
}

namespace {
// One muscle (nothing shields it) heated with a constant power P, its fan (G_f) under a fan
// controller at the reference T_amb + rise.
std::string cooled_bundle(int count, double rise, const std::string& measure = "hottest",
                          const std::string& fan = "speed: controller") {
  return bundle_yaml(count,
                     "  packing: {layout: hexagonal, pitch: 1.5 mm}\n"
                     "  thermal: {shielding: 0.6, fan: {conductance: 4 mW/K, " +
                         fan +
                         "}}\n"
                         "  electrical: {wiring: individual, drive: {mode: power, power: 0.2 "
                         "W}}\n",
                     200.0) +
         "controller: {type: fan, bundle: bundle, measure: " + measure +
         ", reference: " + number(kAmbient + rise) +
         " K, gains: {proportional: 0.5 1/K, integral_time: 5 s}, sample_period: 0.1 s}\n";
}
}  // namespace

TEST_CASE("A fan controller holds a muscle at its reference with the speed the balance asks") {
  // Steady state: P = (hA + G_f s)(T_ref - T_amb), so s = (P / 40 K - hA) / G_f = 0.75.
  const auto trace = simulate(cooled_bundle(1, 40.0));
  CHECK(trace[member(0, "/temperature")].back() - kAmbient == Approx(40.0).margin(1e-6));
  CHECK(trace["controller/fan_speed"].back() == Approx((0.2 / 40.0 - kConductance) / 4e-3));
  CHECK(trace["bundle/air/fan_speed"].back() == trace["controller/fan_speed"].back());
  // Heated from ambient, it starts with the fan off.
  CHECK(trace["controller/fan_speed"].front() == 0.0);
}

TEST_CASE("An unreachable reference runs the fan at full speed, no further") {
  // 10 K is below what full cooling reaches: T - T_amb = P / (hA + G_f) = 33.3 K.
  const auto trace = simulate(cooled_bundle(1, 10.0));
  CHECK(trace["controller/fan_speed"].back() == 1.0);
  CHECK(trace[member(0, "/temperature")].back() - kAmbient ==
        Approx(0.2 / (kConductance + 4e-3)).margin(1e-6));
}

TEST_CASE("A fan controller regulates the hottest member, or the members' mean") {
  // The centre keeps f = 0.4 of hA and G_f: at 100 K, 0.4 (hA + G_f s) = P / 100 K, s = 0.75.
  const auto hottest = simulate(cooled_bundle(7, 100.0));
  // The shielded centre is the hottest; the ring stays below the reference.
  CHECK(hottest[member(0, "/temperature")].back() - kAmbient == Approx(100.0).margin(1e-6));
  CHECK(hottest["controller/fan_speed"].back() == Approx(0.75));
  // The ring (f = 1 - 0.6 * 3/6 = 0.7, no contact conduction) under the same fan.
  for (int k = 1; k < 7; ++k)
    CHECK(hottest[member(k, "/temperature")].back() - kAmbient ==
          Approx(0.2 / (0.7 * (kConductance + 4e-3 * 0.75))).epsilon(1e-6));
  for (int k = 1; k < 7; ++k)
    CHECK(hottest[member(k, "/temperature")].back() < hottest[member(0, "/temperature")].back());
  const auto mean = simulate(cooled_bundle(7, 100.0, "mean"));
  double sum = 0.0;
  for (int k = 0; k < 7; ++k) sum += mean[member(k, "/temperature")].back();
  CHECK(sum / 7.0 - kAmbient == Approx(100.0).margin(1e-6));
  CHECK(mean["controller/measured_temperature"].back() == Approx(sum / 7.0).epsilon(1e-9));
  // Each member's rise is P / (f (hA + G_f s)), so the mean is 100 K where
  // hA + G_f s = P (1/0.4 + 6/0.7) / 7 / 100 K.
  const double cooling = 0.2 * (1.0 / 0.4 + 6.0 / 0.7) / 7.0 / 100.0;
  CHECK(mean["controller/fan_speed"].back() == Approx((cooling - kConductance) / 4e-3));
}

TEST_CASE("A commanded fan needs exactly its controller") {
  CHECK_THAT(config_error(bundle_yaml(2,
                                      "  packing: {layout: square, pitch: 1.5 mm}\n"
                                      "  thermal: {shielding: 0.3, fan: {conductance: 1 mW/K, "
                                      "speed: controller}}\n"
                                      "  electrical: {wiring: parallel, voltage: 1 V}\n")),
             Catch::Contains("bundle.thermal.fan.speed: no controller commands this fan"));
  CHECK_THAT(config_error(cooled_bundle(2, 40.0, "hottest", "speed: 0.5")),
             Catch::Contains("controller.bundle: the fan of bundle has a prescribed speed"));
  CHECK_THAT(config_error(cooled_bundle(2, 40.0), {"controller.gains.proportional=-0.5 1/K"}),
             Catch::Contains("expected a positive gain"));
}

TEST_CASE("Bundles of 20 states or more get the sparse solver with warm restarts by default") {
  // Two states per member here (temperature, dashpot): 10 members make 20.
  const auto with = [](int count, const std::string& solver) {
    std::string yaml = bundle_yaml(count,
                                   "  packing: {layout: hexagonal, pitch: 1.5 mm}\n"
                                   "  thermal: {shielding: 0.6}\n"
                                   "  electrical: {wiring: individual, drive: {mode: power, "
                                   "power: 0.05 W}}\n",
                                   5.0);
    return scenario_from_text(replaced(yaml, "solver: {rtol: 1.0e-9}", solver));
  };
  const Scenario small = with(9, "solver: {rtol: 1.0e-9}");
  const Scenario large = with(10, "solver: {rtol: 1.0e-9}");
  const Scenario bare = with(10, "");
  REQUIRE(large.system->state_size() == 20);
  CHECK(small.solver.linear_solver == LinearSolverKind::dense);
  CHECK(small.solver.restart == RestartKind::cold);
  for (const Scenario* scenario : {&large, &bare}) {
    CHECK(scenario->solver.linear_solver == LinearSolverKind::klu);
    CHECK(scenario->solver.restart == RestartKind::warm);
  }
  // Adams needs no linear solver; an explicit choice stands.
  CHECK(with(10, "solver: {method: adams}").solver.linear_solver == LinearSolverKind::dense);
  CHECK(with(10, "solver: {linear_solver: dense}").solver.linear_solver == LinearSolverKind::dense);
  // The resolved configuration names the solver the run used.
  CHECK_THAT(large.resolved_yaml, Catch::Contains("linear_solver: klu"));
}

TEST_CASE(
    "A bundle hanging a mass gets its dense load row by the chain rule, as dense differences") {
  // The mass's acceleration reads every member's force: a dense Jacobian row. KLU's differences
  // apportion it through the force signals instead of giving each column a group of its own.
  const std::string yaml = replaced(
      bundle_yaml(20,
                  "  packing: {layout: hexagonal, pitch: 1.5 mm}\n"
                  "  thermal: {shielding: 0.6, contact_conductance: 0.5 mW/K}\n"
                  "  electrical: {wiring: individual, drive: {mode: power, power: {type: steps, "
                  "initial: 0.05 W, times: [10 s], values: [0.1 W]}}}\n",
                  30.0),
      "load: {type: deflection, bundle: bundle, deflection: 20 mm}",
      "load: {type: hanging_mass, bundle: bundle, mass: 0.2 kg, damping: 0.5 N*s/m, "
      "initial_deflection: equilibrium}");
  const auto run = [&](const char* solver) {
    return simulate(yaml, {std::string("solver.linear_solver=") + solver, "solver.restart=cold"});
  };
  const auto sparse = run("klu"), dense = run("dense");
  REQUIRE(sparse.statistics.jacobian_evaluations > 0);
  // The same Jacobian up to the differences' own error (their increments differ): the Newton
  // iteration converges alike, and the trajectories agree within the tolerance (50 rtol of the
  // 0.05 m deflection). A row missing its chain-rule entries would cost iterations and failures.
  CHECK(std::abs(sparse.statistics.steps - dense.statistics.steps) < 0.02 * dense.statistics.steps);
  CHECK(sparse.statistics.nonlinear_iterations < 1.05 * dense.statistics.nonlinear_iterations);
  CHECK(sparse.statistics.nonlinear_convergence_failures <=
        dense.statistics.nonlinear_convergence_failures + 2);
  CHECK(max_abs_difference(sparse["load/deflection"], dense["load/deflection"]) <
        allowed(1e-9, 0.05));
  // 42 states: dense differences take 42 evaluations per Jacobian, the chain rule a handful.
  CHECK(dense.statistics.rhs_evaluations_for_jacobian ==
        42 * dense.statistics.jacobian_evaluations);
  CHECK(sparse.statistics.rhs_evaluations_for_jacobian <=
        12 * sparse.statistics.jacobian_evaluations);
}
