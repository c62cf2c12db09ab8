#!/usr/bin/python3
"""Benchmark: tcpmsim against the same model in SciPy (solve_ivp BDF), on the default scenario.

Prints the wall-time ratios and the largest difference between the two force trajectories,
and each code's error against a tight-tolerance tcpmsim reference (rtol 1e-12), so the speed is
compared at equal accuracy. Timings are reported, never asserted.

Usage: bench_default_scenario.py TCPMSIM_BINARY CONFIG [--repeat N]
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import scipy_reference  # noqa: E402


def run_tcpmsim(binary, config, output, extra=()):
    """One process run; returns (process wall time, the run's own wall time)."""
    started = time.perf_counter()
    completed = subprocess.run([binary, "run", config, "-o", output, *extra], check=True,
                               capture_output=True, text=True)
    process = time.perf_counter() - started
    inside = float(re.search(r"; ([0-9.e+-]+) s wall", completed.stdout).group(1))
    return process, inside


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("binary")
    parser.add_argument("config")
    parser.add_argument("--repeat", type=int, default=15)
    arguments = parser.parse_args()

    with tempfile.TemporaryDirectory() as work:
        record_path = os.path.join(work, "run.h5")
        reference_path = os.path.join(work, "reference.h5")
        runs = [run_tcpmsim(arguments.binary, arguments.config, record_path) for _ in range(arguments.repeat)]
        tcpmsim_process = statistics.median(r[0] for r in runs)
        tcpmsim_inside = statistics.median(r[1] for r in runs)
        run_tcpmsim(arguments.binary, arguments.config, reference_path, ["--set", "solver.rtol=1e-12"])

        with h5py.File(record_path, "r") as record, h5py.File(reference_path, "r") as reference:
            rtol = float(record.attrs["rtol"])
            tcpmsim_force = record["muscle/force"][:]
            exact = reference["muscle/force"][:]
            scipy_times = []
            for _ in range(3):
                started = time.perf_counter()
                times, scipy_force = scipy_reference.simulate(record, rtol)
                scipy_times.append(time.perf_counter() - started)
            scipy_time = statistics.median(scipy_times)
            steps = int(record.attrs["solver_steps"])
            segments = int(record.attrs["solver_segments"])

    difference = np.max(np.abs(tcpmsim_force - scipy_force))
    print(f"default scenario ({arguments.config}): {len(times)} samples, {segments} segments, "
          f"rtol {rtol:g}")
    print(f"  tcpmsim   {tcpmsim_process * 1e3:8.1f} ms per process (median of {arguments.repeat}), "
          f"{tcpmsim_inside * 1e3:6.1f} ms inside the run (integration + HDF5), {steps} steps")
    print(f"  SciPy BDF {scipy_time * 1e3:8.1f} ms integration only (median of 3)")
    print(f"  speed-up: {scipy_time / tcpmsim_process:6.0f}x per process, "
          f"{scipy_time / tcpmsim_inside:6.0f}x per run")
    print(f"  max |F_tcpmsim - F_scipy| = {difference:.3e} N")
    print(f"  error against rtol-1e-12 reference: tcpmsim {np.max(np.abs(tcpmsim_force - exact)):.3e} N, "
          f"SciPy {np.max(np.abs(scipy_force - exact)):.3e} N")


if __name__ == "__main__":
    main()
