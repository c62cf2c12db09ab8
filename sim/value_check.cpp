#include "sim/value_check.h"

#include <cmath>
#include <sstream>
#include <utility>

namespace tcpmsim {

ValueCheck ValueCheck::positive() {
  ValueCheck check;
  check.lower_ = 0.0;
  check.lower_open_ = true;
  return check;
}

ValueCheck ValueCheck::non_negative() {
  return at_least(0.0);
}

ValueCheck ValueCheck::at_least(double lower) {
  ValueCheck check;
  check.lower_ = lower;
  return check;
}

ValueCheck ValueCheck::between(double lower, double upper) {
  ValueCheck check;
  check.lower_ = lower;
  check.upper_ = upper;
  return check;
}

ValueCheck ValueCheck::count(double limit, std::string reason) {
  ValueCheck check = between(1.0, limit);
  check.reason_ = std::move(reason);
  return check;
}

ValueCheck ValueCheck::fraction() {
  return between(0.0, 1.0);
}

bool ValueCheck::unbounded() const {
  return std::isinf(lower_) && lower_ < 0.0 && std::isinf(upper_);
}

bool ValueCheck::accepts(double value) const {
  if (lower_open_ ? !(value > lower_) : !(value >= lower_)) return false;
  return value <= upper_;
}

std::string number_text(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

std::string number_text(double value, int digits) {
  std::ostringstream out;
  out.precision(digits);
  out << value;
  return out.str();
}

std::string ValueCheck::problem(double value, std::string_view unit,
                                const std::string& shown) const {
  if (!std::isfinite(value)) return "expected a finite value, got " + shown;
  if (!accepts(value)) return "expected " + expectation(unit) + ", got " + shown;
  return {};
}

std::string ValueCheck::expectation(std::string_view unit) const {
  const std::string in_unit = unit.empty() || unit == "1" ? "" : " in " + std::string(unit);
  if (lower_open_ && lower_ == 0.0 && std::isinf(upper_)) return "a positive value" + in_unit;
  if (lower_ == 0.0 && std::isinf(upper_)) return "a non-negative value" + in_unit;
  if (std::isinf(upper_)) return "a value of at least " + number_text(lower_) + in_unit;
  const std::string limit = reason_.empty() ? "" : " (the limit: " + reason_ + ")";
  return "a value in [" + number_text(lower_) + ", " + number_text(upper_) + "]" + in_unit + limit;
}

}  // namespace tcpmsim
