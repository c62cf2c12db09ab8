"""A bundle's per-muscle spread from a tcpmsim record.

Left: the bundle's cross-section (/<bundle>/centre_x, centre_y), each muscle coloured by its
temperature at `time` (default: the end). Right: every member's temperature over time, coloured
by how many neighbours shield it."""
import numpy as np
from matplotlib.patches import Circle

from tcpmsim_plot.common import PlotError, open_file, plt, save, text_attribute, texts


def bundle_figure(path, bundle, at_time=None):
    """The figure of a bundle's cross-section at `at_time` (default: the end) and its members'
    temperatures [degC]."""
    with open_file(path, required="time") as record:
        try:
            group = record[bundle]
            temperature = group["temperature"][:] - 273.15
            x, y = group["centre_x"][:] * 1e3, group["centre_y"][:] * 1e3
            neighbours = group["neighbours"][:]
            members = texts(group["temperature"].attrs["members"])
        except KeyError as error:
            raise PlotError(f"{path} has no record of a bundle '{bundle}': {error}") from error
        time = record["time"][:]
        scenario = text_attribute(record, "scenario")
    index = len(time) - 1 if at_time is None else int(np.argmin(np.abs(time - at_time)))

    figure, (section, traces) = plt.subplots(1, 2, figsize=(11, 4.6), gridspec_kw={"width_ratios": [1, 1.5]})
    # Member 0 is the centre; its nearest neighbour is one pitch away.
    pitch = np.hypot(x[1:] - x[0], y[1:] - y[0]).min() if len(x) > 1 else 1.0
    colours = plt.get_cmap("inferno")
    low, high = temperature[index].min(), temperature[index].max()
    span = max(high - low, 1e-9)
    for k in range(len(x)):
        shade = colours(0.15 + 0.75 * (temperature[index, k] - low) / span)
        section.add_patch(Circle((x[k], y[k]), 0.48 * pitch, color=shade))
        if len(x) <= 61:
            section.text(x[k], y[k], f"{temperature[index, k]:.1f}", ha="center", va="center", fontsize=6,
                         color="white" if temperature[index, k] < low + 0.6 * span else "black")
    section.set_xlim(x.min() - pitch, x.max() + pitch)
    section.set_ylim(y.min() - pitch, y.max() + pitch)
    section.set_aspect("equal")
    section.set_xlabel("x [mm]")
    section.set_ylabel("y [mm]")
    section.set_title(f"temperature [degC] at t = {time[index]:.0f} s")

    shades = plt.get_cmap("viridis")
    most = max(neighbours.max(), 1)
    for k in range(len(members)):
        traces.plot(time, temperature[:, k], color=shades(neighbours[k] / most), linewidth=0.8)
    for count in sorted(set(neighbours.astype(int))):
        traces.plot([], [], color=shades(count / most), label=f"{count} neighbours")
    traces.axvline(time[index], color="grey", linewidth=0.6, linestyle="--")
    traces.set_xlabel("time [s]")
    traces.set_ylabel("temperature [degC]")
    traces.grid(True, alpha=0.3)
    traces.legend(fontsize=8)
    traces.set_title(f"{len(members)} members")
    figure.suptitle(f"{scenario}: {bundle}")
    return figure


def plot_bundle(path, bundle, at_time, output):
    save(bundle_figure(path, bundle, at_time), output)

