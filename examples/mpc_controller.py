"""A constrained model-predictive controller on the chapter-7 force and deflection tasks, beside
the thesis' PID: the "control methods better equipped to deal with a limited control-action
space" the thesis asks for (section 8.3).

The MPC closes the loop from Python through tcpmsim.Simulator on the scenarios with the loop
opened (configs/ch7_control/external_*.yaml: plant, Muscle Drive, self-sensing estimator, seed
and task of the built-in PID's scenarios). Each PWM sample (20 Hz, as the PID) it

- reads the self-sensed estimate (the controller sees no more than the PID does);
- predicts with a linear model of (7.1) and (7.5)-(7.6) under the task's load (the deflection
  held at 20 mm, or the force held at 0.40 N), plus the estimator's low-pass on the deflection,
  discretised exactly for the held power. Its parameters are the estimator's own copy of
  Table 7.2, read from the scenario: the model is not the plant;
- is offset-free: the model runs on the powers sent, and the difference between the estimate
  and the model's output is a disturbance held over the horizon;
- solves one QP (python3-cvxopt): minimise sum_j (y_j - r)^2 / s^2 + rho sum_j (u_j - u_j-1)^2
  over a move-blocked horizon of 10 s, subject to P_min <= u_j <= P_max (7.9), the limits the
  PID saturates at. The reference is held over the horizon: no preview, as the PID has none.

Both controllers run without the calibration of section 7.3.4, on the same seed; the analysis
is tcpmsim.control_task's, the one `tcpmsim control-tasks` makes (rise times, bandwidth), with
each step's overshoot beyond its new reference and the tracking RMSE over the task. Prints the
comparison table (the README's) and draws results/examples/mpc_vs_pid.png.

    examples/mpc_controller.py            # the four tasks: steps and sweeps, about 80 s
    examples/mpc_controller.py --steps    # the step tasks only, about 8 s
"""
import argparse
import os
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from cvxopt import matrix, solvers  # noqa: E402
from scipy.linalg import cho_factor, cho_solve, expm  # noqa: E402

import tcpmsim  # noqa: E402

CONFIGS = "configs/ch7_control"
SWEEP_REFERENCE = {"force": "{type: stepped_sine_sweep, offset: 0.40 N, amplitude: 0.05 N, "
                            "start_time: 40 s}",
                   "deflection": "{type: stepped_sine_sweep, offset: 20 mm, amplitude: 5 mm, "
                                 "start_time: 40 s}"}
HORIZON_BLOCKS = [1, 1, 2, 4, 8, 16, 24, 32, 48, 64]  # samples each move is held: 200 = 10 s
solvers.options.update({"show_progress": False, "abstol": 1e-9, "reltol": 1e-8,
                        "feastol": 1e-9})


def linear_model(simulator, target):
    """(A, B, e, C, Cm) of dz/dt = A z + B P + e, the tracked output C z and the measured output
    Cm z (as the estimator reports it), from the estimator's parameters (SI).

    Force task, z = [F_T]: (7.1) dF_T/dt = kappa_P P - kappa_c F_T; with the deflection held,
    (7.6)'s F_l is constant and (7.5) F = F_l + F_T + phi_0 differs from F_T by a constant the
    disturbance carries.
    Deflection task, z = [F_T, x, x_f]: the load holds F, so (7.5) gives F_l = F - phi_0 - F_T
    and (7.6) becomes (k1 + k2) dx/dt = -dF_T/dt + (k2 / c)(F - phi_0 - F_T) - (k1 k2 / c) x;
    x_f is the estimator's first-order low-pass of x (its filters' cut-off)."""
    p = simulator.parameter
    kappa_p, kappa_c = p("estimator.thermal.kappa_P"), p("estimator.thermal.kappa_c")
    if target == "force":
        return (np.array([[-kappa_c]]), np.array([kappa_p]), np.zeros(1), np.array([1.0]),
                np.array([1.0]))
    k1, k2 = p("estimator.mechanics.k1"), p("estimator.mechanics.k2")
    c, phi0 = p("estimator.mechanics.damping"), p("estimator.mechanics.force_offset")
    load = p("load.force")
    cutoff = 2 * np.pi * p("estimator.filters.low_pass_cutoff")
    a = np.array([[-kappa_c, 0.0, 0.0],
                  [(kappa_c - k2 / c) / (k1 + k2), -(k1 * k2 / c) / (k1 + k2), 0.0],
                  [0.0, cutoff, -cutoff]])
    b = np.array([kappa_p, -kappa_p / (k1 + k2), 0.0])
    e = np.array([0.0, (k2 / c) * (load - phi0) / (k1 + k2), 0.0])
    return a, b, e, np.array([0.0, 1.0, 0.0]), np.array([0.0, 0.0, 1.0])


def discretise(a, b, e, dt):
    """Exact zero-order hold of dz/dt = A z + B P + e over dt: z+ = Ad z + Bd P + ed."""
    n = len(b)
    augmented = np.zeros((n + 2, n + 2))
    augmented[:n, :n], augmented[:n, n], augmented[:n, n + 1] = a, b, e
    phi = expm(augmented * dt)
    return phi[:n, :n], phi[:n, n], phi[:n, n + 1]


class Mpc:
    """The QP of the module's text, condensed over the move-blocked horizon: its Hessian is
    fixed, each sample only the linear term changes."""

    def __init__(self, simulator, target, dt):
        a, b, e, self.c, self.cm = linear_model(simulator, target)
        self.ad, self.bd, self.ed = discretise(a, b, e, dt)
        inputs = simulator.inputs()["controller.power_command"]
        self.low, self.high = inputs["low"], inputs["high"]
        self.scale = 0.05 if target == "force" else 5e-3  # the sweep's amplitude [N] or [m]
        self.rho = 2e-3  # per W^2 of move, against 1 per scale^2 of error and sample
        n, steps = len(self.bd), sum(HORIZON_BLOCKS)
        # y_j = C (Ad^j z0 + sum_i Ad^(j-1-i) (Bd u_i + ed)) for j = 1..steps, u_i blocked.
        blocks = np.repeat(np.arange(len(HORIZON_BLOCKS)), HORIZON_BLOCKS)
        self.free = np.zeros((steps, n))     # C Ad^j
        self.forced = np.zeros((steps, len(HORIZON_BLOCKS)))
        self.affine = np.zeros(steps)
        power = np.eye(n)
        response, offset = np.zeros((n, len(HORIZON_BLOCKS))), np.zeros(n)
        for j in range(steps):
            response = self.ad @ response
            response[:, blocks[j]] += self.bd
            offset = self.ad @ offset + self.ed
            power = self.ad @ power
            self.free[j], self.forced[j], self.affine[j] = self.c @ power, self.c @ response, \
                self.c @ offset
        moves = np.eye(len(HORIZON_BLOCKS)) - np.eye(len(HORIZON_BLOCKS), k=-1)
        hessian = self.forced.T @ self.forced / self.scale ** 2 + self.rho * moves.T @ moves
        self.hessian = matrix(2 * hessian)
        self.factor = cho_factor(2 * hessian)
        self.moves = moves
        count = len(HORIZON_BLOCKS)
        self.g = matrix(np.vstack([np.eye(count), -np.eye(count)]))
        self.h = matrix(np.concatenate([np.full(count, self.high), np.full(count, -self.low)]))
        # The model, run on the powers sent from t = 0 (the thermal force from 0, as the
        # estimator's); a deflection model starts at the first estimate.
        self.z = np.zeros(n)
        self.started = False
        self.last = self.low
        self.samples = self.qp_calls = 0

    def command(self, reference, estimate):
        """The power for the next sample; P_min while the estimator has no estimate yet."""
        if not np.isfinite(estimate):
            self.z = self.ad @ self.z + self.bd * self.low + self.ed
            return self.low
        if not self.started:
            self.z[1:] = estimate
            self.started = True
        disturbance = estimate - self.cm @ self.z
        predicted = self.free @ self.z + self.affine + disturbance
        error = predicted - reference
        linear = 2 * (self.forced.T @ error / self.scale ** 2)
        linear[0] -= 2 * self.rho * self.last
        # A convex QP whose unconstrained minimiser is within the box has it as its solution:
        # the QP solver is called when a limit is active.
        moves = -cho_solve(self.factor, linear)
        if moves.min() < self.low or moves.max() > self.high:
            moves = np.array(solvers.qp(self.hessian, matrix(linear), self.g, self.h)["x"])
            self.qp_calls += 1
        self.samples += 1
        power = float(np.clip(moves[0], self.low, self.high))
        self.z = self.ad @ self.z + self.bd * power + self.ed
        self.last = power
        return power


def closed_by_mpc(target, settings):
    simulator = tcpmsim.Simulator(tcpmsim.Scenario.from_yaml(
        f"{CONFIGS}/external_{target}.yaml", set=settings))
    dt = 1.0 / simulator.parameter("drive.pwm_frequency")
    mpc = Mpc(simulator, target, dt)
    outputs = simulator.outputs()
    while not simulator.finished:
        power = mpc.command(outputs["controller/reference"], outputs[f"estimator/{target}"])
        outputs = simulator.step({"controller.power_command": power}, dt)
    print(f"  MPC on {target}: {mpc.qp_calls} of {mpc.samples} samples with a limit active "
          "(a QP solved)")
    return simulator.result()


def closed_by_pid(target, settings):
    return tcpmsim.Scenario.from_yaml(f"{CONFIGS}/{target}_steps.yaml", set=settings).run()


def measured(result, target):
    task = tcpmsim.control_task(result)
    row = {"tracking_rmse": task["tracking_error"]["rmse"], "bandwidth": task["bandwidth"]}
    if "steps" in task:
        steps = task["steps"]
        reached = np.asarray(steps["reached"])
        row["rise"] = steps["rise_time"][reached]
        row["not_reached"] = int((~reached).sum())
        row["overshoot"] = np.median(steps["overshoot"])
    else:
        row["response"] = task["response"]
    return row


def run_task(target, sweep):
    settings = {}
    if sweep:
        settings = {"scenario.duration": "3800 s",
                    "controller.reference": SWEEP_REFERENCE[target]}
    started = time.perf_counter()
    mpc = closed_by_mpc(target, settings)
    mpc_seconds = time.perf_counter() - started
    if sweep:
        pid = tcpmsim.Scenario.from_yaml(f"{CONFIGS}/{target}_sweep.yaml").run()
    else:
        pid = closed_by_pid(target, settings)
    assert np.array_equal(mpc["controller/reference"], pid["controller/reference"]), "one task"
    return {"pid": (pid, measured(pid, target)), "mpc": (mpc, measured(mpc, target)),
            "mpc_seconds": mpc_seconds}


def table(rows):
    lines = ["| task | controller | rise 10-90 % [s] | steps not reached in 20 s | "
             "median overshoot [%] | tracking RMSE | bandwidth [Hz] |",
             "|---|---|---|---|---|---|---|"]
    for target in ("force", "deflection"):
        unit, scale = ("mN", 1e3) if target == "force" else ("mm", 1e3)
        for controller in ("pid", "mpc"):
            steps = rows.get((target, "steps"), {}).get(controller)
            sweep = rows.get((target, "sweep"), {}).get(controller)
            cells = ["-"] * 5
            if steps:
                rise = steps[1]["rise"]
                cells[0] = f"{rise.min():.1f}-{rise.max():.1f}" if len(rise) else "-"
                cells[1] = str(steps[1]["not_reached"])
                cells[2] = f"{100 * steps[1]['overshoot']:.1f}"
                cells[3] = f"{scale * steps[1]['tracking_rmse']:.1f} {unit}"
            if sweep and sweep[1]["bandwidth"]:
                cells[4] = f"{sweep[1]['bandwidth']:.4f}"
            name = "thesis' PID" if controller == "pid" else "MPC (QP, cvxopt)"
            lines.append(f"| {target} | {name} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def picture(rows, path):
    figure, axes = plt.subplots(2, 2, figsize=(11, 7))
    for column, target in enumerate(("force", "deflection")):
        unit, scale = ("mN", 1e3) if target == "force" else ("mm", 1e3)
        steps = rows.get((target, "steps"))
        top = axes[0, column]
        if steps:
            result = steps["pid"][0]
            top.plot(result["time"], scale * result["controller/reference"], color="grey",
                     linewidth=1, label="reference")
            for controller, colour in (("pid", "tab:blue"), ("mpc", "tab:red")):
                result = steps[controller][0]
                top.plot(result["time"], scale * result[f"muscle/{target}"], color=colour,
                         linewidth=1, label="PID" if controller == "pid" else "MPC")
            top.set_xlim(30, result["time"][-1])
        top.set(xlabel="time [s]", ylabel=f"{target} [{unit}] (true)",
                title=f"{target} steps, power limits [0.10, 3.12] W")
        top.legend(fontsize=8)
        bottom = axes[1, column]
        sweep = rows.get((target, "sweep"))
        if sweep:
            for controller, colour in (("pid", "tab:blue"), ("mpc", "tab:red")):
                response = sweep[controller][1]["response"]
                bottom.semilogx(response["frequency"], response["magnitude_db"], "o-",
                                color=colour, markersize=3,
                                label="PID" if controller == "pid" else "MPC")
            bottom.axhline(-3, color="grey", linewidth=0.8, linestyle="--")
            bottom.legend(fontsize=8)
        bottom.set(xlabel="frequency [Hz]", ylabel="|y / r| [dB]",
                   title=f"{target} sine sweep (the -3 dB line)")
    figure.tight_layout()
    os.makedirs(os.path.dirname(path), exist_ok=True)
    figure.savefig(path, dpi=110)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--steps", action="store_true", help="the step tasks only")
    parser.add_argument("-o", "--output", default="results/examples/mpc_vs_pid.png")
    arguments = parser.parse_args()
    rows = {}
    for target in ("force", "deflection"):
        for kind in ("steps",) if arguments.steps else ("steps", "sweep"):
            rows[(target, kind)] = run_task(target, kind == "sweep")
            print(f"{target} {kind}: the MPC's run took "
                  f"{rows[(target, kind)]['mpc_seconds']:.1f} s")
    print(table(rows))
    picture(rows, arguments.output)
    print(f"wrote {arguments.output}")
    # What the example shows, checked: both controllers track every task within the limits,
    # and with the same watts the MPC is as fast as the PID (rise, bandwidth) within 10 %.
    for (target, kind), row in rows.items():
        for controller in ("pid", "mpc"):
            power = row[controller][0]["controller/power_command"]
            assert power.min() >= 0.10 - 1e-12 and power.max() <= 3.12 + 1e-12, (target, kind)
        pid, mpc = row["pid"][1], row["mpc"][1]
        if kind == "steps":
            assert len(mpc["rise"]) == len(pid["rise"]) >= 4, target
            assert abs(mpc["tracking_rmse"] / pid["tracking_rmse"] - 1) < 0.1, target
        else:
            assert abs(mpc["bandwidth"] / pid["bandwidth"] - 1) < 0.1, target


if __name__ == "__main__":
    main()
