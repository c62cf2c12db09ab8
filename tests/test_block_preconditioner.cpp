// GMRES preconditioned by the Jacobian within members (sim/block_preconditioner.h): which
// entries the preconditioner leaves out, and that the Krylov solves reach the direct solver's
// solution on bundles whose members are coupled (contact conduction, a hanging mass).
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>

#include "sim/run.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {

// A hexagonal bundle of `count` muscles on their own power drives (a step at 10 s), with the
// `thermal` section given, on an imposed 20 mm.
std::string packed_bundle(int count, const std::string& thermal) {
  return "scenario: {name: packed, duration: 40 s, seed: 5}\n"
         "output: {rate: 2 Hz}\n"
         "solver: {rtol: 1.0e-8}\n"
         "bundle:\n"
         "  count: " +
         std::to_string(count) +
         "\n"
         "  packing: {layout: hexagonal, pitch: 1.5 mm}\n"
         "  muscle:\n"
         "    thermal: {heat_capacity: 0.01 J/K, conductance: 2 mW/K, ambient_temperature: 23 "
         "degC}\n"
         "    thermal_force: {form: physical, force_per_kelvin: 4 mN/K, reference_temperature: "
         "23 degC}\n"
         "    mechanics: {k1: 10.8 N/m, k2: 2.7 N/m, damping: 4.3 N*s/m, force_offset: 0.1 N}\n"
         "    resistance: 10 ohm\n"
         "    inductance: {lambda_l: 107.4 uH*mm, lambda_x: 61 mm, lambda_0: 2.67 uH}\n"
         "  spread: {thermal.conductance: {distribution: normal, relative: 0.2}}\n"
         "  thermal: " +
         thermal +
         "\n"
         "  electrical: {wiring: individual, drive: {mode: power, power: {type: steps, initial: "
         "0.05 W, times: [10 s], values: [0.15 W]}}}\n"
         "load: {type: deflection, bundle: bundle, deflection: 20 mm}\n";
}

const std::string kContact = "{shielding: 0.6, contact_conductance: 2 mW/K}";
const std::string kNoContact = "{shielding: 0.6}";

bool contains(const SparsityPattern& whole, const SparsityPattern& part) {
  for (int column = 0; column < part.size; ++column) {
    const auto& rows = whole.rows_of_column[static_cast<std::size_t>(column)];
    for (int row : part.rows_of_column[static_cast<std::size_t>(column)])
      if (!std::binary_search(rows.begin(), rows.end(), row)) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("The Jacobian within members leaves out exactly what couples members") {
  const Scenario touching = scenario_from_text(packed_bundle(7, kContact));
  const Scenario apart = scenario_from_text(packed_bundle(7, kNoContact));
  const auto whole = touching.system->jacobian_pattern();
  const auto within = touching.system->jacobian_pattern(JacobianEntries::within_members);
  // The hexagon of seven has 12 touching pairs: contact adds 24 entries, both ways, and the
  // within-members pattern is the bundle's without contact, entry for entry.
  CHECK(whole.non_zeros() - within.non_zeros() == 24);
  CHECK(contains(whole, within));
  CHECK(within.rows_of_column == apart.system->jacobian_pattern().rows_of_column);
  // Members that do not touch have nothing between them to leave out.
  CHECK(apart.system->jacobian_pattern(JacobianEntries::within_members).rows_of_column ==
        apart.system->jacobian_pattern().rows_of_column);
}

TEST_CASE("GMRES on the within-members preconditioner reaches KLU's solution") {
  const std::string load = GENERATE(
      std::string("load: {type: deflection, bundle: bundle, deflection: 20 mm}"),
      std::string("load: {type: hanging_mass, bundle: bundle, mass: 0.2 kg, damping: 0.5 N*s/m, "
                  "initial_deflection: equilibrium}"));
  const std::string yaml =
      replaced(packed_bundle(19, kContact),
               "load: {type: deflection, bundle: bundle, deflection: 20 mm}", load);
  const auto run = [&](const char* solver) {
    return simulate(yaml, {std::string("solver.linear_solver=") + solver});
  };
  const auto direct = run("klu"), krylov = run("gmres");
  // The Krylov solves are converged to CVODE's linear tolerance (a twentieth of the Newton
  // iteration's), so the Newton iterations, and with them the steps, follow the direct
  // solver's to a few percent; the trajectories agree within the tolerance. Contact moves heat
  // between members, which only GMRES's iterations resolve.
  REQUIRE(krylov.statistics.linear_iterations > 0);
  CHECK(direct.statistics.linear_iterations == 0);
  CHECK(std::abs(krylov.statistics.steps - direct.statistics.steps) <=
        0.05 * direct.statistics.steps);
  CHECK(krylov.statistics.nonlinear_convergence_failures <=
        direct.statistics.nonlinear_convergence_failures + 2);
  // Nineteen members are named m00 to m18: the centre, its ring, the outer ring.
  for (const char* name : {"m00", "m01", "m07", "m18"}) {
    const std::string temperature = std::string("bundle/") + name + "/temperature";
    CHECK(max_abs_difference(krylov[temperature], direct[temperature]) < allowed(1e-8, 400.0));
  }
  const auto& force = direct["load/force"];
  const double largest_force = std::max(*std::max_element(force.begin(), force.end()),
                                        -*std::min_element(force.begin(), force.end()));
  CHECK(max_abs_difference(krylov["load/force"], force) < allowed(1e-8, largest_force));
  // The centre runs hotter than the outer ring in both: contact shares, shielding holds.
  CHECK(krylov["bundle/m00/temperature"].back() > krylov["bundle/m18/temperature"].back());
}

TEST_CASE("A scenario may choose GMRES by name, and it restarts warm unless told otherwise") {
  const Scenario chosen =
      scenario_from_text(packed_bundle(7, kContact), {"solver.linear_solver=gmres"});
  CHECK(chosen.solver.linear_solver == LinearSolverKind::gmres);
  CHECK(chosen.solver.restart == RestartKind::warm);
  CHECK_THAT(chosen.resolved_yaml, Catch::Contains("linear_solver: gmres"));
  CHECK_THAT(config_error(packed_bundle(7, kContact), {"solver.linear_solver=bicgstab"}),
             Catch::Contains("expected one of dense, band, klu, gmres"));
}
