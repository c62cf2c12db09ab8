#pragma once

#include <optional>
#include <string>
#include <vector>

namespace tcpmsim {

// What `tcpmsim discover` tries of an effect kind, declared with the kind's registration
// (Kind::candidates, models/effects/effect_kinds.cpp) so that one place says what the effect is,
// how it is built, its examples and how discover looks for it. identification/effect_catalogue
// turns these declarations into candidates for a base model; `tcpmsim kinds` lists them.

// The base model's and the measurement's scales a candidate value is set in (SI).
enum class CandidateScale {
  one,              // 1
  k1,               // the SLS's parallel stiffness [N/m]
  k2,               // its branch stiffness [N/m]
  conductance,      // the heat loss per kelvin, hA [W/K]
  ambient,          // the ambient temperature [K]
  range,            // the measured deflection's range (2 cm without a deflection channel) [m]
  k1_range,         // k1 x range [N]
  deflection_low,   // the measured deflection's smallest [m]
  deflection_high,  // and largest [m]
  deflection_sum,   // their sum [m]
  power_peak,       // the measured power's largest [W]
  warm,             // where a heated threshold starts: ambient + 10 K, or half the base model's
                    // largest rise above ambient when that is less than 20 K [K]
  coil_scale,       // |lambda_0| of the coil law (1 if zero) [its unit]
};

// scale x factor / divisor + offset (in that order: declared values round as written).
struct CandidateValue {
  double factor = 0.0;
  CandidateScale scale = CandidateScale::one;
  double offset = 0.0;
  double divisor = 1.0;
};

// A plain number.
inline CandidateValue fixed_value(double value) {
  return {value, CandidateScale::one};
}
inline CandidateValue scaled(double factor, CandidateScale scale, double offset = 0.0,
                             double divisor = 1.0) {
  return {factor, scale, offset, divisor};
}

// A key of an effect section: held at `start`, or freed by the refit within [lower, upper]
// from `start`, where the candidate is the base model (zero size).
struct CandidateKey {
  std::string key;
  std::string unit;
  CandidateValue start;
  std::optional<CandidateValue> lower;  // both or neither: free
  std::optional<CandidateValue> upper;
};

// Sections of one key fixed on a log-spaced grid (a Prandtl-Ishlinskii operator's radii): one
// section per point, the grid key first, then `keys`.
struct CandidateGrid {
  std::string key;
  std::string unit;
  CandidateValue low;
  CandidateValue high;
  int points = 0;
};

// A term of the muscle's own law rather than an attached section (the coil's lambda_T): the
// scenario gives `key` of the muscle's `section` the value `given` (so that the term is
// assembled), and the refit frees the parameter "<muscle>.<section>.<key>" from `key`'s start.
struct CandidateLawTerm {
  std::string section;
  CandidateValue given;
};

// One form of a family: `sections` effect sections of the kind (or a grid of them), or a law
// term; `order` counts its elements.
struct CandidateMember {
  std::string member;  // "one Dahl element, free radius"
  int order = 1;
  std::vector<std::vector<CandidateKey>> sections;
  std::optional<CandidateGrid> grid;     // with sections.size() == 1: those keys per point
  std::optional<CandidateLawTerm> term;  // with sections.size() == 1: the term's one key
};

// What a family needs of the base model and the measurement; without it, it is skipped.
enum class CandidateNeed { temperature, deflection, power, coil_output, coil_temperature_term };

// A family the verdict names ("hysteresis"): what it models, the diagnostic that should give it
// away, its place in the catalogue's order and its members (model orders).
struct CandidateFamily {
  std::string name;
  int position = 0;
  std::string description;
  std::string signature;
  std::vector<CandidateNeed> needs;
  std::vector<CandidateMember> members;
};

// A kind's declaration: its families, or why discover does not try it.
struct CandidateDeclaration {
  std::vector<CandidateFamily> families;
  std::string excluded;  // non-empty: not a candidate, and why
};

}  // namespace tcpmsim
