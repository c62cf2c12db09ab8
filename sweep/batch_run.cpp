#include "sweep/batch_run.h"

#include <map>

#include "kinds/standard_kinds.h"
#include "sim/config/config_error.h"
#include "sweep/run_pool.h"

namespace tcpmsim::sweep {

std::vector<BatchRun> run_batch(const BatchOptions& options,
                                std::shared_ptr<const UnitSystem> units,
                                const std::function<void(std::size_t, std::size_t)>& progress) {
  std::vector<Scenario> scenarios;
  std::map<std::string, std::string> files_by_name;
  for (const auto& config : options.configs) {
    scenarios.push_back(load_scenario(config, options.overrides, units));
    scenarios.back().invocation = options.invocation;
    check_record_size(scenarios.back(), options.max_record_bytes);
    const std::string& name = scenarios.back().settings.name;
    if (const auto [earlier, added] = files_by_name.emplace(name, config); !added)
      throw ConfigError({config, 0, 0, {}}, "scenario.name",
                        "'" + name + "' is also the scenario of " + earlier->second +
                            ": their records would both be " + options.output_directory + "/" +
                            name + ".h5");
  }
  std::vector<BatchRun> runs(scenarios.size());
  CountingDispenser dispenser(scenarios.size());
  run_slots(
      scenarios.size(), options.threads, dispenser,
      [&](std::size_t slot) {
        runs[slot].config = options.configs[slot];
        runs[slot].outcome =
            run_scenario(scenarios[slot],
                         options.output_directory + "/" + scenarios[slot].settings.name + ".h5");
      },
      [&](std::size_t done) {
        if (progress) progress(done, scenarios.size());
      });
  return runs;
}

}  // namespace tcpmsim::sweep
