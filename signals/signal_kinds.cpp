#include "signals/signal_kinds.h"

#include "signals/data_signal.h"
#include "signals/signal_readers.h"

namespace tcpmsim {

namespace {

// A whole scenario in which `signal` is a drive's power demand, for the listing of kinds.
KindExample as_power(const std::string& signal) {
  return {R"(scenario: {name: example, duration: 10 s, seed: 1}
output: {rate: 10 Hz}
muscle:
  thermal_force: {form: reduced, kappa_P: 7.2e-3 N/J, kappa_c: 131.6e-3 1/s, ambient_temperature: 23 degC}
  mechanics: {k1: 10.8e-3 N/mm, k2: 2.7e-3 N/mm, damping: 4.3e-3 N*s/mm, force_offset: 106.9e-3 N}
  resistance: 10.18 ohm
  inductance: {quantity: measure, lambda_l: 2.81 mm, lambda_x: 28.8 mm, lambda_0: 0.433}
drive:
  mode: power
  power: )" + signal +
              R"(
load: {type: deflection, deflection: 20 mm}
)",
          "drive.power"};
}

KindExample with_file(KindExample example, std::string name, std::string content) {
  example.files.emplace_back(std::move(name), std::move(content));
  return example;
}

void add(KindRegistry& kinds, const char* name, const char* summary, SignalBuilder read,
         std::vector<KindExample> examples) {
  kinds.add({kSignalCategory, name, summary, std::move(examples), std::move(read)});
}

}  // namespace

void register_signal_kinds(KindRegistry& kinds) {
  namespace read = signal_readers;
  kinds.add_category({kSignalCategory, "", "type", "",
                      "a prescribed function of time: a power, duty or current, an imposed "
                      "deflection or force, an ambient temperature, a reference",
                      "constant", 0});
  add(kinds, "constant", "a constant value; a bare quantity is one", read::constant,
      {as_power("1.5 W"), as_power("{type: constant, value: 1.5 W}")});
  add(kinds, "steps", "initial, then values[k] from times[k] on", read::steps,
      {as_power("{type: steps, initial: 0 W, times: [2 s, 6 s], values: [1 W, 0.5 W]}")});
  add(kinds, "ramp", "from `from` at start_time linearly to `to` at end_time, constant outside",
      read::ramp, {as_power("{type: ramp, start_time: 1 s, end_time: 5 s, from: 0 W, to: 2 W}")});
  add(kinds, "piecewise_linear", "straight lines between (times, values), constant outside",
      read::piecewise_linear,
      {as_power("{type: piecewise_linear, times: [0 s, 4 s, 8 s], values: [0 W, 2 W, 1 W]}")});
  add(kinds, "data",
      "a measured channel replayed: a column of a CSV file (name[unit] headings) or a tcpmsim "
      "record, its samples held or joined by lines; relative files are the scenario's "
      "neighbours",
      read_data_signal,
      {with_file(as_power("{type: data, file: bench.csv, channel: power, interpolation: hold}"),
                 "bench.csv",
                 "# a bench recording: power and load-cell force\n"
                 "time[s],power[mW],force[mN]\n"
                 "0,0,107.0\n2,1500,107.2\n4,1500,118.9\n6,500,124.0\n8,500,121.3\n"
                 "10,500,119.5\n")});
  add(kinds, "staircase",
      "levels held for `hold`, moving between them at `rate` (a testing machine's program)",
      read::staircase,
      {as_power("{type: staircase, levels: [0 W, 1 W, 2 W], hold: 2 s, rate: 1 W/s, "
                "start_time: 1 s}")});
  add(kinds, "sine", "offset + amplitude sin(2 pi f t + phase)", read::sine,
      {as_power("{type: sine, offset: 1 W, amplitude: 0.5 W, frequency: 0.2 Hz, phase: 0.3 rad}")});
  add(kinds, "multisine",
      "Schroeder-phased multisine (7.11)-(7.12) over a band, scaled to a range or with equal "
      "amplitudes",
      read::multisine,
      {as_power("{type: multisine, components: 7, band: [0.01 Hz, 0.1 Hz], range: [0.1 W, 3 W], "
                "phase_offset: 0.5 rad, duration: 10 s}"),
       as_power("{type: multisine, components: 3, band: [0.01 Hz, 0.1 Hz], offset: 1 W, "
                "amplitude: 0.2 W}")});
  add(kinds, "random_steps", "generalised binary noise (7.13)-(7.14) scaled to a range",
      read::random_steps,
      {as_power("{type: random_steps, range: [0.1 W, 3 W], process_time_constant: 2 s, "
                "sample_rate: 20 Hz, max_step_fraction: 0.25, scale_to_range: true, "
                "duration: 10 s}")});
  add(kinds, "log_sweep", "exponential sine sweep over a band", read::log_sweep,
      {as_power("{type: log_sweep, offset: 1 W, amplitude: 0.5 W, band: [0.01 Hz, 1 Hz], "
                "duration: 10 s}")});
  add(kinds, "sequence", "signals one after another, each on its own clock", read::sequence,
      {as_power("{type: sequence, segments: [{duration: 4 s, signal: 1 W}, {duration: 6 s, "
                "signal: 2 W}]}")});
  add(kinds, "periodic", "a signal repeated every period", read::periodic,
      {as_power("{type: periodic, period: 2 s, signal: {type: steps, initial: 0 W, times: [1 s], "
                "values: [1 W]}}")});
  add(kinds, "stepped_sine_sweep",
      "the thesis' control-task sweep (7.3.4): log-spaced sines, a few periods each",
      read::stepped_sine_sweep,
      {as_power("{type: stepped_sine_sweep, offset: 1 W, amplitude: 0.5 W, band: [0.05 Hz, "
                "0.5 Hz], frequencies: 3, periods: 1, start_time: 1 s}")});
  add(kinds, "step_sequence",
      "the thesis' control-task steps (7.3.4): levels visited from the outside in",
      read::step_sequence,
      {as_power("{type: step_sequence, range: [0.5 W, 2 W], steps: 4, hold: 2 s, start_time: 1 s, "
                "initial: 1 W}")});
}

}  // namespace tcpmsim
