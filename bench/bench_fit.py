#!/usr/bin/python3
"""Fit benchmark (issue 12): `tcpmsim fit` of the six force-model parameters (kappa_P, kappa_c,
phi0, k1, k2, c) on 620 s of 16 Hz data (the chapter-7 bench, configs/discover/ch7_protocol.yaml),
from Table 7.2's values and from 20 % away, on 2 threads, with each gradient (forward
sensitivities, forward differences). Target: under 5 s.
Reference in the same run: one simulation of the model replaying the data (bench_integration),
so the fit's cost is also quoted in simulations.
Timings are the median of a few repeats; nothing is asserted.
Usage: bench_fit.py BUILD_DIR"""
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

from chapter7_bench import protocol_record, simulation_seconds

FAR = ("set: [muscle.thermal_force.kappa_P=8.64e-3 N/J, muscle.thermal_force.kappa_c=0.105 1/s, "
       "muscle.mechanics.force_offset=0.0855 N, muscle.mechanics.k1=12.96e-3 N/mm, "
       "muscle.mechanics.k2=2.16e-3 N/mm, muscle.mechanics.damping=5.16e-3 N*s/mm]\n")


def timed(command, repeats=3):
    times, output = [], ""
    for _ in range(repeats):
        started = time.perf_counter()
        output = subprocess.run(command, check=True, capture_output=True, text=True).stdout
        times.append(time.perf_counter() - started)
    return statistics.median(times), output


def main():
    build = sys.argv[1] if len(sys.argv) > 1 else "build"
    tcpmsim = os.path.join(build, "tcpmsim")
    work = tempfile.mkdtemp()
    try:
        data = protocol_record(tcpmsim, os.path.join(work, "bench.h5"))
        simulation = simulation_seconds(build, data)
        print(f"one simulation of the model replaying 620 s at 16 Hz: {simulation * 1e3:.1f} ms")
        far = os.path.join(work, "far.yaml")
        with open("configs/discover/ch7_fit.yaml") as source, open(far, "w") as target:
            text = source.read().replace("model: ch7_base.yaml",
                                         "model: " + os.path.abspath("configs/discover/ch7_base.yaml"))
            target.write(text + FAR)
        for gradient in ("sensitivities", "differences"):
            for name, fit_file in (("from Table 7.2", "configs/discover/ch7_fit.yaml"),
                                   ("from 20 % away", far)):
                seconds, output = timed([tcpmsim, "fit", fit_file, "--data", data, "--jobs", "2",
                                         "--set", "gradient=" + gradient,
                                         "--out", os.path.join(work, "fit")])
                simulations = int(re.search(r"(\d+) simulations", output).group(1))
                print(f"fit {name}, gradient by {gradient}: {seconds:.2f} s wall on 2 threads "
                      f"({seconds / simulation:.0f} simulation times; {simulations} runs) "
                      f"[target < 5 s]")
    finally:
        shutil.rmtree(work)


if __name__ == "__main__":
    main()
