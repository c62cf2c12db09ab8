"""The default scenario from Python: force against heating power over the identification
protocol of thesis section 7.3.5 (multisines, then random steps, on power and deflection)."""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import tcpmsim  # noqa: E402

result = tcpmsim.Scenario.from_yaml("configs/ch7_identification.yaml").run()
time, power, force = result["time"], result["drive/power"], result["muscle/force"]
print(f"{result.scenario}: {len(time)} samples, peak force {force.max():.4f} "
      f"{result.units['muscle/force']}, {result.statistics['steps']} solver steps")

figure, (traces, loop) = plt.subplots(1, 2, figsize=(11, 4))
traces.plot(time, force * 1e3, linewidth=0.8, label="force [mN]")
traces.plot(time, power * 100, linewidth=0.8, label="power [10 mW]")
traces.set_xlabel("time [s]")
traces.legend(fontsize=8)
loop.scatter(power, force * 1e3, s=2, c=time, cmap="viridis")
loop.set_xlabel(f"power [{result.units['drive/power']}]")
loop.set_ylabel("force [mN]")
loop.set_title("force against power (colour: time)")
os.makedirs("results/examples", exist_ok=True)
figure.tight_layout()
figure.savefig("results/examples/default_scenario.png", dpi=110)
print("wrote results/examples/default_scenario.png")
assert force.max() > force.min() > 0.0  # the muscle pulls throughout
