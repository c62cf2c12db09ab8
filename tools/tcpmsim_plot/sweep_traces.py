"""A sweep's stored traces (a sweep file with `store: {traces: decimated}` or `full` keeps
/runs/<id>/<scenario>/<group>/<name>): one channel of every stored run (or of the runs asked
for) over time, each run a line labelled by its values of the sweep's axes. Up to MAX_LEGEND
runs are named in a legend; more are coloured by the first axis' value, with a colour bar."""
import h5py
import numpy as np

from tcpmsim_plot.common import (PlotError, display, display_difference, is_absolute_temperature,
                                 open_file, plt, save, sweep_axes, sweep_metric_types,
                                 text_attribute, texts, units, with_unit)

MAX_LEGEND = 20


def run_parameters(handle, path):
    """The sweep's axes (parameter paths, in the summary) with their values per run id, in the
    display units: {path: (values by id, unit, texts or None)}."""
    summary = handle["summary"]
    names = [name for name in sweep_axes(handle) if name in summary]
    if not names:  # an older file: every column that is neither a metric nor the bookkeeping
        metrics = sweep_metric_types(handle)
        names = [name for name in summary
                 if name not in metrics and name not in ("id", "status", "message")]
    ids = summary["id"][:].astype(int)
    found = {}
    for name in names:
        values = summary[name][:]
        if values.dtype.kind in "SOU":
            found[name] = (dict(zip(ids, texts(values))), "", True)
            continue
        unit = units(summary[name])
        values = values.astype(float)
        values, unit = (display if is_absolute_temperature(name, unit, {})
                        else display_difference)(values, unit)
        found[name] = (dict(zip(ids, values)), unit, False)
    return found


def short_names(paths):
    """Each path's last component, or the whole path where two would share one."""
    last = [p.rsplit(".", 1)[-1] for p in paths]
    return {p: (s if last.count(s) == 1 else p) for p, s in zip(paths, last)}


def sweep_traces_figure(path, channel, scenario=None, runs=None):
    """The figure of one channel of a sweep's stored runs, each labelled by its parameters."""
    with open_file(path, required="summary") as handle:
        if "runs" not in handle or not len(handle["runs"]):
            raise PlotError(f"{path} holds no traces: the sweep stored none (give it "
                            "store: {traces: decimated} or --set store.traces=decimated)")
        stored = {int(name): name for name in handle["runs"]}
        scenarios = sorted({s for name in stored.values() for s in handle["runs"][name]})
        holding = [s for s in scenarios
                   if any(f"{s}/{channel}" in handle["runs"][name] for name in stored.values())]
        if scenario is None:
            if len(holding) != 1:
                raise PlotError(f"{path}: " + (f"the scenarios {', '.join(holding)} each record "
                                               f"'{channel}': choose one with --scenario"
                                               if holding else
                                               f"no stored run records '{channel}' (scenarios: "
                                               f"{', '.join(scenarios)})"))
            scenario = holding[0]
        elif scenario not in scenarios:
            raise PlotError(f"{path} stores no scenario '{scenario}' "
                            f"(it has: {', '.join(scenarios)})")
        elif scenario not in holding:
            raise PlotError(f"{path}: the stored runs of '{scenario}' do not record '{channel}'")
        ids = sorted(stored) if runs is None else list(runs)
        unknown = [str(i) for i in ids if i not in stored]
        if unknown:
            raise PlotError(f"{path} stores no run {', '.join(unknown)} "
                            f"(it stores {len(stored)} runs, ids {min(stored)}-{max(stored)})")
        parameters = run_parameters(handle, path)
        shorts = short_names(list(parameters))
        drawn = []
        for run in ids:
            group = handle["runs"][stored[run]]
            if f"{scenario}/{channel}" not in group or f"{scenario}/time" not in group:
                continue  # a run that failed before any trace
            item = group[f"{scenario}/{channel}"]
            if not isinstance(item, h5py.Dataset):
                raise PlotError(f"{path}: '{channel}' is a group, not a channel")
            values, unit = display(item[()], units(item))
            drawn.append((run, group[f"{scenario}/time"][()], values, unit))
        name = text_attribute(handle, "sweep")
    if not drawn:
        raise PlotError(f"{path}: no stored run of '{scenario}' has '{channel}'")

    def label(run):
        parts = []
        for parameter, (values, unit, textual) in parameters.items():
            value = values.get(run)
            shown = value if textual else f"{value:.3g}" + (f" {unit}" if unit else "")
            parts.append(f"{shorts[parameter]} = {shown}")
        return f"run {run}: " + ", ".join(parts) if parts else f"run {run}"

    figure, axis = plt.subplots(figsize=(11, 5), layout="constrained")
    many = len(drawn) > MAX_LEGEND
    first = next(iter(parameters.items()), None)
    colour_by = None
    if many and first is not None and not first[1][2]:
        colour_by = first
        level = np.array([first[1][0][run] for run, *_ in drawn])
        low, high = level.min(), level.max()
        log = low > 0 and high / low > 10
        colors = plt.matplotlib.colors
        norm = (colors.LogNorm if log else colors.Normalize)(low, high)
    shades = plt.get_cmap("viridis" if many else ("tab10" if len(drawn) <= 10 else "tab20"))
    for k, (run, time, values, unit) in enumerate(drawn):
        if colour_by is not None:
            colour = shades(norm(colour_by[1][0][run]))
        elif many:
            colour = shades(k / max(len(drawn) - 1, 1))
        else:
            colour = shades(k)
        lines = axis.plot(time, values, linewidth=0.9, color=colour)
        if not many:
            lines[0].set_label(label(run))
    if many and colour_by is not None:
        mappable = plt.cm.ScalarMappable(norm=norm, cmap=shades)
        figure.colorbar(mappable, ax=axis, label=with_unit(colour_by[0], colour_by[1][1]))
    elif not many:
        axis.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0,
                    title="run: parameters", title_fontsize=7)
    axis.set_xlabel("time [s]")
    axis.set_ylabel(with_unit(channel, drawn[0][3]))
    axis.grid(True, alpha=0.3)
    missing = len(ids) - len(drawn)
    axis.set_title(f"{name}: {scenario}/{channel} of {len(drawn)} runs"
                   + (f" ({missing} without a trace left out)" if missing else ""))
    return figure


def plot_sweep_traces(path, channel, output, scenario=None, runs=None):
    save(sweep_traces_figure(path, channel, scenario, runs), output)
