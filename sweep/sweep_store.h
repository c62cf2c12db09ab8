#pragma once

#include <string>
#include <vector>

#include "sweep/file_lock.h"
#include "sweep/sweep_run.h"
#include "sweep/sweep_spec.h"

namespace tcpmsim::sweep {

// Where a sweep's results live while it runs and after: each finished run is written at once to
// its own file in "<output>.parts/" (under a temporary name, renamed when complete, so a killed
// process leaves no half-written run that looks complete), beside the sweep's identity (its
// file and scenarios as read). merge() gathers them, in run order, into the one output file and
// removes the parts. A resumed sweep finds the runs already done and redoes only the rest; its
// identity must match, so runs of another sweep are never mixed in. Nor do two live sweeps write
// into one parts directory (a --resume while the first still runs, or the ranks of a launcher
// that was killed before them): the process that creates or resumes a sweep holds the parts'
// "sweep.lock" for as long as its store lives, and every process that writes runs holds
// "writers.lock" shared; a sweep that finds either held is refused before it touches a run.
//
// The output file:
//   /summary/id, /summary/<axis or derived parameter>, /summary/<metric>, /summary/status,
//   /summary/message   one row per run, flat 1-D datasets with a `units` attribute
//   /timing/wall_seconds  per run (apart from /summary: it differs from run to run)
//   /runs/<id>/<scenario>/time, /runs/<id>/<scenario>/<group>/<name>  traces, if stored
class SweepStore {
 public:
  // create: a new sweep (fails if parts of an interrupted sweep are there); resume: finish one
  // (fails if its parts are of another sweep); both fail while another sweep writes into the
  // parts. join: the store another process (MPI rank 0) created or resumed, and keeps open while
  // this one lives. Creating or resuming checks the output path first (prepare_output_file): a
  // directory or a device is refused before any run.
  enum class Access { create, resume, join };
  SweepStore(const SweepSpec& spec, std::string output, Access access);

  const std::string& output() const { return output_; }
  // Whether this process sees the store's identity (an MPI rank on another node must).
  bool visible() const;
  // Whether this process holds the parts' writers' lock (shared with the sweep's other
  // processes), as it must before it writes a run. A visible store it joins holds it unless a
  // sweep that is not this one's is opening the parts.
  bool writing() const { return writer_lock_.taken(); }
  // The ids of the runs not yet done, in order.
  std::vector<std::size_t> pending() const;
  // Safe to call from several threads at once: each run has its own file (and HDF5 calls take
  // turns, sim/io/hdf5_files.h).
  void write(const RunResult& result) const;
  // Lets go of this process's lock on the parts once it writes no more runs: under MPI every
  // rank does so before rank 0 merges, since a file still open keeps an NFS directory (or one
  // its client shares with the merging rank) from being removed.
  void finish_writing() const;
  // Writes the output file from the parts (all runs must be done), lets go of the locks and
  // removes the parts. Returns the number of failed runs.
  // `invocation`: the command line, written into the summary.
  std::size_t merge(const std::string& invocation = "") const;

 private:
  std::string part_path(std::size_t id) const;
  // Takes the parts' locks for a sweep that creates or resumes them; throws if another sweep's
  // process holds one.
  void lock_out_other_sweeps();

  const SweepSpec& spec_;
  std::string output_;
  std::string parts_;
  // Mutable: merge and finish_writing let go of them on a store that is otherwise read-only.
  mutable FileLock owner_lock_;
  mutable FileLock writer_lock_;
};

// The text that identifies a sweep: its file and every scenario as read (not where the file
// lies: the same sweep started from another directory resumes).
std::string sweep_identity(const SweepSpec& spec);

}  // namespace tcpmsim::sweep
