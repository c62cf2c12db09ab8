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
  bool accepts(double value) const;
  bool unbounded() const;
  // "a positive value", "a value in [0, 1]", ... followed by " in <unit>" when given.
  std::string expectation(std::string_view unit = "") const;

 private:
  double lower_ = -std::numeric_limits<double>::infinity();
  double upper_ = std::numeric_limits<double>::infinity();
  bool lower_open_ = false;
};

}  // namespace tcpmsim
