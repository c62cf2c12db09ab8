// Candidates the data do not tell apart (issue 28): a heat loss growing with the temperature
// rise and a convection boosted by a lagged copy of the power change a heating protocol's force
// in nearly the same way. Neither BIC difference of a few units is evidence then; the verdict
// names the commoner effect, the first of the group in the catalogue's order, and lists the rest.
#include <catch2/catch.hpp>

#include <cmath>

#include "identification/candidate_aliases.h"

using namespace tcpmsim;
using namespace tcpmsim::fit;

namespace {

const std::vector<std::string> kOrder{"slow_relaxation", "hysteresis", "nonlinear_convection",
                                      "thermal_lag", "heating_dependent_convection"};

// A significant candidate whose validation change is `shape` (one output, unit noise).
CandidateOutcome candidate(const std::string& name, double delta_bic, std::vector<double> shape) {
  CandidateOutcome outcome;
  outcome.name = name;
  outcome.status = "fitted";
  outcome.significant = true;
  outcome.delta_bic = delta_bic;
  outcome.validation_change = {std::move(shape)};
  return outcome;
}

// A smooth rise: what a loss ~ dT^2 takes from the force while the muscle heats.
std::vector<double> rise(double scale, double wobble = 0.0) {
  std::vector<double> values;
  for (int i = 0; i < 200; ++i) {
    const double t = i / 20.0;
    values.push_back(scale * (1.0 - std::exp(-t / 3.0)) + wobble * std::sin(7.0 * t));
  }
  return values;
}

std::vector<std::string> names(const std::vector<CandidateOutcome>& ranked) {
  std::vector<std::string> result;
  for (const auto& outcome : ranked) result.push_back(outcome.name);
  return result;
}

}  // namespace

TEST_CASE("The correlation of two changes is weighted by each output's noise") {
  const std::vector<std::vector<double>> a{{1, 0, 0}, {0, 0, 1}};
  CHECK(change_correlation(a, a, {1.0, 2.0}) == Approx(1.0));
  CHECK(change_correlation(a, {{0, 1, 0}, {0, 1, 0}}, {1.0, 1.0}) == 0.0);
  CHECK(change_correlation(a, {{0, 0, 0}, {0, 0, 0}}, {1.0, 1.0}) == 0.0);
  // b agrees with a on the first output only; a noisier second output weighs its disagreement
  // less: with noise s on it, the correlation is 1 / (1 + 1/s^2).
  const std::vector<std::vector<double>> b{{1, 0, 0}, {0, 0, -1}};
  CHECK(change_correlation(a, b, {1.0, 1.0}) == Approx(0.0));
  CHECK(change_correlation(a, b, {1.0, 3.0}) == Approx((1.0 - 1.0 / 9) / (1.0 + 1.0 / 9)));
}

TEST_CASE(
    "Of two significant candidates with the same change and a BIC difference below the "
    "threshold, the first in the catalogue's order is named, the other its alias") {
  std::vector<CandidateOutcome> ranked{
      candidate("heating_dependent_convection", -91.1, rise(2.0, 0.05)),
      candidate("nonlinear_convection", -82.2, rise(1.9)),
      candidate("hysteresis", -30.0, rise(-1.0, 1.0))};
  name_first_of_aliases(ranked, {1.0}, 10.0, 0.9, kOrder);
  CHECK(names(ranked) == std::vector<std::string>{"nonlinear_convection",
                                                  "heating_dependent_convection", "hysteresis"});
  REQUIRE(ranked.front().aliases.size() == 1);
  const auto& alias = ranked.front().aliases.front();
  CHECK(alias.name == "heating_dependent_convection");
  CHECK(alias.correlation > 0.99);
  CHECK(alias.delta_bic == Approx(-91.1 + 82.2));
}

TEST_CASE("Candidates the data tell apart keep the BIC's order") {
  SECTION("a BIC difference at the threshold is evidence") {
    std::vector<CandidateOutcome> ranked{
        candidate("heating_dependent_convection", -100.0, rise(2.0)),
        candidate("nonlinear_convection", -90.0, rise(2.0))};
    name_first_of_aliases(ranked, {1.0}, 10.0, 0.9, kOrder);
    CHECK(ranked.front().name == "heating_dependent_convection");
    CHECK(ranked.front().aliases.empty());
  }
  SECTION("changes of different shapes are different explanations") {
    std::vector<CandidateOutcome> ranked{
        candidate("heating_dependent_convection", -91.0, rise(2.0)),
        candidate("nonlinear_convection", -90.0, rise(0.1, 1.0))};
    name_first_of_aliases(ranked, {1.0}, 10.0, 0.9, kOrder);
    CHECK(ranked.front().name == "heating_dependent_convection");
    CHECK(ranked.front().aliases.empty());
  }
  SECTION("an insignificant or superseded candidate is no alias") {
    std::vector<CandidateOutcome> ranked{
        candidate("heating_dependent_convection", -91.0, rise(2.0)),
        candidate("nonlinear_convection", -90.0, rise(2.0)),
        candidate("slow_relaxation", -89.0, rise(2.0))};
    ranked[1].significant = false;
    ranked[2].superseded = true;
    name_first_of_aliases(ranked, {1.0}, 10.0, 0.9, kOrder);
    CHECK(ranked.front().name == "heating_dependent_convection");
    CHECK(ranked.front().aliases.empty());
  }
  SECTION("without a significant best there is no verdict to move") {
    std::vector<CandidateOutcome> ranked{candidate("heating_dependent_convection", -5.0, rise(2.0)),
                                         candidate("nonlinear_convection", -4.0, rise(2.0))};
    for (auto& outcome : ranked) outcome.significant = false;
    name_first_of_aliases(ranked, {1.0}, 10.0, 0.9, kOrder);
    CHECK(ranked.front().name == "heating_dependent_convection");
  }
}
