#pragma once

#include <string>
#include <vector>

#include "fmu/fmu_interface.h"
#include "sim/config/units.h"

namespace tcpmsim::fmu {

// modelDescription.xml of a co-simulation FMU (FMI 2.0 chapter 2.2 and section 4.3): every
// variable Real and SI, each unit defined by its SI base units; inputs with their start value
// and range; outputs calculated (initial="calculated", no start, as the standard asks of an
// output the model computes); parameters exact with their start; the model structure lists the
// outputs. `generated` is the generationDateAndTime (ISO 8601, UTC).
std::string model_description_xml(const FmuInterface& fmu, const UnitSystem& units,
                                  const std::string& tool, const std::string& generated);

// What in a modelDescription.xml breaks the FMI 2.0 standard's rules, one message each (empty:
// none): the root's required attributes and fmiVersion "2.0"; a CoSimulation element whose
// modelIdentifier is a C identifier; unique unit names with integer base exponents; unique
// variable names in the structured naming convention and unique value references; the
// causality, variability and initial combinations of the standard's tables (2.2.7), with start
// values where required and only there, min <= start <= max; units defined in UnitDefinitions;
// ModelStructure's Outputs listing exactly the outputs, in order, and InitialUnknowns every
// output that is calculated or approximate; DefaultExperiment startTime <= stopTime.
std::vector<std::string> model_description_problems(const std::string& xml);

}  // namespace tcpmsim::fmu
