#!/usr/bin/python3
"""The default scenario's model in SciPy, for speed and accuracy comparison with tcpmsim.

Model (thesis ch. 7, Table 7.2), states y = [F_T, x_d]:
    dF_T/dt = kappa_P P(t) - kappa_c F_T                    (7.1)
    dx_d/dt = (k2 / c) (x(t) - x_d)                         (7.6), Maxwell-arm form
    F = k1 x + k2 (x - x_d) + F_T + phi_0                   (7.5)
P(t) and x(t) are rebuilt exactly from the /inputs group of a tcpmsim record, so both codes see
the same excitation. solve_ivp(method="BDF") runs segment by segment between the same
breakpoints (it cannot stop at discontinuities by itself), with the same rtol and per-state
atol as tcpmsim, the analytic Jacobian, and dense output at the record's sample times.
"""
import math

import numpy as np
from scipy.integrate import solve_ivp

# Table 7.2 in SI units.
KAPPA_P = 7.2e-3        # N/J
KAPPA_C = 131.6e-3      # 1/s
PHI_0 = 106.9e-3        # N
K1 = 10.8               # N/m
K2 = 2.7                # N/m
DAMPING = 4.3           # N s/m
ATOL = np.array([1e-10, 1e-12])  # tcpmsim's defaults for F_T [N] and x_d [m]


class Signal:
    """A tcpmsim signal rebuilt from its /inputs description."""

    def __init__(self, group):
        self.type = group.attrs["type"]
        if isinstance(self.type, bytes):
            self.type = self.type.decode()
        self.attrs = {k: group.attrs[k] for k in group.attrs}
        self.arrays = {k: group[k][:] for k in group if not hasattr(group[k], "keys")}
        self.parts = [Signal(group[k]) for k in sorted((k for k in group if hasattr(group[k], "keys")),
                                                       key=lambda name: int(name.replace("segment", "")))]

    def value(self, t):
        if self.type == "multisine":
            a, f, p = self.arrays["amplitudes"], self.arrays["frequencies"], self.arrays["phases"]
            return self.attrs["offset"] + float(np.sum(a * np.sin(2 * math.pi * f * t + p)))
        if self.type in ("steps", "random_steps"):
            times = self.arrays["times"]
            k = np.searchsorted(times, t, side="right")
            return self.attrs["initial"] if k == 0 else self.arrays["values"][k - 1]
        if self.type == "constant":
            return self.attrs["value"]
        if self.type == "sequence":
            starts = self.arrays["starts"]
            k = max(0, np.searchsorted(starts, t, side="right") - 1)
            return self.parts[k].value(t - starts[k])
        raise NotImplementedError(self.type)

    def breakpoints(self, offset=0.0):
        if self.type in ("steps", "random_steps"):
            return list(self.arrays["times"] + offset)
        if self.type == "sequence":
            points = []
            for start, part in zip(self.arrays["starts"], self.parts):
                points.append(start + offset)
                points.extend(part.breakpoints(start + offset))
            return points
        return []


def simulate(record, rtol):
    """Integrates the model over the record's time grid. Returns (times, force)."""
    power = Signal(record["inputs/drive.power"])
    deflection = Signal(record["inputs/load.deflection"])
    times = record["time"][:]
    t_end = float(times[-1])
    stops = sorted({b for b in power.breakpoints() + deflection.breakpoints() if 0.0 < b < t_end})
    edges = [0.0] + stops + [t_end]

    jacobian = np.array([[-KAPPA_C, 0.0], [0.0, -K2 / DAMPING]])
    y = np.array([0.0, deflection.value(0.0)])  # rested: F_T = 0, relaxed dashpot
    force = np.empty_like(times)
    for start, stop in zip(edges[:-1], edges[1:]):
        # Signals sampled inside the segment, as tcpmsim does: a step at `stop` is not seen early.
        def inputs(t):
            t = min(max(t, start), math.nextafter(stop, start))
            return power.value(t), deflection.value(t)

        def rhs(t, state):
            p, x = inputs(t)
            return [KAPPA_P * p - KAPPA_C * state[0], K2 / DAMPING * (x - state[1])]

        last = stop == t_end
        mask = (times >= start) & ((times < stop) | last & (times <= stop))
        # Outputs by dense interpolation at the sample times, plus the segment end for the
        # next segment's initial state.
        evaluate_at = np.append(times[mask], stop) if not last else times[mask]
        solution = solve_ivp(rhs, (start, stop), y, method="BDF", rtol=rtol, atol=ATOL,
                             jac=jacobian, t_eval=evaluate_at)
        if not solution.success:
            raise RuntimeError(solution.message)
        for t, (thermal, dashpot), index in zip(solution.t, solution.y.T, np.nonzero(mask)[0]):
            _, x = inputs(t)
            force[index] = K1 * x + K2 * (x - dashpot) + thermal + PHI_0
        y = solution.y[:, -1]
    return times, force
