#pragma once

#include <array>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

namespace tcpmsim {

class UnitError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A unit as SI base units: value [unit] = factor * value [base] + offset, base =
// kg^e0 m^e1 s^e2 A^e3 K^e4 mol^e5 cd^e6 rad^e7 (an FMU's <BaseUnit>, FMI 2.0 section 2.2.2).
struct SiBaseUnit {
  static constexpr std::array<const char*, 8> kSymbols{"kg", "m",   "s",  "A",
                                                       "K",  "mol", "cd", "rad"};
  std::array<int, 8> exponents{};
  double factor = 1.0;
  double offset = 0.0;
};

// Unit conversion at the configuration boundary, backed by udunits2 and its unit database.
// Knows SI prefixes, offset units (degC), and derived units ("N.s/mm", "uH/degC").
// Safe on any thread: udunits2's parser keeps global state, so every call into it takes one
// process-wide lock (units.cpp). Scenario loads on several threads therefore take turns at
// their unit conversions; integrating in parallel is not affected.
class UnitSystem {
 public:
  UnitSystem();
  ~UnitSystem();
  UnitSystem(const UnitSystem&) = delete;
  UnitSystem& operator=(const UnitSystem&) = delete;

  // Converts `value` expressed in `from` into `to`. Throws UnitError if `from` is not a unit
  // udunits knows or does not measure the same quantity as `to`: a unit and its reciprocal
  // (s and Hz, mm/N and N/mm) are not convertible here, although udunits would invert them.
  double convert(double value, std::string_view from, std::string_view to) const;
  // Converts a difference of two values (a noise, a spread): without the units' offsets, so
  // 0.5 degC is 0.5 K. Between units without an offset it is convert's value to the bit.
  double convert_difference(double value, std::string_view from, std::string_view to) const;
  bool convertible(std::string_view from, std::string_view to) const;
  // The conversion from `from` into `to` as a function, parsed once, for converting many
  // values (a data file's column). Throws UnitError as convert does.
  std::function<double(double)> converter(std::string_view from, std::string_view to) const;
  // What a value in `unit` measures, for a message that asks for one: "a stiffness
  // (force/length), e.g. N/m or N/mm" for N/m or any unit of its dimension; empty for a unit of
  // a dimension this table does not name.
  std::string describe_dimension(std::string_view unit) const;
  // `unit` in SI base units. Throws UnitError for a unit udunits does not know, or one built on
  // a base outside SiBaseUnit's (a timestamp, a logarithmic unit).
  SiBaseUnit si_base(std::string_view unit) const;

 private:
  struct Handle;
  std::unique_ptr<Handle> handle_;
};

}  // namespace tcpmsim
