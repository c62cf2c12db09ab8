#!/usr/bin/python3
"""discover benchmark (issue 12): a full `tcpmsim discover` over every candidate of the effect
catalogue on 620 s of 16 Hz chapter-7 data (power and deflection replayed; force and L*
compared) holding a hidden hysteresis, on 2 threads. Target: under 2 minutes.
Reference in the same run: one simulation of the base model replaying the data
(bench_integration), so the workflow's cost is also quoted in simulations. Nothing is asserted.
Usage: bench_discover.py BUILD_DIR"""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

from chapter7_bench import protocol_record, simulation_seconds


def main():
    build = sys.argv[1] if len(sys.argv) > 1 else "build"
    tcpmsim = os.path.join(build, "tcpmsim")
    work = tempfile.mkdtemp()
    try:
        inputs = protocol_record(tcpmsim, os.path.join(work, "inputs.h5"))
        data = os.path.join(work, "measured.csv")
        subprocess.run([tcpmsim, "measure", "configs/discover/ch7_base.yaml", "--set",
                        "measurement.file=" + inputs, "--set",
                        "muscle.effects=[{type: hysteresis, stiffness: 50 N/m, force: 6 mN}]",
                        "--bench", "configs/discover/ch7_bench.yaml", "-o", data, "-q"], check=True)
        simulation = simulation_seconds(build, data)
        print(f"one simulation of the base model replaying 620 s at 16 Hz: {simulation * 1e3:.1f} ms")
        out = os.path.join(work, "discover")
        started = time.perf_counter()
        subprocess.run([tcpmsim, "discover", "--model", "configs/discover/ch7_base.yaml", "--data",
                        data, "--inputs", "power,deflection", "--outputs",
                        "force,inductance_measure", "--validate-from", "400", "--out", out,
                        "--jobs", "2", "--no-plots", "-q"], check=False)
        seconds = time.perf_counter() - started
        with open(os.path.join(out, "discovery.json"), encoding="utf-8") as file:
            found = json.load(file)
        fitted = [c for c in found["ranking"] if c["status"] == "fitted"]
        slowest = max(fitted, key=lambda c: c["seconds"])
        total = sum(c.get("seconds", 0.0) for c in found["ranking"])
        print(f"discover over {len(found['ranking'])} candidates (force and L*): {seconds:.1f} s "
              f"wall on 2 threads, {found['simulations']} runs ({seconds / simulation:.0f} "
              f"simulation times); verdict {found['verdict']} [target < 120 s]")
        print(f"  base fit {found['baseline']['simulations']} runs; slowest candidate "
              f"{slowest['effect']} [{slowest['member']}] {slowest['seconds']:.1f} s "
              f"({slowest['simulations']} runs); the candidates' fits {total:.1f} s in all, "
              f"{found['baseline']['candidate_rounds']} round(s)")
        for c in found["ranking"]:
            print(f"    {c['effect']} [{c['member']}]: {c.get('seconds', 0.0):.1f} s, "
                  f"{c.get('simulations', 0)} runs, {c.get('iterations', 0)} iterations")
    finally:
        shutil.rmtree(work)


if __name__ == "__main__":
    main()
