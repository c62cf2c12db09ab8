// The MPI part of sweeps: built only when CMake finds an MPI (TCPMSIM_WITH_MPI).
#include <mpi.h>

#include <cstdint>
#include <mutex>
#include <optional>
#include <stdexcept>

#include "sweep/run_pool.h"
#include "sweep/sweep_mpi.h"
#include "sweep/sweep_store.h"

namespace tcpmsim::sweep {
namespace {

void check(int code, const char* call) {
  if (code != MPI_SUCCESS) throw std::runtime_error(std::string("MPI failed in ") + call);
}

// MPI for the length of one sweep. Serialised threads: the worker threads of a rank call MPI
// one at a time (RunDispenser::next under a mutex).
class MpiSession {
 public:
  MpiSession() {
    int provided = 0;
    check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided), "MPI_Init_thread");
    serialised_ = provided >= MPI_THREAD_SERIALIZED;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
  }
  ~MpiSession() { MPI_Finalize(); }
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }
  bool serialised() const { return serialised_; }

 private:
  int rank_ = 0;
  int size_ = 1;
  bool serialised_ = false;
};

// `root`'s text on every rank.
std::string broadcast_text(std::string text, int root) {
  long length = static_cast<long>(text.size());
  MPI_Bcast(&length, 1, MPI_LONG, root, MPI_COMM_WORLD);
  text.resize(static_cast<std::size_t>(length));
  if (length > 0) MPI_Bcast(text.data(), static_cast<int>(length), MPI_CHAR, root, MPI_COMM_WORLD);
  return text;
}

// Every rank's problem (empty: none) decided together: if any rank has one, the lowest such
// rank's message is thrown on every rank, so no rank waits for one that failed and the cause
// reaches rank 0, which reports it.
void fail_together(const MpiSession& session, const std::string& problem) {
  const int mine = problem.empty() ? session.size() : session.rank();
  int first = session.size();
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (first == session.size()) return;
  const std::string message = broadcast_text(problem, first);
  throw std::runtime_error(first == 0 ? message : "rank " + std::to_string(first) + ": " + message);
}

// What `action` threw, as text ("" if nothing).
template <typename Action>
std::string problem_of(Action action) {
  try {
    action();
  } catch (const std::exception& error) {
    return error.what()[0] != '\0' ? error.what() : "unknown error";
  } catch (...) {
    return "unknown error";
  }
  return "";
}

template <typename Action>
void on_rank_zero(const MpiSession& session, Action action) {
  fail_together(session, session.rank() == 0 ? problem_of(action) : std::string());
}

std::vector<std::size_t> broadcast(std::vector<std::size_t> values) {
  std::uint64_t count = values.size();
  MPI_Bcast(&count, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
  std::vector<std::uint64_t> buffer(values.begin(), values.end());
  buffer.resize(count);
  if (count > 0) MPI_Bcast(buffer.data(), static_cast<int>(count), MPI_UINT64_T, 0, MPI_COMM_WORLD);
  return {buffer.begin(), buffer.end()};
}

// A counter in rank 0's memory, advanced by atomic fetch-and-add from any rank.
class SharedCounter final : public RunDispenser {
 public:
  SharedCounter(std::size_t count, int rank) : count_(count) {
    const MPI_Aint size = rank == 0 ? sizeof(std::int64_t) : 0;
    check(MPI_Win_allocate(size, sizeof(std::int64_t), MPI_INFO_NULL, MPI_COMM_WORLD, &base_,
                           &window_),
          "MPI_Win_allocate");
    if (rank == 0) {
      MPI_Win_lock(MPI_LOCK_EXCLUSIVE, 0, 0, window_);
      *base_ = 0;
      MPI_Win_unlock(0, window_);
    }
    MPI_Barrier(MPI_COMM_WORLD);  // nobody counts before it is zero
  }
  ~SharedCounter() override {
    MPI_Barrier(MPI_COMM_WORLD);
    MPI_Win_free(&window_);
  }
  SharedCounter(const SharedCounter&) = delete;
  SharedCounter& operator=(const SharedCounter&) = delete;

  std::optional<std::size_t> next() override {
    const std::lock_guard lock(mutex_);
    const std::int64_t one = 1;
    std::int64_t slot = 0;
    MPI_Win_lock(MPI_LOCK_SHARED, 0, 0, window_);
    MPI_Fetch_and_op(&one, &slot, MPI_INT64_T, 0, 0, MPI_SUM, window_);
    MPI_Win_unlock(0, window_);
    handed_out_ = static_cast<std::size_t>(slot) + 1;
    if (static_cast<std::size_t>(slot) >= count_) return std::nullopt;
    return static_cast<std::size_t>(slot);
  }
  // Runs handed out to all ranks so far, as this rank last saw the counter.
  std::size_t handed_out() const {
    const std::lock_guard lock(mutex_);
    return std::min(handed_out_, count_);
  }

 private:
  std::size_t count_;
  std::int64_t* base_ = nullptr;
  MPI_Win window_{};
  mutable std::mutex mutex_;
  std::size_t handed_out_ = 0;
};

}  // namespace

bool mpi_available() {
  return true;
}

SweepOutcome run_sweep_mpi(const SweepSpec& spec, const SweepOptions& options,
                           std::shared_ptr<const UnitSystem> units, const SweepProgress& progress) {
  const MpiSession session;
  const auto access = options.resume ? SweepStore::Access::resume : SweepStore::Access::create;
  std::vector<std::size_t> pending;
  // Rank 0 keeps the store it opened, and with it the parts' lock, until the sweep ends: no other
  // sweep starts into them meanwhile. The other ranks join it.
  std::optional<SweepStore> opened;
  on_rank_zero(session, [&] { pending = opened.emplace(spec, options.output, access).pending(); });
  pending = broadcast(std::move(pending));
  std::optional<SweepStore> joined;
  if (!opened) joined.emplace(spec, options.output, SweepStore::Access::join);
  const SweepStore& store = opened ? *opened : *joined;
  // Every rank must see the store rank 0 opened, or its runs would be written where the merge
  // never looks.
  fail_together(session, !store.visible()
                             ? "cannot see " + options.output +
                                   ".parts/, which rank 0 created: the output must be on a file "
                                   "system every rank shares"
                         : !store.writing() ? "cannot lock " + options.output +
                                                  ".parts/ for writing: another "
                                                  "sweep is opening it"
                                            : std::string());
  SweepOutcome outcome;
  outcome.runs = spec.runs.size();
  outcome.resumed = outcome.runs - pending.size();
  outcome.output = store.output();
  ScenarioLoader loader(std::move(units));
  std::string local_problem;
  {
    SharedCounter counter(pending.size(), session.rank());
    try {
      run_slots(
          pending.size(), session.serialised() ? options.threads : 1, counter,
          [&](std::size_t slot) { store.write(execute_run(spec, pending[slot], loader)); },
          [&](std::size_t) {
            // Rank 0 reports the runs handed out so far (every rank's).
            if (progress && session.rank() == 0)
              progress(outcome.resumed + counter.handed_out(), outcome.runs);
          });
    } catch (const std::exception& error) {
      local_problem = error.what();
    }
  }
  // Every rank lets go of the parts before rank 0 merges and removes them.
  store.finish_writing();
  // A rank that failed to store a run fails the sweep everywhere; its runs are redone on resume.
  int failed_here = local_problem.empty() ? 0 : 1, failed_anywhere = 0;
  MPI_Allreduce(&failed_here, &failed_anywhere, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  if (failed_anywhere != 0)
    throw std::runtime_error(local_problem.empty() ? "another rank failed to store its runs"
                                                   : local_problem);
  std::uint64_t failed = 0;
  on_rank_zero(session, [&] { failed = store.merge(options.invocation); });
  MPI_Bcast(&failed, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
  outcome.failed = failed;
  return outcome;
}

}  // namespace tcpmsim::sweep
