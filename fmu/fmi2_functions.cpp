// The FMI 2.0 co-simulation functions a tcpmsim FMU's library exports (fmu/fmi2/fmi2Functions.h),
// each a thin call into FmuInstance. A null instance, and every call the FMU does not offer,
// returns fmi2Error; no exception leaves the library.
#include "fmu/fmi2/fmi2Functions.h"

#include <exception>

#include "fmu/fmu_instance.h"

using tcpmsim::fmu::FmuInstance;

namespace {

FmuInstance* instance_of(fmi2Component c) {
  return static_cast<FmuInstance*>(c);
}

// Runs `call` on the instance; a null instance or an escaping exception is fmi2Error.
template <typename Call>
fmi2Status guarded(fmi2Component c, const char* function, Call call) {
  FmuInstance* instance = instance_of(c);
  if (!instance) return fmi2Error;
  try {
    return call(*instance);
  } catch (const std::exception& error) {
    return instance->report(fmi2Error, std::string(function) + ": " + error.what());
  } catch (...) {
    return instance->report(fmi2Error, std::string(function) + ": an unknown error");
  }
}

fmi2Status unsupported(fmi2Component c, const char* function) {
  return guarded(c, function, [&](FmuInstance& i) { return i.unsupported(function); });
}

}  // namespace

extern "C" {

const char* fmi2GetTypesPlatform(void) {
  return fmi2TypesPlatform;
}

const char* fmi2GetVersion(void) {
  return fmi2Version;
}

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t, const fmi2String[]) {
  return guarded(c, "fmi2SetDebugLogging", [&](FmuInstance& i) {
    i.set_logging(loggingOn != fmi2False);
    return fmi2OK;
  });
}

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation,
                              const fmi2CallbackFunctions* functions, fmi2Boolean,
                              fmi2Boolean loggingOn) {
  try {
    return FmuInstance::instantiate(instanceName, fmuType, fmuGUID, fmuResourceLocation, functions,
                                    loggingOn);
  } catch (...) {
    return nullptr;
  }
}

void fmi2FreeInstance(fmi2Component c) {
  delete instance_of(c);
}

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined, fmi2Real tolerance,
                               fmi2Real startTime, fmi2Boolean stopTimeDefined, fmi2Real stopTime) {
  return guarded(c, "fmi2SetupExperiment", [&](FmuInstance& i) {
    return i.setup_experiment(toleranceDefined != fmi2False, tolerance, startTime,
                              stopTimeDefined != fmi2False, stopTime);
  });
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
  return guarded(c, "fmi2EnterInitializationMode",
                 [](FmuInstance& i) { return i.enter_initialization(); });
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
  return guarded(c, "fmi2ExitInitializationMode",
                 [](FmuInstance& i) { return i.exit_initialization(); });
}

fmi2Status fmi2Terminate(fmi2Component c) {
  return guarded(c, "fmi2Terminate", [](FmuInstance& i) { return i.terminate(); });
}

fmi2Status fmi2Reset(fmi2Component c) {
  return guarded(c, "fmi2Reset", [](FmuInstance& i) { return i.reset(); });
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       fmi2Real value[]) {
  return guarded(c, "fmi2GetReal", [&](FmuInstance& i) { return i.get_real(vr, nvr, value); });
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       const fmi2Real value[]) {
  return guarded(c, "fmi2SetReal", [&](FmuInstance& i) { return i.set_real(vr, nvr, value); });
}

// The FMU has Real variables only: the other types have no value reference to address.
fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference[], size_t nvr, fmi2Integer[]) {
  return nvr == 0 ? fmi2OK : unsupported(c, "fmi2GetInteger (the FMU's variables are all Real)");
}
fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference[], size_t nvr, fmi2Boolean[]) {
  return nvr == 0 ? fmi2OK : unsupported(c, "fmi2GetBoolean (the FMU's variables are all Real)");
}
fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference[], size_t nvr, fmi2String[]) {
  return nvr == 0 ? fmi2OK : unsupported(c, "fmi2GetString (the FMU's variables are all Real)");
}
fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference[], size_t nvr,
                          const fmi2Integer[]) {
  return nvr == 0 ? fmi2OK : unsupported(c, "fmi2SetInteger (the FMU's variables are all Real)");
}
fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference[], size_t nvr,
                          const fmi2Boolean[]) {
  return nvr == 0 ? fmi2OK : unsupported(c, "fmi2SetBoolean (the FMU's variables are all Real)");
}
fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference[], size_t nvr,
                         const fmi2String[]) {
  return nvr == 0 ? fmi2OK : unsupported(c, "fmi2SetString (the FMU's variables are all Real)");
}

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate*) {
  return unsupported(c, "fmi2GetFMUstate");
}
fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate) {
  return unsupported(c, "fmi2SetFMUstate");
}
fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate*) {
  return unsupported(c, "fmi2FreeFMUstate");
}
fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate, size_t*) {
  return unsupported(c, "fmi2SerializedFMUstateSize");
}
fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate, fmi2Byte[], size_t) {
  return unsupported(c, "fmi2SerializeFMUstate");
}
fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte[], size_t, fmi2FMUstate*) {
  return unsupported(c, "fmi2DeSerializeFMUstate");
}
fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference[], size_t,
                                        const fmi2ValueReference[], size_t, const fmi2Real[],
                                        fmi2Real[]) {
  return unsupported(c, "fmi2GetDirectionalDerivative");
}

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference[], size_t,
                                       const fmi2Integer[], const fmi2Real[]) {
  return unsupported(c, "fmi2SetRealInputDerivatives (canInterpolateInputs is false)");
}
fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference[], size_t,
                                        const fmi2Integer[], fmi2Real[]) {
  return unsupported(c, "fmi2GetRealOutputDerivatives (maxOutputDerivativeOrder is 0)");
}

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint,
                      fmi2Real communicationStepSize, fmi2Boolean) {
  return guarded(c, "fmi2DoStep", [&](FmuInstance& i) {
    return i.do_step(currentCommunicationPoint, communicationStepSize);
  });
}

fmi2Status fmi2CancelStep(fmi2Component c) {
  return unsupported(c, "fmi2CancelStep (steps complete before fmi2DoStep returns)");
}

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status* value) {
  return guarded(c, "fmi2GetStatus", [&](FmuInstance& i) { return i.status(s, value); });
}
fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real* value) {
  return guarded(c, "fmi2GetRealStatus", [&](FmuInstance& i) { return i.real_status(s, value); });
}
fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind, fmi2Integer*) {
  return unsupported(c, "fmi2GetIntegerStatus");
}
fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean* value) {
  // fmi2Terminated: whether the FMU asks the master to stop (it never does before stopTime).
  if (s == fmi2Terminated && value) {
    *value = fmi2False;
    return instance_of(c) ? fmi2OK : fmi2Error;
  }
  return unsupported(c, "fmi2GetBooleanStatus");
}
fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind, fmi2String*) {
  return unsupported(c, "fmi2GetStringStatus");
}

}  // extern "C"
