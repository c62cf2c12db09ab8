#pragma once

#include <limits>
#include <string>
#include <string_view>

namespace tcpmsim {

// A constraint a number must satisfy, with the words to explain it: checked when a scenario is
// read and again when a parameter is set in a run context.
class ValueCheck {
 public:
  ValueCheck() = default;
  static ValueCheck positive();
  static ValueCheck non_negative();
  static ValueCheck at_least(double lower);
  static ValueCheck between(double lower, double upper);  // inclusive
  static ValueCheck fraction();                           // [0, 1]
  // A size read from a scenario (components, windings, samples): in [1, limit], where the limit
  // keeps a run's memory and time bounded; `reason` says what the limit protects, for messages.
  static ValueCheck count(double limit, std::string reason);
  // The same check with the range values usually take for the muscles and springs the thesis
  // and the literature describe. A value outside it is accepted, with a warning: most often a
  // unit's prefix slipped (N/mm for mN/mm), a factor of 1000.
  ValueCheck typical(double lower, double upper) const;
  bool accepts(double value) const;
  bool unbounded() const;
  bool has_typical_range() const;
  // "typically 0.1 to 5000 N/m"; empty without a typical range.
  std::string typical_text(std::string_view unit = "") const;
  // "" if `value` lies in the typical range (or there is none), else why it is implausible and
  // the likely slip: "'14.04 N/mm' is 14040 N/m, outside the typical range (0.1 to 5000 N/m) ...;
  // 1/1000 of it would be typical: a unit's prefix slipped (N for mN, m for mm)?".
  std::string implausibility(double value, std::string_view unit, const std::string& shown) const;
  // "a positive value", "a value in [0, 1]", ... followed by " in <unit>" when given.
  std::string expectation(std::string_view unit = "") const;
  // "" if `value` is finite and accepted, else "expected ..., got <shown>" (`shown`: the value
  // as its source gave it).
  std::string problem(double value, std::string_view unit, const std::string& shown) const;

 private:
  double lower_ = -std::numeric_limits<double>::infinity();
  double upper_ = std::numeric_limits<double>::infinity();
  bool lower_open_ = false;
  std::string reason_;
  double typical_lower_ = -std::numeric_limits<double>::infinity();
  double typical_upper_ = std::numeric_limits<double>::infinity();
};

// A number as messages print it (the default stream format: 0.001, 1e-09, 2.5).
std::string number_text(double value);
// The same to `digits` significant digits (%g): 17 round-trips a double through text.
std::string number_text(double value, int digits);

}  // namespace tcpmsim
