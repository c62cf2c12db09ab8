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
  bool accepts(double value) const;
  bool unbounded() const;
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
};

// A number as messages print it (the default stream format: 0.001, 1e-09, 2.5).
std::string number_text(double value);
// The same to `digits` significant digits (%g): 17 round-trips a double through text.
std::string number_text(double value, int digits);

}  // namespace tcpmsim
