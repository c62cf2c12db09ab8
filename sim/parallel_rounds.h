#pragma once

#include <functional>
#include <vector>

namespace tcpmsim {

// Runs the tasks of `first`, then those `second` names once every task of `first` is finished,
// on `threads` threads (the caller's among them), and returns that second round. Tasks are the
// caller's ids below `task_count`; `run(k)` writes only task k's result. `second(finished)` is
// called under a lock after the results of the tasks marked finished are written, and reads
// only those.
//
// The second round is guessed ahead: once the first `lead` tasks of `first` are finished (the
// ones the choice depends on most), a thread starts a task that `second` names for the tasks
// finished so far before the rest of `first`, and a thread that finds no task of `first` left
// does the same rather than idle. If the final choice drops a guessed task, its result is
// simply not asked for; a task's result never depends on when it ran, so what is returned, and
// every result in it, is the same on any number of threads.
// A task that throws: the first such of `first` and the final second round, in id order, is
// rethrown as it was thrown, once all threads are done. `first` must hold distinct ids below
// `task_count` (std::invalid_argument) and `second` must name none of them
// (std::logic_error); an exception from `second` stops every thread from starting another task
// and is rethrown once all are done.
std::vector<std::size_t> run_two_rounds(
    const std::vector<std::size_t>& first, std::size_t lead,
    const std::function<std::vector<std::size_t>(const std::vector<char>& finished)>& second,
    std::size_t task_count, int threads, const std::function<void(std::size_t)>& run);

}  // namespace tcpmsim
