#!/usr/bin/python3
"""Sweep benchmark (issue 11): throughput, parallel efficiency, per-run overhead, and the cost of
compressing a record.

  throughput   runs/s of bench/sweep_throughput.yaml (24 runs) on 1 and 2 threads and under
               mpirun -n 2 (whole processes: loading, runs, storing, merging); parallel
               efficiency = rate(2) / (2 rate(1)). Target >= 90 % on 2 cores.
  overhead     the sweep's time per run on one thread against the integration alone of the
               same scenario (bench_integration, in-process, all outputs kept in memory):
               configuration, context set-up, metrics, part files and the merge. Target < 5 %.
               Measured metrics-only and with decimated traces.
  compression  1000 s of the default scenario at 100 Hz: the integration alone against a whole
               `tcpmsim run` writing an uncompressed record (the default) and a deflated one.
Timings are the median of a few repeats; nothing is asserted.
Usage: bench_sweep.py BUILD_DIR"""
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

SWEEP = "bench/sweep_throughput.yaml"
RUNS = 24
MPI_ENV = {"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"}


def timed(command, repeats=3, env=None, fresh=None):
    """Median wall time of `command`; `fresh` is removed before each repeat (outside the timing:
    overwriting a file makes the kernel drop its pages, which is not the writer's cost)."""
    times = []
    for _ in range(repeats):
        if fresh and os.path.exists(fresh):
            os.remove(fresh)
        started = time.perf_counter()
        subprocess.run(command, check=True, stdout=subprocess.DEVNULL,
                       env={**os.environ, **(env or {})})
        times.append(time.perf_counter() - started)
    return statistics.median(times)


def integration_seconds(bench, config, overrides, repeats):
    line = subprocess.run([bench, config, str(repeats), *overrides], check=True,
                          capture_output=True, text=True).stdout
    return float(re.search(r"median_seconds=([0-9.e+-]+)", line).group(1))


def main():
    build = sys.argv[1] if len(sys.argv) > 1 else "build"
    tcpmsim = os.path.join(build, "tcpmsim")
    bench = os.path.join(build, "bench", "bench_integration")
    work = tempfile.mkdtemp()
    try:
        out = os.path.join(work, "sweep.h5")
        sweep = [tcpmsim, "sweep", SWEEP, "-q", "-o", out]
        one = timed(sweep + ["--jobs", "1"])
        two = timed(sweep + ["--jobs", "2"])
        rates = {"1 thread": RUNS / one, "2 threads": RUNS / two}
        if shutil.which("mpirun"):
            mpirun = ["mpirun", "-n", "2", "--oversubscribe"]
            mpi = timed(mpirun + [tcpmsim, "sweep", SWEEP, "-q", "-o", out], env=MPI_ENV)
            rates["mpirun -n 2"] = RUNS / mpi
            # Starting an MPI job (mpirun, MPI_Init, the window, MPI_Finalize) costs a fixed time,
            # paid once per job: a one-run sweep under mpirun against the same without it.
            startup = ["sweep", "bench/sweep_startup.yaml", "-q", "-o", os.path.join(work, "one.h5")]
            fixed = timed(mpirun + [tcpmsim, *startup], repeats=5, env=MPI_ENV) - timed(
                [tcpmsim, *startup], repeats=5)
            rates[f"mpirun -n 2 without the job's start-up ({fixed:.2f} s)"] = RUNS / (mpi - fixed)
        for name, rate in rates.items():
            efficiency = rate / (2 * rates["1 thread"]) if name != "1 thread" else 1.0
            print(f"throughput, {name}: {rate:.1f} runs/s"
                  + (f", parallel efficiency {efficiency * 100:.0f} % (target >= 90 %)"
                     if name != "1 thread" else ""))

        # The same 24 runs alone: the integration of each, at the sweep's values, in-process.
        import h5py
        with h5py.File(out, "r") as f:
            hA = f["summary/muscle.thermal.conductance"][:]
            kappa = f["summary/estimator.thermal.kappa_c"][:]
        alone = statistics.mean(
            integration_seconds(bench, "configs/sweeps/thermal_force_loop.yaml",
                                [f"muscle.thermal.conductance={h!r} W/K",
                                 f"estimator.thermal.kappa_c={k!r} 1/s"], 1)
            for h, k in zip(hA, kappa))
        decimated = timed(sweep + ["--jobs", "1", "--set", "store={traces: decimated, interval: 1 s}"])
        for name, total in (("metrics only", one), ("decimated traces (1 s)", decimated)):
            per_run = total / RUNS
            print(f"per-run overhead, {name}: {per_run * 1e3:.1f} ms per run against "
                  f"{alone * 1e3:.1f} ms of integration of the same runs: "
                  f"{(per_run / alone - 1) * 100:+.1f} % (target < 5 %)")

        config = "configs/ch7_identification.yaml"
        record = os.path.join(work, "record.h5")
        start = timed([tcpmsim, "--version"], repeats=7)
        print(f"program start-up (tcpmsim --version, loading its shared libraries): "
              f"{start * 1e3:.0f} ms")
        for label, longer in (("as shipped (400 s at 16 Hz)", []),
                              ("1000 s at 100 Hz", ["scenario.duration=1000 s",
                                                    "output.rate=100 Hz"])):
            compare_compression(tcpmsim, bench, config, record, label, longer)
    finally:
        shutil.rmtree(work)


def compare_compression(tcpmsim, bench, config, record, label, longer):
    """The default scenario recorded uncompressed and deflated, against its integration."""
    integration = integration_seconds(bench, config, longer, 10)
    sets = [item for override in longer for item in ("--set", override)]
    for name, extra in (("uncompressed (default)", []),
                        ("deflate level 1", ["--set", "output.compression=deflate"])):
        total = timed([tcpmsim, "run", config, "-q", "-o", record, *sets, *extra], repeats=7,
                      fresh=record)
        walls = []
        for _ in range(7):  # run_scenario's own time: integration, recording, closing
            if os.path.exists(record):
                os.remove(record)
            line = subprocess.run([tcpmsim, "run", config, "-o", record, *sets, *extra],
                                  check=True, capture_output=True, text=True).stdout
            walls.append(float(re.search(r"([0-9.e+-]+) s wall", line).group(1)))
        wall = statistics.median(walls)
        print(f"default scenario, {label}, {name}: integration and record "
              f"{wall * 1e3:.1f} ms = {wall / integration:.1f}x the integration alone "
              f"({integration * 1e3:.1f} ms); whole process {total * 1e3:.0f} ms; "
              f"file {os.path.getsize(record) / 1e6:.2f} MB")


if __name__ == "__main__":
    main()
