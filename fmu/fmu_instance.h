#pragma once

#include <map>
#include <memory>
#include <string>

#include "fmu/fmi2/fmi2FunctionTypes.h"
#include "fmu/fmu_interface.h"
#include "sim/config/units.h"
#include "sim/step_simulator.h"

namespace tcpmsim::fmu {

// One instance of a tcpmsim FMU: the state machine of FMI 2.0 co-simulation (section 4.2.4)
// around a StepSimulator of the scenario the FMU carries (resources/scenario.yaml). Every call a
// master may not make in the state it is in, and every value it may not set, returns fmi2Error
// and says why through the master's logger; nothing throws out of it.
class FmuInstance {
 public:
  // The instance, or null after logging why: a GUID that is not this FMU's, a model-exchange
  // request, a resource location without the scenario, a scenario that does not load.
  static FmuInstance* instantiate(fmi2String name, fmi2Type type, fmi2String guid,
                                  fmi2String resource_location,
                                  const fmi2CallbackFunctions* callbacks, fmi2Boolean logging);

  fmi2Status setup_experiment(bool tolerance_defined, double tolerance, double start,
                              bool stop_defined, double stop);
  fmi2Status enter_initialization();
  fmi2Status exit_initialization();
  fmi2Status terminate();
  fmi2Status reset();
  fmi2Status get_real(const fmi2ValueReference references[], std::size_t count, fmi2Real values[]);
  fmi2Status set_real(const fmi2ValueReference references[], std::size_t count,
                      const fmi2Real values[]);
  fmi2Status do_step(double current, double step);
  fmi2Status status(fmi2StatusKind kind, fmi2Status* value);
  fmi2Status real_status(fmi2StatusKind kind, fmi2Real* value);
  void set_logging(bool on) { logging_ = on; }

  // Logs `message` (category "logError" for an error) and returns `status`.
  fmi2Status report(fmi2Status status, const std::string& message) const;
  // A call this FMU does not offer (model exchange, FMU states, derivatives).
  fmi2Status unsupported(const char* function) const;

 private:
  enum class Mode { instantiated, initialization, stepping, failed, terminated };
  FmuInstance(std::string name, const fmi2CallbackFunctions& callbacks, bool logging);
  fmi2Status refuse_in(const char* call, std::initializer_list<Mode> allowed) const;
  const FmuVariable* variable(fmi2ValueReference reference) const;

  std::string name_;
  fmi2CallbackFunctions callbacks_;
  bool logging_;
  std::shared_ptr<UnitSystem> units_;
  FmuInterface interface_;
  std::unique_ptr<StepSimulator> simulator_;
  std::map<std::string, double> pending_parameters_;  // set before initialization ends
  Mode mode_ = Mode::instantiated;
  double stop_time_ = 0.0;
};

}  // namespace tcpmsim::fmu
