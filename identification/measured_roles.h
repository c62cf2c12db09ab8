#pragma once

#include <string>
#include <vector>

#include "identification/fit_problem.h"
#include "sim/io/measured_data.h"
#include "sim/scenario.h"

// Which measured channels carry the heating power and the deflection. Discover's catalogue takes
// its scales from them (the power's peak, the deflection's range) and its diagnostics hold the
// residual against them, whatever the measurement calls them.
namespace tcpmsim::fit {

struct MeasuredRoles {
  std::string power = "power";
  std::string deflection = "deflection";
};

// The channels the scenario's data signals replay ({type: data, channel: power}), in the order
// of its resolved YAML.
std::vector<std::string> replayed_channels(const std::string& resolved_yaml);

// The channel of `data` that carries the model's `quantity` ("power", "deflection"): the one a
// data signal under a key of that name replays (drive: {power: {type: data, channel: P_h}}),
// else the channel of a compared output the model publishes as <group>.<quantity> (a hanging
// mass's measured deflection), else a channel named `quantity`; `quantity` itself when the data
// hold none of these (so that whoever looks it up finds no channel).
std::string channel_carrying(const Scenario& model, const MeasuredData& data,
                             const std::vector<FitOutput>& outputs, const std::string& quantity);

MeasuredRoles measured_roles(const Scenario& model, const MeasuredData& data,
                             const std::vector<FitOutput>& outputs);

}  // namespace tcpmsim::fit
