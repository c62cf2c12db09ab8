"""A parameter sweep from Python: the SLS branch stiffness k2 of (7.5)-(7.6) at four values, run
on two threads, each the chapter-7 muscle under imposed force (configs/ch7_force_creep.yaml).
The step response of the deflection to the force steps at 20 s and 40 s: a jump of
dF / (k1 + k2), then creep to dF / k1 with the time constant c (k1 + k2) / (k1 k2); the larger
k2, the smaller the jump and the faster the creep, the same end."""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import tcpmsim  # noqa: E402

scenario = tcpmsim.Scenario.from_yaml("configs/ch7_force_creep.yaml")
values = ["1.35 mN/mm", "2.7 mN/mm", "5.4 mN/mm", "10.8 mN/mm"]
results = tcpmsim.sweep(scenario, "muscle.mechanics.k2", values, jobs=2)

figure, axis = plt.subplots(figsize=(7, 4))
for value, result in zip(values, results):
    shown = (result["time"] >= 15) & (result["time"] <= 55)
    axis.plot(result["time"][shown], result["muscle/deflection"][shown] * 1e3,
              label=f"k2 = {value}")
axis.set_xlabel("time [s]")
axis.set_ylabel("deflection [mm]")
axis.set_title("step response to the force steps, for four k2 (Table 7.2: 2.7 mN/mm)")
axis.legend(fontsize=8)
os.makedirs("results/examples", exist_ok=True)
figure.tight_layout()
figure.savefig("results/examples/sweep_k2.png", dpi=110)
print("wrote results/examples/sweep_k2.png")

# The same runs one at a time give the same samples, bit for bit.
alone = scenario.copy().set("muscle.mechanics.k2", values[1]).run()
assert np.array_equal(alone["muscle/deflection"], results[1]["muscle/deflection"])
# Just after the step at 40 s the stiffer branch has moved less; all end at the same creep.
time = results[0]["time"]
just_after, settled = np.searchsorted(time, 40.25), np.searchsorted(time, 55.0)
jumps = [result["muscle/deflection"][just_after] for result in results]
for value, jump, result in zip(values, jumps, results):
    print(f"k2 = {value}: {jump * 1e3:.3f} mm at 40.25 s, "
          f"{result['muscle/deflection'][settled] * 1e3:.3f} mm at 55 s")
assert jumps == sorted(jumps)  # the force falls at 40 s: a stiffer k2 drops less at once
