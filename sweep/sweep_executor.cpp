#include "sweep/sweep_executor.h"

#include <atomic>

#include "sweep/run_pool.h"
#include "sweep/sweep_run.h"
#include "sweep/sweep_store.h"

namespace tcpmsim::sweep {
namespace {

// The threads of one process take the pending runs in order.
class LocalDispenser final : public RunDispenser {
 public:
  explicit LocalDispenser(std::size_t count) : count_(count) {}
  std::optional<std::size_t> next() override {
    const std::size_t slot = next_.fetch_add(1);
    if (slot >= count_) return std::nullopt;
    return slot;
  }

 private:
  std::size_t count_;
  std::atomic<std::size_t> next_{0};
};

}  // namespace

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
  LocalDispenser dispenser(pending.size());
  run_slots(spec, store, pending, options.threads, dispenser, loader, [&](std::size_t done) {
    if (progress) progress(outcome.resumed + done, outcome.runs);
  });
  outcome.failed = store.merge();
  return outcome;
}

}  // namespace tcpmsim::sweep
