"""Bode plots with the -3 dB line and the bandwidth where the magnitude crosses it (7.3.6): a
control task's stepped sine sweep (tcpmsim control-tasks' file), or an estimated frequency
response (tcpmsim analyze's file, frequency_response/<input>), with its 95 % confidence band."""
import h5py
import numpy as np

from tcpmsim_plot.common import PlotError, open_file, plt, save


def responses(handle):
    """Every group holding a frequency response, by path."""
    found = []
    handle.visititems(lambda name, item: found.append(name)
                      if isinstance(item, h5py.Group) and "frequency" in item else None)
    return found


def bode_figure(path, task=None):
    """The Bode figure of a sweep task (or an estimated frequency response) in `path`."""
    with open_file(path) as handle:
        return _bode_figure(handle, path, task)


def plot_bode(path, task, output):
    save(bode_figure(path, task), output)


def _bode_figure(handle, path, task):
    sweeps = responses(handle)
    if task is None:
        if len(sweeps) != 1:
            raise PlotError(f"{path} holds the sweep tasks {', '.join(sweeps) or '(none)'}: name one with --task")
        task = sweeps[0]
    if task not in sweeps:
        matches = [name for name in sweeps if name.split("/")[-1] == task]
        if len(matches) != 1:
            raise PlotError(f"{path} has no sweep task '{task}' (it has: {', '.join(sweeps) or 'none'})")
        task = matches[0]
    group = handle[task]
    frequency = group["frequency"][:]
    magnitude = group["magnitude"][:]
    phase = np.degrees(group["phase"][:])
    bandwidth = np.ravel(group["bandwidth"][()])[0] if "bandwidth" in group else float("nan")
    # An estimate's -3 dB is taken against its reference magnitude (1, or the lowest frequency's).
    reference_db = 20 * np.log10(group["reference_magnitude"][()]) if "reference_magnitude" in group else 0.0
    figure, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(7, 5.5))
    estimate = "radius_95" in group
    style = "o-" if len(frequency) <= 60 else "-"
    top.semilogx(frequency, magnitude, style, markersize=4)
    if estimate:
        ratio = group["magnitude_ratio"][:]
        radius = group["radius_95"][:]
        low = 20 * np.log10(np.maximum(ratio - radius, ratio * 1e-3))
        top.fill_between(frequency, low, 20 * np.log10(ratio + radius), alpha=0.25, label="95 % band")
        spread = np.degrees(np.arcsin(np.minimum(radius / ratio, 1.0)))
        bottom.fill_between(frequency, phase - spread, phase + spread, alpha=0.25)
    top.axhline(reference_db - 3.0103, color="grey", linestyle="--", linewidth=0.8, label="-3 dB")
    if np.isfinite(bandwidth):
        top.axvline(bandwidth, color="red", linewidth=0.8, label=f"bandwidth {bandwidth * 1e3:.1f} mHz")
    unit = group["magnitude_ratio"].attrs.get("units", "") if estimate else ""
    top.set_ylabel(f"magnitude [dB re 1 {unit}]" if unit else "magnitude [dB]")
    top.legend(fontsize=8)
    top.grid(True, which="both", alpha=0.3)
    bottom.semilogx(frequency, phase, style, markersize=4)
    bottom.set_ylabel("phase [deg]")
    bottom.set_xlabel("frequency [Hz]")
    bottom.grid(True, which="both", alpha=0.3)
    title = task
    if estimate:
        title = f"{group.attrs.get('input', task)} -> {handle.attrs.get('output', '')}"
    top.set_title(title)
    return figure
