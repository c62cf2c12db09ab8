#include "identification/bench_measurement.h"

#include <cmath>

#include "identification/fit_problem.h"
#include "sim/config/config_node.h"
#include "sim/io/measured_data.h"
#include "sim/random_stream.h"
#include "sim/run.h"

namespace tcpmsim::fit {

namespace {

Instrument read_instrument(const ConfigNode& entry, const Scenario& scenario) {
  entry.declare({"channel", "output", "unit", "noise", "correlated_noise", "resolution", "spikes"});
  Instrument instrument;
  instrument.channel = entry.text("channel");
  if (!measured_quantity_of(instrument.channel) || instrument.channel == "time") {
    entry.at("channel").fail(
        "expected a measured quantity (power, deflection, force, "
        "decay_time, ...; left.force for an instance), got '" +
        instrument.channel + "'");
  }
  instrument.output = entry.text("output");
  instrument.si_unit = named_output(*scenario.system, entry.at("output"), "scenario").unit;
  const std::string quantity_unit(measured_quantity_of(instrument.channel)->si_unit);
  if (!entry.units().convertible(instrument.si_unit, quantity_unit)) {
    entry.at("output").fail("output '" + instrument.output + "' is in " + instrument.si_unit +
                            "; channel '" + instrument.channel + "' measures " + quantity_unit);
  }
  instrument.unit = entry.text("unit");
  if (!entry.units().convertible(instrument.unit, quantity_unit)) {
    entry.at("unit").fail("'" + instrument.unit + "' is not a unit of " + quantity_unit);
  }
  instrument.noise =
      entry.difference_or("noise", instrument.si_unit, 0.0, ValueCheck::non_negative());
  instrument.resolution =
      entry.difference_or("resolution", instrument.si_unit, 0.0, ValueCheck::non_negative());
  if (const auto correlated = entry.find("correlated_noise")) {
    correlated->declare({"size", "correlation_time"});
    instrument.correlated_noise =
        correlated->difference("size", instrument.si_unit, ValueCheck::non_negative());
    instrument.correlation_time =
        correlated->quantity("correlation_time", "s", ValueCheck::positive());
  }
  if (const auto spikes = entry.find("spikes")) {
    spikes->declare({"probability", "size"});
    instrument.spike_probability = spikes->number("probability", ValueCheck::between(0.0, 1.0));
    instrument.spike_size = spikes->difference("size", instrument.si_unit, ValueCheck::positive());
  }
  return instrument;
}

// An instrument's correlated noise, one reading after another: first-order with its
// correlation time, stationary from the first reading.
class CorrelatedNoise {
 public:
  CorrelatedNoise(const Instrument& instrument, std::uint64_t seed)
      : instrument_(instrument),
        stream_(seed, "instrument " + instrument.channel + " correlated") {}

  double at(double time) {
    const double draw = instrument_.correlated_noise * stream_.normal();
    if (started_) {
      const double phi = std::exp(-(time - last_time_) / instrument_.correlation_time);
      last_ = phi * last_ + std::sqrt(1.0 - phi * phi) * draw;
    } else {
      last_ = draw;
      started_ = true;
    }
    last_time_ = time;
    return last_;
  }

 private:
  const Instrument& instrument_;
  RandomStream stream_;
  bool started_ = false;
  double last_ = 0.0, last_time_ = 0.0;
};

// One reading: the true value, a spike now and then, white normal noise, then the resolution.
double read(const Instrument& instrument, double value, RandomStream& stream) {
  if (instrument.spike_probability > 0 && stream.chance(instrument.spike_probability))
    value += stream.chance(0.5) ? instrument.spike_size : -instrument.spike_size;
  if (instrument.noise > 0) value += instrument.noise * stream.normal();
  if (instrument.resolution > 0)
    value = instrument.resolution * std::round(value / instrument.resolution);
  return value;
}

}  // namespace

Bench load_bench(const std::string& file, const Scenario& scenario,
                 std::shared_ptr<const UnitSystem> units) {
  const ConfigNode root = ConfigNode::load_file(file, {}, units);
  root.declare({"seed", "channels"});
  Bench bench;
  bench.seed = static_cast<std::uint64_t>(root.integer_or("seed", 1, ValueCheck::non_negative()));
  const ConfigNode channels = root.at("channels");
  if (channels.elements().empty()) channels.fail("expected at least one channel");
  for (const ConfigNode& entry : channels.elements()) {
    bench.instruments.push_back(read_instrument(entry, scenario));
    for (std::size_t k = 0; k + 1 < bench.instruments.size(); ++k) {
      if (bench.instruments[k].channel == bench.instruments.back().channel)
        entry.at("channel").fail("channel '" + bench.instruments.back().channel +
                                 "' is measured twice");
    }
  }
  root.reject_unknown_keys();
  return bench;
}

std::string measure(const Scenario& scenario, const Bench& bench, const UnitSystem& units) {
  std::vector<std::string> outputs;
  for (const auto& instrument : bench.instruments) outputs.push_back(instrument.output);
  OutputPicker picker(*scenario.system, outputs);
  integrate(scenario, picker);
  std::string text = "time[s]";
  std::vector<std::vector<double>> readings;
  for (std::size_t k = 0; k < bench.instruments.size(); ++k) {
    const auto& instrument = bench.instruments[k];
    text += "," + instrument.channel + "[" + instrument.unit + "]";
    RandomStream stream(bench.seed, "instrument " + instrument.channel);
    const auto to_unit = units.converter(instrument.si_unit, instrument.unit);
    CorrelatedNoise correlated(instrument, bench.seed);
    std::vector<double> column;
    for (std::size_t i = 0; i < picker.values[k].size(); ++i) {
      double value = picker.values[k][i];
      if (instrument.correlated_noise > 0) value += correlated.at(picker.times[i]);
      column.push_back(to_unit(read(instrument, value, stream)));
    }
    readings.push_back(std::move(column));
  }
  text += "\n";
  for (std::size_t i = 0; i < picker.times.size(); ++i) {
    text += number_text(picker.times[i], 17);
    for (const auto& column : readings) {
      text += ',';
      text += number_text(column[i], 17);
    }
    text += "\n";
  }
  return text;
}

}  // namespace tcpmsim::fit
