#include "sim/config/units.h"

#include <udunits2.h>

#include <algorithm>
#include <mutex>

namespace tcpmsim {

namespace {
// udunits2's unit parser is a non-reentrant flex/bison lexer with global state (two threads
// parsing at once corrupt it, even in separate unit systems), so every call into the library
// takes this one process-wide lock, mirroring the library's own global state.
std::mutex& udunits_mutex() {
  static std::mutex mutex;
  return mutex;
}
}  // namespace

struct UnitSystem::Handle {
  ut_system* system = nullptr;
  ~Handle() {
    const std::lock_guard lock(udunits_mutex());
    if (system) ut_free_system(system);
  }
};

namespace {
struct UnitDeleter {
  void operator()(ut_unit* unit) const { ut_free(unit); }
};
using UnitPointer = std::unique_ptr<ut_unit, UnitDeleter>;

UnitPointer parse(ut_system* system, std::string_view text) {
  const std::string spelled = text.empty() ? std::string("1") : std::string(text);
  return UnitPointer(ut_parse(system, spelled.c_str(), UT_UTF8));
}

// Whether `source` and `target` measure the same quantity. udunits converts a unit into its
// reciprocal too (ut_are_convertible("s", "Hz") holds), so "16 s" would be read as a rate of
// 1/16 Hz; the quotient of the two units must be dimensionless instead.
bool same_dimension(ut_system* system, const ut_unit* source, const ut_unit* target) {
  if (ut_are_convertible(source, target) == 0) return false;
  UnitPointer quotient(ut_divide(source, target));
  return quotient && ut_are_convertible(quotient.get(), ut_get_dimensionless_unit_one(system)) != 0;
}
// The dimensions a scenario's quantities have, each named with two units a user would write.
// A unit finds its entry by its spelling first, then by its dimension (the first entry of that
// dimension); dimensionless entries (an angle) match by spelling only.
struct Dimension {
  std::string_view unit;
  std::string_view name;
  std::string_view examples;
  bool dimensionless = false;
};

constexpr Dimension kDimensions[] = {
    {"m", "a length", "mm or m"},
    {"s", "a time", "s or ms"},
    {"Hz", "a frequency (1/time)", "Hz or 1/s"},
    {"K", "a temperature", "degC or K"},
    {"N", "a force", "N or mN"},
    {"N/m", "a stiffness (force/length)", "N/m or N/mm"},
    {"N*s/m", "a damping (force*time/length)", "N*s/m or N*s/mm"},
    {"kg", "a mass", "g or kg"},
    {"m/s", "a velocity", "m/s or mm/s"},
    {"m/s^2", "an acceleration", "m/s^2 or mm/s^2"},
    {"W", "a power", "W or mW"},
    {"J", "an energy", "J or mJ"},
    {"W/K", "a thermal conductance (power/temperature)", "W/K or mW/K"},
    {"J/K", "a heat capacity (energy/temperature)", "J/K or mJ/K"},
    {"N/K", "a force per temperature", "N/K or mN/K"},
    {"N/J", "a force per energy", "N/J or mN/J"},
    {"1/K", "a temperature coefficient (1/temperature)", "1/K"},
    {"ohm", "a resistance", "ohm or mohm"},
    {"ohm/m", "a resistance per length", "ohm/m or ohm/mm"},
    {"H", "an inductance", "H or uH"},
    {"V", "a voltage", "V or mV"},
    {"A", "a current", "A or mA"},
    {"rad", "an angle", "rad or deg", true},
};

std::string described(const Dimension& dimension) {
  return std::string(dimension.name) + ", e.g. " + std::string(dimension.examples);
}
}  // namespace

UnitSystem::UnitSystem() : handle_(std::make_unique<Handle>()) {
  const std::lock_guard lock(udunits_mutex());
  // udunits reports database redefinitions on stderr; they are not errors for us.
  ut_set_error_message_handler(ut_ignore);
  handle_->system = ut_read_xml(nullptr);
  if (!handle_->system) {
    throw UnitError(
        "could not read the udunits2 unit database (is the Debian package libudunits2-data "
        "installed?)");
  }
}

UnitSystem::~UnitSystem() = default;

bool UnitSystem::convertible(std::string_view from, std::string_view to) const {
  const std::lock_guard lock(udunits_mutex());
  UnitPointer source = parse(handle_->system, from);
  UnitPointer target = parse(handle_->system, to);
  return source && target && same_dimension(handle_->system, source.get(), target.get());
}

std::function<double(double)> UnitSystem::converter(std::string_view from,
                                                    std::string_view to) const {
  const std::lock_guard lock(udunits_mutex());
  UnitPointer source = parse(handle_->system, from);
  if (!source) throw UnitError("'" + std::string(from) + "' is not a unit");
  UnitPointer target = parse(handle_->system, to);
  if (!target) throw UnitError("internal: '" + std::string(to) + "' is not a unit");
  cv_converter* converter = same_dimension(handle_->system, source.get(), target.get())
                                ? ut_get_converter(source.get(), target.get())
                                : nullptr;
  if (!converter) {
    throw UnitError("unit '" + std::string(from) + "' cannot be converted to '" + std::string(to) +
                    "'");
  }
  std::shared_ptr<cv_converter> owned(converter, cv_free);
  return [owned](double value) { return cv_convert_double(owned.get(), value); };
}

std::string UnitSystem::describe_dimension(std::string_view unit) const {
  for (const Dimension& dimension : kDimensions) {
    if (dimension.unit == unit) return described(dimension);
  }
  if (unit.empty() || convertible(unit, "1")) return {};
  for (const Dimension& dimension : kDimensions) {
    if (!dimension.dimensionless && convertible(unit, dimension.unit)) return described(dimension);
  }
  return {};
}

namespace {

// Collects a parsed unit's base units and powers (udunits represents every unit as a product of
// basic units, possibly scaled and offset: a galilean unit).
struct BaseCollector {
  SiBaseUnit base;
  std::string problem;
};

ut_status visit_basic(const ut_unit* unit, void* data);
ut_status visit_product(const ut_unit*, int count, const ut_unit* const* basics, const int* powers,
                        void* data) {
  auto& collector = *static_cast<BaseCollector*>(data);
  for (int k = 0; k < count; ++k) {
    const char* symbol = ut_get_symbol(basics[k], UT_ASCII);
    const auto& symbols = SiBaseUnit::kSymbols;
    const auto found = std::find_if(symbols.begin(), symbols.end(), [&](const char* known) {
      return symbol && std::string_view(symbol) == known;
    });
    if (found == symbols.end()) {
      collector.problem = std::string("a base unit outside SI's: ") + (symbol ? symbol : "?");
      return UT_VISIT_ERROR;
    }
    collector.base.exponents[static_cast<std::size_t>(found - symbols.begin())] += powers[k];
  }
  return UT_SUCCESS;
}
ut_status visit_basic(const ut_unit* unit, void* data) {
  const int power = 1;
  return visit_product(unit, 1, &unit, &power, data);
}
ut_status visit_galilean(const ut_unit*, double scale, const ut_unit* underlying, double offset,
                         void* data);
ut_status visit_timestamp(const ut_unit*, const ut_unit*, double, void* data) {
  static_cast<BaseCollector*>(data)->problem = "a timestamp unit";
  return UT_VISIT_ERROR;
}
ut_status visit_logarithmic(const ut_unit*, double, const ut_unit*, void* data) {
  static_cast<BaseCollector*>(data)->problem = "a logarithmic unit";
  return UT_VISIT_ERROR;
}
ut_visitor base_visitor() {
  ut_visitor visitor{};
  visitor.visit_basic = visit_basic;
  visitor.visit_product = visit_product;
  visitor.visit_galilean = visit_galilean;
  visitor.visit_timestamp = visit_timestamp;
  visitor.visit_logarithmic = visit_logarithmic;
  return visitor;
}
// udunits' galilean unit: value [underlying] = scale * value [unit] + offset (degC: 1, 273.15;
// mN: 0.001, 0), composed with the underlying's own value [base] = factor * value + offset.
ut_status visit_galilean(const ut_unit*, double scale, const ut_unit* underlying, double offset,
                         void* data) {
  auto& collector = *static_cast<BaseCollector*>(data);
  ut_visitor visitor = base_visitor();
  BaseCollector inner;
  if (ut_accept_visitor(underlying, &visitor, &inner) != UT_SUCCESS) {
    collector.problem = inner.problem;
    return UT_VISIT_ERROR;
  }
  collector.base.exponents = inner.base.exponents;
  collector.base.factor = scale * inner.base.factor;
  collector.base.offset = offset * inner.base.factor + inner.base.offset;
  return UT_SUCCESS;
}

}  // namespace

SiBaseUnit UnitSystem::si_base(std::string_view unit) const {
  const std::lock_guard lock(udunits_mutex());
  UnitPointer parsed = parse(handle_->system, unit);
  if (!parsed) throw UnitError("'" + std::string(unit) + "' is not a unit");
  ut_visitor visitor = base_visitor();
  BaseCollector collector;
  if (ut_accept_visitor(parsed.get(), &visitor, &collector) != UT_SUCCESS)
    throw UnitError("'" + std::string(unit) + "' has no SI base form: " + collector.problem);
  return collector.base;
}

double UnitSystem::convert(double value, std::string_view from, std::string_view to) const {
  return converter(from, to)(value);
}

double UnitSystem::convert_difference(double value, std::string_view from,
                                      std::string_view to) const {
  const double converted = convert(value, from, to);  // checks that the two are convertible
  const SiBaseUnit source = si_base(from), target = si_base(to);
  if (source.offset == 0.0 && target.offset == 0.0) return converted;
  // value [base] = factor * value [unit] + offset: a difference scales by the factors alone.
  return value * source.factor / target.factor;
}

}  // namespace tcpmsim
