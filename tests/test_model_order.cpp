// How discover chooses a family's model order (identification/model_order.h): the higher orders
// of the families whose simplest member gave evidence.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "identification/model_order.h"

using namespace tcpmsim::fit;

namespace {

constexpr double kThreshold = 10.0;  // discover's default --bic-threshold

// A catalogue of three families: hysteresis (Dahl element, then an operator of 8 parameters),
// heating_dependent_convection (a boost, then a switched fan of 5) and ratchet (one member).
struct Catalogue {
  std::vector<EffectCandidate> tried;
  std::vector<CandidateOutcome> fitted;

  Catalogue() {
    add("hysteresis", 1, 2);                    // 0
    add("heating_dependent_convection", 1, 2);  // 1
    add("ratchet", 1, 2);                       // 2
    add("hysteresis", 4, 8);                    // 3
    add("heating_dependent_convection", 2, 5);  // 4
  }
  void add(const std::string& family, int order, std::size_t parameters) {
    EffectCandidate candidate;
    candidate.name = family;
    candidate.order = order;
    candidate.parameters.resize(parameters);
    tried.push_back(candidate);
    CandidateOutcome outcome;
    outcome.name = family;
    outcome.order = order;
    outcome.status = "fitted";
    fitted.push_back(outcome);
  }
  // Member k lowered the BIC by `drop`, significant or not.
  void scored(std::size_t k, double drop, bool significant) {
    fitted[k].delta_bic = -drop;
    fitted[k].significant = significant;
  }
  std::vector<std::size_t> higher(const std::vector<char>& finished) const {
    return higher_orders_to_try(families_of(tried), tried, fitted, finished, kThreshold);
  }
};

const std::vector<char> kFirstRoundDone = {1, 1, 1, 0, 0};

}  // namespace

TEST_CASE("A family is its simplest members and its higher orders, in the catalogue's order") {
  const Catalogue catalogue;
  const auto families = families_of(catalogue.tried);
  REQUIRE(families.size() == 3);
  CHECK(families[0].simplest == std::vector<std::size_t>{0});
  CHECK(families[0].higher == std::vector<std::size_t>{3});
  CHECK(families[1].simplest == std::vector<std::size_t>{1});
  CHECK(families[1].higher == std::vector<std::size_t>{4});
  CHECK(families[2].simplest == std::vector<std::size_t>{2});
  CHECK(families[2].higher.empty());
  CHECK(longest_first({0, 1, 4, 3}, catalogue.tried) == std::vector<std::size_t>{3, 4, 0, 1});
}

TEST_CASE("Higher orders are tried where their family's simplest member gave evidence") {
  Catalogue catalogue;
  SECTION("a significant drop opens its own family only") {
    catalogue.scored(0, 300.0, true);
    catalogue.scored(1, 5.0, false);
    catalogue.scored(2, 2.0, false);
    CHECK(catalogue.higher(kFirstRoundDone) == std::vector<std::size_t>{3});
  }
  SECTION("a drop below a tenth of the largest opens nothing, however far past the threshold") {
    catalogue.scored(0, 300.0, true);
    catalogue.scored(1, 29.0, false);
    catalogue.scored(2, 0.0, false);
    CHECK(catalogue.higher(kFirstRoundDone) == std::vector<std::size_t>{3});
    catalogue.scored(1, 30.0, false);
    CHECK(catalogue.higher(kFirstRoundDone) == std::vector<std::size_t>{3, 4});
  }
  SECTION("a failed fit is no evidence") {
    catalogue.scored(0, 300.0, true);
    catalogue.fitted[0].status = "failed";
    catalogue.scored(1, 50.0, false);
    CHECK(catalogue.higher(kFirstRoundDone) == std::vector<std::size_t>{4});
  }
  SECTION("a simplest member that never left zero size is no evidence") {
    catalogue.scored(0, 40.0, false);
    catalogue.scored(1, 0.0, false);
    catalogue.scored(2, 3.0, false);
    CHECK(catalogue.higher(kFirstRoundDone) == std::vector<std::size_t>{3});
  }
  SECTION("only finished members are read: a guess ahead while the first round runs") {
    catalogue.scored(0, 300.0, true);
    catalogue.scored(1, 50.0, false);
    CHECK(catalogue.higher({0, 1, 0, 0, 0}) == std::vector<std::size_t>{4});
    CHECK(catalogue.higher(kFirstRoundDone) == std::vector<std::size_t>{3, 4});
  }
}
