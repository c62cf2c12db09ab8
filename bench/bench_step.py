#!/usr/bin/python3
"""Step-by-step overhead (issue 29): a single muscle under a controller written in Python at
100 Hz, 400 s (40 000 steps), through tcpmsim.Simulator. Target: under 4 s.
Reference in the same run: the same loop closed by the built-in PID (configs/ch7_control/
force_steps.yaml with its PWM, and so its PID's sampling, at 100 Hz) run in one call, so the
stepping's cost is also quoted as a ratio. Timings are the median of three repeats; nothing is
asserted.
Usage: bench_step.py BUILD_DIR"""
import math
import os
import statistics
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SETTINGS = {"scenario.duration": "400 s", "drive.pwm_frequency": "100 Hz", "output.rate": "100 Hz"}


def median_time(function, repeats=3):
    times = []
    for _ in range(repeats):
        started = time.perf_counter()
        result = function()
        times.append(time.perf_counter() - started)
    return statistics.median(times), result


def main():
    build = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build")
    sys.path.insert(0, os.path.join(build, "python"))
    import tcpmsim

    builtin = tcpmsim.Scenario.from_yaml(os.path.join(ROOT, "configs/ch7_control/force_steps.yaml"),
                                         set=SETTINGS)
    external = tcpmsim.Scenario.from_yaml(
        os.path.join(ROOT, "configs/ch7_control/external_force.yaml"), set=SETTINGS)

    def closed_in_python():
        simulator = tcpmsim.Simulator(external)
        dt, kp, ti, low, high = 0.01, 540.0, 1.0, 0.10, 3.12
        integral, power, steps = 0.0, low, 0
        outputs = simulator.outputs()
        while not simulator.finished:
            t = simulator.time
            reference = 0.45 if t < 40.0 else 0.40 + 0.025 * (int((t - 40.0) // 20.0) % 5)
            estimate = outputs["estimator/force"]
            if math.isfinite(estimate):
                error = reference - estimate
                demand = kp * (error + integral / ti)
                power = min(high, max(low, demand))
                integral += dt * (error - (demand - power) / kp)
            outputs = simulator.step({"controller.power_command": power}, dt)
            steps += 1
        return steps

    builtin_seconds, _ = median_time(lambda: builtin.run())
    python_seconds, steps = median_time(closed_in_python)
    print(f"built-in PID at 100 Hz, 400 s in one call: {builtin_seconds:.3f} s")
    print(f"Python PI at 100 Hz through tcpmsim.Simulator, {steps} steps: {python_seconds:.3f} s "
          f"({python_seconds / steps * 1e6:.1f} us per step; {python_seconds / builtin_seconds:.2f}"
          f" x the built-in run; target 4 s)")


if __name__ == "__main__":
    main()
