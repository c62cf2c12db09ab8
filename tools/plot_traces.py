#!/usr/bin/python3
"""Plot the traces of any tcpmsim HDF5 record.

By default: heating power, muscle temperature, deflection and force over time, each in the
panel's display unit (degC, mm). Pass --channels to plot other datasets, e.g.
    tools/plot_traces.py results/run.h5 --channels muscle/inductance_measure load/force

Uses Debian's python3-h5py and python3-matplotlib (no network installs).
"""
import argparse
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

DEFAULT_CHANNELS = ["drive/power", "muscle/temperature", "muscle/deflection", "muscle/force"]

# Display conversions: SI unit in the file -> (offset, scale, display unit).
DISPLAY = {"K": (-273.15, 1.0, "degC"), "m": (0.0, 1e3, "mm")}


def load(path):
    try:
        record = h5py.File(path, "r")
    except OSError as error:
        sys.exit(f"plot_traces: cannot read {path}: {error}")
    if "time" not in record:
        sys.exit(f"plot_traces: {path} is not a tcpmsim record (no /time dataset)")
    return record


def display(values, unit):
    offset, scale, shown = DISPLAY.get(unit, (0.0, 1.0, unit))
    return (values + offset) * scale, shown


def plot(record, channels, output, title):
    available = [c for c in channels if c in record]
    missing = sorted(set(channels) - set(available))
    if missing:
        print(f"plot_traces: not in this record, skipped: {', '.join(missing)}", file=sys.stderr)
    if not available:
        sys.exit("plot_traces: none of the requested channels is in the record")
    time = record["time"][:]
    figure, axes = plt.subplots(len(available), 1, sharex=True, figsize=(10, 2.2 * len(available)),
                                squeeze=False)
    for axis, channel in zip(axes[:, 0], available):
        dataset = record[channel]
        unit = dataset.attrs.get("units", "")
        values, shown = display(dataset[:], unit)
        axis.plot(time, values, linewidth=0.9)
        axis.set_ylabel(f"{channel}\n[{shown}]", fontsize=8)
        axis.grid(True, alpha=0.3)
    axes[-1, 0].set_xlabel("time [s]")
    figure.suptitle(title)
    figure.tight_layout()
    figure.savefig(output, dpi=110)
    print(f"wrote {output}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("record", help="a tcpmsim HDF5 file")
    parser.add_argument("-o", "--output", help="PNG to write (default: the record's name with .png)")
    parser.add_argument("--channels", nargs="+", default=DEFAULT_CHANNELS,
                        help="datasets to plot, as group/name (default: %(default)s)")
    arguments = parser.parse_args()
    record = load(arguments.record)
    output = arguments.output or arguments.record.rsplit(".", 1)[0] + ".png"
    title = f"{record.attrs.get('scenario', '')} (tcpmsim {record.attrs.get('tcpmsim_version', '')})"
    plot(record, arguments.channels, output, title)


if __name__ == "__main__":
    main()
