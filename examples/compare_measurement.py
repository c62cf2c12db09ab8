"""A model run against a measurement CSV. The chapter-7 bench (configs/discover/ch7_bench.yaml)
reads a run with a load cell of 0.5 mN resolution and 1 mN noise, as `tcpmsim measure` writes
it; the section 7.2 model then replays the measured power and deflection (measurement.file) and
its force is compared with the measured one. With the model that made the data, the residual is
the load cell's noise: an RMS of about 1 mN."""
import os
import shutil
import subprocess

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import tcpmsim  # noqa: E402

PROGRAM = shutil.which("tcpmsim") or os.path.expanduser("~/.local/bin/tcpmsim")
os.makedirs("results/examples", exist_ok=True)
inputs, measured_csv = "results/examples/ch7_inputs.h5", "results/examples/ch7_measured.csv"

# The measurement: the protocol's inputs, then the bench's reading of the model driven by them.
tcpmsim.Scenario.from_yaml("configs/discover/ch7_protocol.yaml").run().save(inputs)
subprocess.run([PROGRAM, "measure", "configs/discover/ch7_base.yaml", "--set",
                f"measurement.file={inputs}", "--bench", "configs/discover/ch7_bench.yaml",
                "-o", measured_csv, "-q"], check=True)
with open(measured_csv) as file:
    header = file.readline().strip().split(",")
measured = np.loadtxt(measured_csv, delimiter=",", skiprows=1)
column = {name.split("[")[0]: k for k, name in enumerate(header)}
assert header[column["force"]] == "force[mN]"
time, force = measured[:, column["time"]], measured[:, column["force"]] * 1e-3  # mN -> N

# The model replays the measured inputs.
model = tcpmsim.Scenario.from_yaml("configs/discover/ch7_base.yaml",
                                  set={"measurement.file": measured_csv})
result = model.run()
simulated = np.interp(time, result["time"], result["load/force"])
residual = force - simulated
rms = np.sqrt(np.mean(residual ** 2))
print(f"{len(time)} samples: force RMS residual {rms * 1e3:.3f} mN (the load cell's noise: 1 mN)")

figure, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(10, 5))
top.plot(time, force * 1e3, linewidth=0.6, label="measured")
top.plot(time, simulated * 1e3, linewidth=0.6, label="model")
top.set_ylabel("force [mN]")
top.legend(fontsize=8)
bottom.plot(time, residual * 1e3, linewidth=0.5, color="grey")
bottom.set_ylabel("residual [mN]")
bottom.set_xlabel("time [s]")
bottom.set_title(f"RMS {rms * 1e3:.2f} mN")
figure.tight_layout()
figure.savefig("results/examples/compare_measurement.png", dpi=110)
print("wrote results/examples/compare_measurement.png")
assert 0.8e-3 < rms < 1.3e-3  # the noise the bench adds, and nothing else
