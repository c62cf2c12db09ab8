#include "sweep/sweep_executor.h"

#include "sweep/run_pool.h"
#include "sweep/sweep_run.h"
#include "sweep/sweep_store.h"

namespace tcpmsim::sweep {

SweepOutcome run_sweep(const SweepSpec& spec, const SweepOptions& options,
                       std::shared_ptr<const UnitSystem> units, const SweepProgress& progress) {
  const SweepStore store(spec, options.output,
                         options.resume ? SweepStore::Access::resume : SweepStore::Access::create);
  const std::vector<std::size_t> pending = store.pending();
  SweepOutcome outcome;
  outcome.runs = spec.runs.size();
  outcome.resumed = outcome.runs - pending.size();
  outcome.output = store.output();
  ScenarioLoader loader(std::move(units));
  CountingDispenser dispenser(pending.size());
  run_slots(
      pending.size(), options.threads, dispenser,
      [&](std::size_t slot) { store.write(execute_run(spec, pending[slot], loader)); },
      [&](std::size_t done) {
        if (progress) progress(outcome.resumed + done, outcome.runs);
      });
  outcome.failed = store.merge(options.invocation);
  return outcome;
}

}  // namespace tcpmsim::sweep
