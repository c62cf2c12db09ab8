#!/usr/bin/python3
"""Benchmark: tcpmsim against the same model in SciPy (solve_ivp BDF) on the default scenario.

Both integrate the chapter-7 model over the identification protocol (400 s, 61 segments
between input discontinuities) at the same rtol and per-state atol, and evaluate the force
at every 16 Hz sample. Measurements are interleaved (tcpmsim, SciPy, tcpmsim, ...) and each
ratio is formed from neighbouring measurements, so drifts in CPU speed cancel.

Reported:
  integration  tcpmsim's in-process integration with all outputs sampled into memory
               (bench_integration) against SciPy's integration with its force samples;
  end to end   a whole `tcpmsim run` process (start-up, units database, config, HDF5
               writing) against the same SciPy integration;
  accuracy     the largest force difference between the codes, and each one's error against
               a tcpmsim run at rtol 1e-12.
Timings are reported, never asserted.

Usage: bench_default_scenario.py BUILD_DIR CONFIG [--rounds N]
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


def tcpmsim_process(binary, config, output, extra=()):
    started = time.perf_counter()
    subprocess.run([binary, "run", config, "-o", output, "--quiet", *extra], check=True)
    return time.perf_counter() - started


def tcpmsim_integration(bench, config):
    line = subprocess.run([bench, config, "20"], check=True, capture_output=True, text=True).stdout
    return float(re.search(r"median_seconds=([0-9.e+-]+)", line).group(1)), line.strip()


def scipy_integration(record, rtol):
    started = time.perf_counter()
    _, force = scipy_reference.simulate(record, rtol)
    return time.perf_counter() - started, force


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("build_dir")
    parser.add_argument("config")
    parser.add_argument("--rounds", type=int, default=5)
    arguments = parser.parse_args()
    binary = os.path.join(arguments.build_dir, "tcpmsim")
    bench = os.path.join(arguments.build_dir, "bench", "bench_integration")

    with tempfile.TemporaryDirectory() as work:
        record_path = os.path.join(work, "run.h5")
        reference_path = os.path.join(work, "reference.h5")
        tcpmsim_process(binary, arguments.config, record_path)
        tcpmsim_process(binary, arguments.config, reference_path, ["--set", "solver.rtol=1e-12"])
        with h5py.File(record_path, "r") as record, h5py.File(reference_path, "r") as reference:
            rtol = float(record.attrs["rtol"])
            tcpmsim_force = record["muscle/force"][:]
            exact = reference["muscle/force"][:]
            samples = record["time"].size
            steps = int(record.attrs["solver_steps"])
            segments = int(record.attrs["solver_segments"])
            integration_ratios, process_ratios = [], []
            integration_times, process_times, scipy_times = [], [], []
            for _ in range(arguments.rounds):
                integration, bench_line = tcpmsim_integration(bench, arguments.config)
                process = tcpmsim_process(binary, arguments.config, os.path.join(work, "timed.h5"))
                scipy_time, scipy_force = scipy_integration(record, rtol)
                integration_times.append(integration)
                process_times.append(process)
                scipy_times.append(scipy_time)
                integration_ratios.append(scipy_time / integration)
                process_ratios.append(scipy_time / process)

    print(f"default scenario {arguments.config}: {samples} samples, {segments} segments, "
          f"{steps} CVODE steps, rtol {rtol:g}")
    print(f"  tcpmsim integration {statistics.median(integration_times) * 1e3:7.2f} ms  (last round: {bench_line})")
    print(f"  tcpmsim end to end  {statistics.median(process_times) * 1e3:7.2f} ms per `tcpmsim run` process")
    print(f"  SciPy BDF           {statistics.median(scipy_times) * 1e3:7.2f} ms integration")
    print(f"  speed-up, integration: {statistics.median(integration_ratios):.0f}x "
          f"(range {min(integration_ratios):.0f}-{max(integration_ratios):.0f} over {arguments.rounds} rounds)")
    print(f"  speed-up, end to end:  {statistics.median(process_ratios):.0f}x "
          f"(range {min(process_ratios):.0f}-{max(process_ratios):.0f})")
    print(f"  max |F_tcpmsim - F_SciPy| = {np.max(np.abs(tcpmsim_force - scipy_force)):.2e} N "
          f"(force range {tcpmsim_force.min():.3f}-{tcpmsim_force.max():.3f} N)")
    print(f"  error against the rtol-1e-12 run: tcpmsim {np.max(np.abs(tcpmsim_force - exact)):.2e} N, "
          f"SciPy {np.max(np.abs(scipy_force - exact)):.2e} N")


if __name__ == "__main__":
    main()
