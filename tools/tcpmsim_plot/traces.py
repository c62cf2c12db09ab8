"""Time traces of any tcpmsim record: one panel per channel, in display units (degC, mm)."""
import sys

from tcpmsim_plot.common import PlotError, display, open_file, plt, save, units

DEFAULT_CHANNELS = ["drive/power", "muscle/temperature", "muscle/deflection", "muscle/force"]


def plot_traces(path, channels, output):
    record = open_file(path, required="time")
    available = [c for c in channels if c in record]
    missing = sorted(set(channels) - set(available))
    if missing:
        print(f"tcpmsim-plot: not in {path}, skipped: {', '.join(missing)}", file=sys.stderr)
    if not available:
        raise PlotError(f"none of the channels {', '.join(channels)} is in {path}")
    time = record["time"][:]
    figure, axes = plt.subplots(len(available), 1, sharex=True, figsize=(10, 2.2 * len(available)),
                                squeeze=False)
    for axis, channel in zip(axes[:, 0], available):
        values, shown = display(record[channel][:], units(record[channel]))
        axis.plot(time, values, linewidth=0.9)
        axis.set_ylabel(f"{channel}\n[{shown}]", fontsize=8)
        axis.grid(True, alpha=0.3)
    axes[-1, 0].set_xlabel("time [s]")
    figure.suptitle(f"{record.attrs.get('scenario', '')} (tcpmsim {record.attrs.get('tcpmsim_version', '')})")
    save(figure, output)
