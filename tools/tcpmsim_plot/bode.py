"""The Bode plot of a control task's stepped sine sweep (tcpmsim control-tasks' file), with the
-3 dB line and the bandwidth where the magnitude crosses it (7.3.6)."""
import h5py
import numpy as np

from tcpmsim_plot.common import PlotError, open_file, plt, save


def plot_bode(path, task, output):
    handle = open_file(path)
    sweeps = [name for name, item in handle.items()
              if isinstance(item, h5py.Group) and "frequency" in item]
    if task is None:
        if len(sweeps) != 1:
            raise PlotError(f"{path} holds the sweep tasks {', '.join(sweeps) or '(none)'}: name one with --task")
        task = sweeps[0]
    if task not in sweeps:
        raise PlotError(f"{path} has no sweep task '{task}' (it has: {', '.join(sweeps) or 'none'})")
    group = handle[task]
    frequency = group["frequency"][:]
    magnitude = group["magnitude"][:]
    phase = np.degrees(group["phase"][:])
    bandwidth = group["bandwidth"][0] if "bandwidth" in group else float("nan")
    figure, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(7, 5.5))
    top.semilogx(frequency, magnitude, "o-", markersize=4)
    top.axhline(-3.0103, color="grey", linestyle="--", linewidth=0.8, label="-3 dB")
    if np.isfinite(bandwidth):
        top.axvline(bandwidth, color="red", linewidth=0.8, label=f"bandwidth {bandwidth * 1e3:.1f} mHz")
    top.set_ylabel("magnitude [dB]")
    top.legend(fontsize=8)
    top.grid(True, which="both", alpha=0.3)
    bottom.semilogx(frequency, phase, "o-", markersize=4)
    bottom.set_ylabel("phase [deg]")
    bottom.set_xlabel("frequency [Hz]")
    bottom.grid(True, which="both", alpha=0.3)
    top.set_title(task)
    save(figure, output)
