#!/usr/bin/env python3
"""The CI sweep's physical law (issue 11): on every run of configs/sweeps/thermal_hA_C.yaml the
measured thermal time constant equals C / hA, to 1e-6 (the step scenario integrates at rtol
1e-10: the error falls with the tolerance, 1e-5 at rtol 1e-8), every run succeeded, and every
closed-loop bandwidth was measured and falls as C grows at fixed hA.
Usage: check_thermal_law.py SWEEP.h5"""
import sys

import h5py
import numpy as np

with h5py.File(sys.argv[1], "r") as f:
    s = f["summary"]
    conductance = s["muscle.thermal.conductance"][:]
    capacity = s["muscle.thermal.heat_capacity"][:]
    tau = s["time_constant"][:]
    bandwidth = s["force_bandwidth"][:]
    status = [x.decode() for x in s["status"][:]]
    assert s["time_constant"].attrs["units"] == "s"

error = np.abs(tau / (capacity / conductance) - 1.0)
print(f"{len(tau)} runs; largest |tau / (C / hA) - 1| = {error.max():.2e} (run {error.argmax()})")
failures = []
if any(x != "ok" for x in status):
    failures.append(f"failed runs: {[i for i, x in enumerate(status) if x != 'ok']}")
if not np.all(error < 1e-6):
    failures.append(f"time constants off C / hA: runs {np.nonzero(error >= 1e-6)[0].tolist()}")
if not np.all(np.isfinite(bandwidth)):
    failures.append("a bandwidth is missing")
for h in np.unique(conductance):
    row = bandwidth[conductance == h][np.argsort(capacity[conductance == h])]
    print(f"  hA = {h * 1e3:6.1f} mW/K: bandwidth {', '.join(f'{b * 1e3:.1f}' for b in row)} mHz "
          "for C rising")
    if not np.all(np.diff(row) < 0):
        failures.append(f"bandwidth does not fall with C at hA = {h}")
if failures:
    sys.exit("check_thermal_law: " + "; ".join(failures))
print("check_thermal_law: ok")
