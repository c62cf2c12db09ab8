"""Your own controller in the loop: the chapter-7 force task (configs/ch7_control/
external_force.yaml: the plant, Muscle Drive and self-sensing estimator of force_steps.yaml,
with the controller left to Python), closed first by a PI written here, then through the
Gymnasium-style environment by a bang-bang law.

The PI is the thesis' (7.7)-(7.9) at the drive's 20 Hz: it reads the self-sensed force after
each step and sets the heating power, which the drive applies from that instant on. Written
exactly as the built-in PID, it gives the built-in run bit for bit, which the example checks;
any other law (an MPC, a policy) goes where `pi` is."""
import math

import numpy as np

import tcpmsim
from tcpmsim.env import MuscleEnv

SETTINGS = {"scenario.duration": "100 s"}
builtin = tcpmsim.Scenario.from_yaml("configs/ch7_control/force_steps.yaml", set=SETTINGS).run()

simulator = tcpmsim.Simulator(
    tcpmsim.Scenario.from_yaml("configs/ch7_control/external_force.yaml", set=SETTINGS))
low, high = 0.10, 3.12  # the controller's power_limits [W]
dt, kp, ti, integral = 0.05, 540.0, 1.0, 0.0


def pi(r, estimate):
    """(7.7)-(7.9): idle at P_min until the estimator has an estimate."""
    global integral
    if not math.isfinite(estimate):
        integral = 0.0
        return low
    error = r - estimate
    demand = kp * (error + integral / ti)
    power = min(high, max(low, demand))
    integral += dt * (error - (demand - power) / kp)
    return power


outputs = simulator.outputs()
while not simulator.finished:
    # The task's reference as the external controller reports it: force_steps.yaml's steps.
    power = pi(outputs["controller/reference"], outputs["estimator/force"])
    outputs = simulator.step({"controller.power_command": power}, dt)
result = simulator.result()
for channel in ("muscle/force", "controller/power_command", "controller/reference"):
    assert np.array_equal(result[channel], builtin[channel]), f"{channel}: not the built-in run"
error = result["muscle/force"] - builtin["controller/reference"]
print(f"PI in Python: {len(result['time'])} samples, the built-in PID's run bit for bit; "
      f"force tracking RMSE after 40 s {np.sqrt(np.mean(error[result['time'] >= 40] ** 2)) * 1e3:.2f} mN")

# The same task as an environment: observation [estimated force, reference, last power].
env = MuscleEnv("configs/ch7_control/external_force.yaml", target="force",
                reference=lambda t: 0.45)
observation, info = env.reset(seed=7)
total, steps, truncated = 0.0, 0, False
while not truncated:
    action = [high if observation[0] < observation[1] else low]  # bang-bang on the estimate
    observation, reward, terminated, truncated, info = env.step(action)
    total, steps = total + reward, steps + 1
print(f"environment: {steps} steps to t = {info['time']:.0f} s, mean reward {total / steps:.3f} "
      f"(minus |force error| / 0.1 N), last true force {info['true'] * 1e3:.1f} mN")
