#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "controllers/self_sensing_estimator.h"
#include "kinds/standard_kinds.h"
#include "sim/integrator.h"
#include "sim/memory_record.h"

namespace tcpmsim::testing {

using MemorySink = MemoryRecord;

struct Trace {
  std::vector<double> time;
  std::map<std::string, std::vector<double>> channels;
  SolverStatistics statistics;
  const std::vector<double>& operator[](const std::string& channel) const;
};

std::shared_ptr<const UnitSystem> shared_units();

Scenario scenario_from_text(const std::string& yaml,
                            const std::vector<std::string>& overrides = {});
Trace simulate(const Scenario& scenario);
// A run of `scenario` in `context` (parameters set in it).
Trace simulate(const Scenario& scenario, Context& context);
// The ConfigError message building `yaml` gives, or "no error".
std::string config_error(const std::string& yaml, const std::vector<std::string>& overrides = {});
Trace simulate(const std::string& yaml, const std::vector<std::string>& overrides = {});

// A small physical-form muscle: C = 0.5 J/K, hA = 0.05 W/K, phi_T = 2 mN/K, SLS with
// k1 = 10 N/m, k2 = 2.5 N/m, c = 5 N s/m, no power, 20 mm imposed deflection, 100 s at 10 Hz.
// Tests override what they study.
std::string physical_muscle_yaml();
// The same muscle in the reduced form (7.1) with the mapped kappa_P, kappa_c.
std::string reduced_muscle_yaml();

// Error allowed for a global solution at relative tolerance rtol on a quantity of magnitude
// `scale`: BDF's global error on these stable linear problems stays within tens of rtol.
double allowed(double rtol, double scale);

// The estimator's model with thesis Table 7.2 in SI, L* in seconds.
SelfSensingEstimatorParameters thesis_estimator_parameters();

// `text` with the first `from` replaced by `to`; throws std::logic_error if there is none.
std::string replaced(std::string text, const std::string& from, const std::string& to);

// %g formatting, for building --set overrides from numbers.
std::string number(double value);

double max_abs_difference(const std::vector<double>& a, const std::vector<double>& b);
// The same doubles bit for bit (NaN equals NaN).
bool bitwise_equal(const std::vector<double>& a, const std::vector<double>& b);
std::string source_path(const std::string& relative);
// A directory of this test process's own under the temporary directory, "<name>_<pid>" (ctest
// runs cases in parallel processes, which must not share files), created if missing. A run that
// passes removes its process's directories at its end (tests/main.cpp); a failed run keeps them.
std::string process_directory(const std::string& name);
// The chapter-7 bench's record (configs/discover/ch7_protocol.yaml, its inputs at 16 Hz), cut to
// `duration` ("" for the whole 620 s): the measurement the model scenarios replay. Run once per
// process and duration, in process_directory("protocol").
std::string protocol_record(const std::string& duration = "");

}  // namespace tcpmsim::testing
