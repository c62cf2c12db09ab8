#include "analysis/spring_forces_command.h"

#include "analysis/provenance.h"

#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <set>
#include <tuple>

#include "analysis/spring_forces.h"
#include "analysis/spring_modes.h"
#include "kinds/standard_kinds.h"
#include "models/coil_spring_chain.h"

namespace tcpmsim {

namespace {

// Eigenfrequencies and transmissibility of each distinct spring among the scenarios.
void print_modes(const std::vector<std::string>& configs, std::ostream& out,
                 std::shared_ptr<const UnitSystem> units) {
  std::set<std::tuple<int, double, double, double>> seen;
  char line[256];
  for (const auto& config : configs) {
    const Scenario scenario = load_scenario(config, {}, units);
    if (const auto* chain = scenario.system->find<const CoilSpringChain>()) {
      const auto& p = chain->defaults();
      if (!seen.insert({p.windings, p.mass, p.stiffness, p.damping_ratio}).second) continue;
      std::snprintf(line, sizeof line, "\nSpring N = %d, m = %g g, k = %g N/m (from %s)\n",
                    p.windings, p.mass * 1e3, p.stiffness, scenario.settings.name.c_str());
      out << line << "  clamped eigenfrequencies, lumped against n pi sqrt(k/m) (4.3):\n";
      const auto lumped = clamped_eigenfrequencies(*chain);
      for (int n = 1; n <= 5; ++n) {
        const double continuum =
            n * std::numbers::pi * std::sqrt(p.stiffness / p.mass) / (2 * std::numbers::pi);
        const double model = lumped[static_cast<std::size_t>(n - 1)] / (2 * std::numbers::pi);
        std::snprintf(line, sizeof line, "    n = %d: %9.3f Hz against %9.3f Hz (%+.4f %%)\n", n,
                      model, continuum, 100.0 * (model / continuum - 1.0));
        out << line;
      }
      // Compare cos(omega tau) with 1/T, finite where T has its poles.
      double worst = 0.0, worst_hz = 0.0;
      for (int hz = 1; hz <= 200; ++hz) {
        const double omega = 2 * std::numbers::pi * hz;
        const double deviation =
            std::abs(1.0 / force_transmissibility(*chain, omega) -
                     1.0 / continuum_transmissibility(omega, p.mass, p.stiffness));
        if (deviation > worst) worst = deviation, worst_hz = hz;
      }
      std::snprintf(line, sizeof line,
                    "  force transmissibility F_o/F_i against 1/cos(omega tau) (4.1), 1-200 Hz in "
                    "1 Hz steps:\n"
                    "    largest |F_i/F_o - cos(omega tau)| = %.2e (at %.0f Hz)\n",
                    worst, worst_hz);
      out << line;
    }
  }
}

}  // namespace

std::string run_spring_forces_command(const SpringForcesOptions& options, std::ostream& out,
                                      std::shared_ptr<const UnitSystem> units) {
  const auto started = std::chrono::steady_clock::now();
  const auto rows = run_spring_forces(options.configs, options.window, options.threads, units);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const std::string output = options.output.empty() ? "results/spring_forces.h5" : options.output;
  write_spring_force_table(rows, output,
                           file_provenance(options.invocation, options.configs, {}, units));
  if (!options.quiet) {
    out << format_spring_force_table(rows);
    char line[160];
    std::snprintf(line, sizeof line, "%zu simulations on %d threads in %.2f s\n", rows.size(),
                  options.threads, seconds);
    out << line;
    print_modes(options.configs, out, units);
    out << "wrote " << output << "\n";
  }
  return output;
}

}  // namespace tcpmsim
