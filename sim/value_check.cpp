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

ValueCheck ValueCheck::typical(double lower, double upper) const {
  ValueCheck check = *this;
  check.typical_lower_ = lower;
  check.typical_upper_ = upper;
  return check;
}

namespace {
// " N/m" after a value; nothing for a plain number.
std::string unit_suffix(std::string_view unit) {
  std::string suffix;
  if (unit.empty() || unit == "1") return suffix;
  suffix.push_back(' ');
  suffix.append(unit.data(), unit.size());
  return suffix;
}
}  // namespace

bool ValueCheck::has_typical_range() const {
  return std::isfinite(typical_lower_) || std::isfinite(typical_upper_);
}

std::string ValueCheck::typical_text(std::string_view unit) const {
  if (!has_typical_range()) return {};
  const std::string in_unit = unit_suffix(unit);
  return "typically " + number_text(typical_lower_) + " to " + number_text(typical_upper_) +
         in_unit;
}

std::string ValueCheck::implausibility(double value, std::string_view unit,
                                       const std::string& shown) const {
  if (!has_typical_range() || (value >= typical_lower_ && value <= typical_upper_)) return {};
  const std::string in_unit = unit_suffix(unit);
  std::string message = shown + " is " + number_text(value) + in_unit +
                        ", outside the typical range (" + number_text(typical_lower_) + " to " +
                        number_text(typical_upper_) + in_unit +
                        ") of the muscles and springs tcpmsim models";
  // The slips a value suffers most: a unit's prefix (1000, a million), centimetres (100).
  struct Slip {
    double factor;
    const char* words;
  };
  for (const Slip slip :
       {Slip{1e3, "1/1000 of it"}, Slip{1e-3, "1000 times it"}, Slip{1e6, "a millionth of it"},
        Slip{1e-6, "a million times it"}, Slip{1e2, "1/100 of it"}, Slip{1e-2, "100 times it"}}) {
    const double meant = value / slip.factor;
    if (meant >= typical_lower_ && meant <= typical_upper_) {
      return message + "; " + slip.words + ", " + number_text(meant) + in_unit +
             ", would be typical: did a unit's prefix slip (N for mN, m for mm, W for mW)?";
    }
  }
  return message + "; check its unit and its size";
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
