"""tcpmsim.analyze from Python: the frequency response P -> F of the chapter-7 muscle, measured
as the thesis measures it (a multisine on the heating power, the deflection held) and estimated
at the multisine's lines from the load cell's force, with its 95 % confidence band, against the
analytic kappa_P / (s + kappa_c) of (7.1) with (7.5). The README's picture."""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import tcpmsim  # noqa: E402

KAPPA_P, KAPPA_C = 7.2e-3, 131.6e-3  # Table 7.2: N/J, 1/s

result = tcpmsim.Scenario.from_yaml("configs/analysis/power_multisine.yaml").run()
estimate = tcpmsim.analyze(result, "load/force", start=100)  # after the thermal transient
power = estimate["responses"]["drive/power"]
print(estimate["report"])

f, H, radius = power["frequency"], power["response"], power["radius_95"]
fine = np.logspace(np.log10(f[0]) - 0.3, np.log10(f[-1]) + 0.2, 200)
analytic = KAPPA_P / (2j * np.pi * fine + KAPPA_C)
figure, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(7, 5.5))
top.semilogx(fine, 20 * np.log10(np.abs(analytic)), color="grey", label="kappa_P / (s + kappa_c)")
top.errorbar(f, 20 * np.log10(np.abs(H)), yerr=20 * np.log10(1 + radius / np.abs(H)), fmt="o",
             markersize=4, label="estimate, 95 % band")
if power["bandwidth"]:
    top.axvline(power["bandwidth"], color="red", linewidth=0.8,
                label=f"-3 dB {power['bandwidth'] * 1e3:.1f} mHz")
top.set_ylabel(f"|F/P| [dB re 1 {power['unit']}]")
top.legend(fontsize=8)
top.grid(True, which="both", alpha=0.3)
bottom.semilogx(fine, np.degrees(np.angle(analytic)), color="grey")
bottom.plot(f, np.degrees(power["phase"]), "o", markersize=4)
bottom.set_ylabel("phase [deg]")
bottom.set_xlabel("frequency [Hz]")
bottom.grid(True, which="both", alpha=0.3)
top.set_title("P -> F at constant deflection, from a multisine on power")
os.makedirs("results/examples", exist_ok=True)
figure.tight_layout()
figure.savefig("results/examples/bode_power_to_force.png", dpi=110)
print("wrote results/examples/bode_power_to_force.png")

truth = KAPPA_P / (2j * np.pi * f + KAPPA_C)
assert np.all(np.abs(H - truth) <= radius), "the analytic response lies outside the band"
