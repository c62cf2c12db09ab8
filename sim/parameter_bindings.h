#pragma once

#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sim/config/config_node.h"
#include "sim/parameters.h"
#include "sim/value_check.h"

namespace tcpmsim {

// The link between a component's typed parameters (a struct P) and its declared parameters: each
// binding names a parameter and the field of P that holds it. A component reads its scenario keys
// through these (so the key, its unit and its check are stated once), declares them to the
// System, and rebuilds P from a run context's values when a run starts.
template <class P>
class ParameterBindings {
 public:
  using Field = std::function<double&(P&)>;
  using ExtraCheck = std::function<std::string(double)>;

  static Field member(double P::*field) {
    return [field](P& values) -> double& { return values.*field; };
  }

  void bind(std::string path, std::string unit, ValueCheck check, Field field,
            ExtraCheck extra = {}) {
    entries_.push_back(
        {std::move(path), std::move(unit), check, std::move(field), std::move(extra)});
  }

  // Reads node[key] in `unit` ("1": a bare number) under `check`, stores it in `values` through
  // `field` and binds it as the parameter of that key.
  double quantity(const ConfigNode& node, std::string_view key, std::string_view unit,
                  const ValueCheck& check, P& values, Field field, ExtraCheck extra = {}) {
    const ConfigNode value_node = node.at(key);
    return store(value_node, value_node.as_quantity(unit, check), unit, check, values,
                 std::move(field), std::move(extra));
  }
  // As quantity, with a default when the key is absent (recorded in the resolved scenario).
  double quantity_or(const ConfigNode& node, std::string_view key, std::string_view unit,
                     double fallback, const ValueCheck& check, P& values, Field field) {
    const double value = node.quantity_or(key, unit, fallback, check);
    field(values) = value;
    bind(node.parameter_path(key), std::string(unit), check, std::move(field));
    return value;
  }
  // The node itself, a scalar quantity.
  double as_quantity(const ConfigNode& node, std::string_view unit, const ValueCheck& check,
                     P& values, Field field, ExtraCheck extra = {}) {
    return store(node, node.as_quantity(unit, check), unit, check, values, std::move(field),
                 std::move(extra));
  }

  // Reads node[key], a pair [low, high] in `unit` with low < high, stores the ends through `low`
  // and `high` and binds them as the parameters key[0] and key[1].
  std::pair<double, double> interval(const ConfigNode& node, std::string_view key,
                                     std::string_view unit, const ValueCheck& check, P& values,
                                     Field low, Field high) {
    const auto ends = node.interval(key, unit, check);
    low(values) = ends.first;
    high(values) = ends.second;
    const std::string path = node.at(key).parameter_path();
    bind(path + "[0]", std::string(unit), check, std::move(low));
    bind(path + "[1]", std::string(unit), check, std::move(high));
    return ends;
  }

  // Adds the bindings of a part of P (a nested struct) reached through `part`.
  template <typename Q>
  void nest(const ParameterBindings<Q>& inner, std::function<Q&(P&)> part) {
    for (const auto& entry : inner.entries_) {
      auto field = entry.field;
      entries_.push_back({entry.path, entry.unit, entry.check,
                          [field, part](P& values) -> double& { return field(part(values)); },
                          entry.extra});
    }
  }

  std::vector<ParameterDeclaration> declarations(const P& values) const {
    std::vector<ParameterDeclaration> declared;
    P copy = values;
    for (const auto& entry : entries_)
      declared.push_back({entry.path, entry.unit, entry.field(copy), entry.check, entry.extra});
    return declared;
  }
  // `base` with the bound fields set from `values`, in binding order.
  P assign(P base, std::span<const double> values) const {
    for (std::size_t i = 0; i < entries_.size(); ++i) entries_[i].field(base) = values[i];
    return base;
  }

 private:
  template <typename>
  friend class ParameterBindings;
  double store(const ConfigNode& node, double value, std::string_view unit, const ValueCheck& check,
               P& values, Field field, ExtraCheck extra) {
    if (extra) {
      if (const std::string problem = extra(value); !problem.empty()) node.fail(problem);
    }
    field(values) = value;
    bind(node.parameter_path(), std::string(unit), check, std::move(field), std::move(extra));
    return value;
  }

  struct Entry {
    std::string path;
    std::string unit;
    ValueCheck check;
    Field field;
    ExtraCheck extra;
  };
  std::vector<Entry> entries_;
};

}  // namespace tcpmsim
