#!/usr/bin/python3
"""Plot a bundle's temperature spread from a tcpmsim record.

Left: the bundle's cross-section (/<bundle>/centre_x, centre_y), each muscle coloured by its
temperature at --time (default: the end). Right: every member's temperature over time, coloured
by how many neighbours shield it. For example
    tools/plot_bundle.py results/bundle.h5 --bundle bundle --time 149 -o docs/images/bundle.png

Uses Debian's python3-h5py and python3-matplotlib (no network installs).
"""
import argparse
import sys

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Circle  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("record", help="a tcpmsim HDF5 record of a scenario with a bundle")
    parser.add_argument("--bundle", default="bundle", help="the bundle's name (default: %(default)s)")
    parser.add_argument("--time", type=float, help="time of the cross-section [s] (default: the end)")
    parser.add_argument("-o", "--output", help="PNG to write (default: the record's name with .png)")
    arguments = parser.parse_args()
    try:
        record = h5py.File(arguments.record, "r")
        group = record[arguments.bundle]
        temperature = group["temperature"][:] - 273.15
        x, y = group["centre_x"][:] * 1e3, group["centre_y"][:] * 1e3
        neighbours = group["neighbours"][:]
        members = [m.decode() if isinstance(m, bytes) else m for m in group["temperature"].attrs["members"]]
    except (OSError, KeyError) as error:
        sys.exit(f"plot_bundle: {arguments.record} has no bundle '{arguments.bundle}' record: {error}")
    time = record["time"][:]
    index = len(time) - 1 if arguments.time is None else int(np.argmin(np.abs(time - arguments.time)))

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
    figure.suptitle(f"{record.attrs.get('scenario', '')}: {arguments.bundle}")
    figure.tight_layout()
    output = arguments.output or arguments.record.rsplit(".", 1)[0] + ".png"
    figure.savefig(output, dpi=110)
    print(f"wrote {output}")


if __name__ == "__main__":
    main()
