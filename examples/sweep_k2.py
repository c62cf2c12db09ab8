"""A parameter sweep from Python: the SLS branch stiffness k2 of (7.5)-(7.6) at four values, run
on two threads, each the chapter-7 muscle under a constant force with a step of heating power.
After the step the deflection jumps by the elastic part and creeps with the time constant
c (k1 + k2) / (k1 k2) of the SLS: the larger k2, the larger the instantaneous part."""
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
    axis.plot(result["time"], result["muscle/deflection"] * 1e3, label=f"k2 = {value}")
axis.set_xlabel("time [s]")
axis.set_ylabel("deflection [mm]")
axis.set_title("creep after the power steps, for four k2 (Table 7.2: 2.7 mN/mm)")
axis.legend(fontsize=8)
os.makedirs("results/examples", exist_ok=True)
figure.tight_layout()
figure.savefig("results/examples/sweep_k2.png", dpi=110)
print("wrote results/examples/sweep_k2.png")

# The same runs one at a time give the same samples, bit for bit.
alone = scenario.copy().set("muscle.mechanics.k2", values[1]).run()
assert np.array_equal(alone["muscle/deflection"], results[1]["muscle/deflection"])
for value, result in zip(values, results):
    print(f"k2 = {value}: deflection {result['muscle/deflection'].min() * 1e3:.3f} to "
          f"{result['muscle/deflection'].max() * 1e3:.3f} mm")
