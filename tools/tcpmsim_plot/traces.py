"""Time traces of any tcpmsim record, in display units (degC, mm).

With --channels: one panel per channel. Without: the channels the record holds, one panel per
quantity, each instance a line named in the legend: every muscle's (a group with a temperature
and a force) force and temperature, every drive's power, and the load's angle (a joint, with the
controller's reference when it is an angle) or deflection. A single muscle's record gives
drive/power, muscle/temperature, muscle/deflection and muscle/force."""
import sys

import h5py

from tcpmsim_plot.common import PlotError, display, open_file, plt, save, text_attribute, units

DEFAULT_CHANNELS = ["drive/power", "muscle/temperature", "muscle/deflection", "muscle/force"]
# What a record without a recognised muscle, drive or load shows at most.
FALLBACK_CHANNELS = 6


def _datasets(group):
    return [name for name, item in group.items() if isinstance(item, h5py.Dataset)]


def default_panels(record):
    """Panels (lists of channels sharing a quantity) chosen from what the record holds."""
    if all(channel in record for channel in DEFAULT_CHANNELS):
        return [[channel] for channel in DEFAULT_CHANNELS]
    groups = [name for name, item in record.items()
              if isinstance(item, h5py.Group) and name not in ("inputs", "controller")]
    muscles = [g for g in groups if {"temperature", "force"} <= set(_datasets(record[g]))]
    others = [g for g in groups if g not in muscles and g != "load"]
    drives = [g for g in others if "power" in _datasets(record[g])]
    if not drives:  # a bundle's supply and wires
        drives = [f"{g}/{sub}" for g in groups for sub, item in record[g].items()
                  if isinstance(item, h5py.Group) and "power" in _datasets(item)]
    panels = []
    if drives:
        panels.append([f"{d}/power" for d in drives])
    if muscles:
        panels.append([f"{m}/temperature" for m in muscles])
        panels.append([f"{m}/force" for m in muscles])
    if "load" in record and isinstance(record["load"], h5py.Group):
        load = _datasets(record["load"])
        if "angle" in load:
            panel = ["load/angle"]
            if ("controller/reference" in record
                    and units(record["controller/reference"]) == units(record["load/angle"])):
                panel.append("controller/reference")
            panels.append(panel)
        elif "deflection" in load:
            panels.append(["load/deflection"])
    if not panels:  # nothing recognised (a spring): the first datasets of each group
        chosen = [f"{g}/{name}" for g in groups for name in _datasets(record[g])]
        panels = [[channel] for channel in chosen[:FALLBACK_CHANNELS]]
    if not panels:
        raise PlotError(f"{text_attribute(record, 'scenario') or 'the record'} holds no channel "
                        "to draw")
    return panels


def traces_figure(path, channels=None):
    """The figure of a record's traces: `channels` one panel each, or the default panels."""
    with open_file(path, required="time") as record:
        if channels:
            samples = record["time"].shape[:1]

            def is_trace(channel):  # a series over the record's time (not an input's samples)
                found = record.get(channel)
                return isinstance(found, h5py.Dataset) and found.shape[:1] == samples

            available = [c for c in channels if is_trace(c)]
            missing = [c for c in channels if c not in available]
            if missing:
                print(f"tcpmsim-plot: not in {path} as a trace over its time, skipped: "
                      f"{', '.join(missing)}", file=sys.stderr)
            if not available:
                raise PlotError(f"none of the channels {', '.join(channels)} is in {path} "
                                "as a trace over its time")
            panels = [[channel] for channel in available]
        else:
            panels = default_panels(record)
        time = record["time"][:]
        count = len(panels)
        figure, axes = plt.subplots(count, 1, sharex=True, squeeze=False, layout="constrained",
                                    figsize=(10, 1.0 + 1.9 * count))
        for axis, panel in zip(axes[:, 0], panels):
            shown_units = []
            for channel in panel:
                values, shown = display(record[channel][()], units(record[channel]))
                shown_units.append(shown)
                lines = axis.plot(time, values, linewidth=0.9)
                lines[0].set_label(channel)
                if len(panel) > 1:  # members of a set (a bundle): one colour, one legend entry
                    for line in lines[1:]:
                        line.set_color(lines[0].get_color())
            name = panel[0] if len(panel) == 1 else panel[0].rsplit("/", 1)[-1]
            unit = shown_units[0] if len(set(shown_units)) == 1 else ", ".join(shown_units)
            axis.set_ylabel(f"{name}\n[{unit}]" if unit else name, fontsize=8)
            if len(panel) > 1:
                axis.legend(fontsize=7, loc="best")
            axis.grid(True, alpha=0.3)
        axes[-1, 0].set_xlabel("time [s]")
        figure.suptitle(f"{text_attribute(record, 'scenario')} "
                        f"(tcpmsim {text_attribute(record, 'tcpmsim_version')})")
    return figure


def plot_traces(path, channels, output):
    save(traces_figure(path, channels), output)
