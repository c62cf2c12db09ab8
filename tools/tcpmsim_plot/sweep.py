"""A sweep's summary (tcpmsim sweep's file): a metric as a heat map over two parameters of a grid
(a coloured scatter when they do not form one), or against one parameter as a scatter, its
points coloured by another column if asked: one colour per value, named in a legend, when that
column has few values (DISCRETE_VALUES at most), else a colour bar. Failed runs are left out and
counted in the title; a structural axis (text values) is placed by its values' order. A numeric
axis is logarithmic when its values are positive and span more than a decade, or are log-spaced
(a geometric sequence, as `spacing: log`). Temperatures (a parameter or a metric of a channel's
value in K) are drawn in degC, a temperature difference (an rmse) in degC without the offset,
lengths in mm."""
import numpy as np
from matplotlib.ticker import FixedLocator, FuncFormatter, LogLocator, NullLocator

from tcpmsim_plot.common import (PlotError, display, display_difference, is_absolute_temperature,
                                 open_file, plt, save, sweep_metric_types, text_attribute, texts,
                                 units, with_unit)

# A colour column with at most this many distinct values gets one colour per value and a legend.
DISCRETE_VALUES = 8


def column(summary, path, name, metric_types=None):
    """A summary column as numbers (text columns as their values' ranks), its display unit and
    its texts (None for a numeric column)."""
    if name not in summary:
        raise PlotError(f"{path} has no summary column '{name}' (it has: {', '.join(summary)})")
    values = summary[name][:]
    if values.dtype.kind in "SOU":  # a structural axis' texts
        labels = texts(values)
        order = sorted(set(labels), key=labels.index)
        return np.array([order.index(v) for v in labels], dtype=float), "", order
    unit = units(summary[name])
    values = values.astype(float)
    if is_absolute_temperature(name, unit, metric_types or {}):
        values, unit = display(values, unit)
    else:  # a difference (an rmse of a temperature: degC without the offset), a length in mm
        values, unit = display_difference(values, unit)
    return values, unit, None


def logarithmic(values):
    """Whether an axis of these values reads best on a log scale: all positive and either
    spanning more than a decade or log-spaced (three or more distinct values in a geometric,
    not an arithmetic, sequence)."""
    values = np.asarray(values, dtype=float)
    values = values[np.isfinite(values)]
    if len(values) == 0 or values.min() <= 0.0:
        return False
    if values.max() / values.min() > 10.0:
        return True
    distinct = np.unique(values)
    if len(distinct) < 3:
        return False
    ratios, steps = distinct[1:] / distinct[:-1], np.diff(distinct)
    geometric = np.ptp(np.log(ratios)) <= 1e-6 * np.abs(np.log(ratios)).max()
    arithmetic = np.ptp(steps) <= 1e-6 * np.abs(steps).max()
    return bool(geometric and not arithmetic)


def ticks(axis_set, values, names):
    """Tick labels: the texts of a text column, else the values."""
    positions = np.arange(len(values)) + 0.5
    shown = [names[int(v)] for v in values] if names else [f"{v:.3g}" for v in values]
    axis_set(positions, shown)


def heat_map(axis, x, y, metric, x_names, y_names):
    """The heat map if (x, y) is a complete grid of distinct pairs, else None."""
    xs, ys = np.unique(x), np.unique(y)
    pairs = set(zip(x.tolist(), y.tolist()))
    if len(pairs) != len(x) or len(pairs) != len(xs) * len(ys):
        return None
    grid = np.full((len(ys), len(xs)), np.nan)
    for value, a, b in zip(metric, x, y):
        grid[np.searchsorted(ys, b), np.searchsorted(xs, a)] = value
    image = axis.pcolormesh(np.arange(len(xs) + 1), np.arange(len(ys) + 1),
                            np.ma.masked_invalid(grid), cmap="viridis", shading="flat")
    for j in range(len(ys)):
        for i in range(len(xs)):
            missing = np.isnan(grid[j, i])
            axis.text(i + 0.5, j + 0.5, "no value" if missing else f"{grid[j, i]:.3g}",
                      ha="center", va="center", fontsize=7, color="grey" if missing else "white")
    ticks(axis.set_xticks, xs, x_names)
    ticks(axis.set_yticks, ys, y_names)
    return image


def scale_axis(axis, which, values, names):
    """A log scale for a numeric axis that reads best so (logarithmic), its ticks in plain
    numbers: at the values themselves when there are few (a swept parameter's)."""
    if names is not None or not logarithmic(values):
        return
    (axis.set_xscale if which == "x" else axis.set_yscale)("log")
    part = axis.xaxis if which == "x" else axis.yaxis
    distinct = np.unique(np.asarray(values, dtype=float)[np.isfinite(values)])
    plain = FuncFormatter(lambda value, _: f"{value:.3g}")
    if len(distinct) <= 10:
        part.set_major_locator(FixedLocator(distinct))
        part.set_minor_locator(NullLocator())
    elif distinct.max() / distinct.min() < 100.0:
        part.set_minor_locator(LogLocator(subs=(2.0, 5.0)))
        part.set_minor_formatter(plain)
    part.set_major_formatter(plain)


def sweep_figure(path, x_name, y_name, metric_name, colour_name=None):
    """The figure of a sweep's metric (a heat map over x and y, or a scatter against x)."""
    with open_file(path, required="summary") as handle:
        summary = handle["summary"]
        metric_types = sweep_metric_types(handle)
        x, x_unit, x_names = column(summary, path, x_name, metric_types)
        metric, metric_unit, _ = column(summary, path, metric_name, metric_types)
        ok = np.array([s == "ok" for s in texts(summary["status"][:])]) & np.isfinite(metric)
        if not ok.any():
            raise PlotError(f"{path}: no run has a value of '{metric_name}'")
        colour = y = None
        if colour_name is not None and y_name is None:
            colour, colour_unit, colour_names = column(summary, path, colour_name, metric_types)
        if y_name is not None:
            y, y_unit, y_names = column(summary, path, y_name, metric_types)
        name = text_attribute(handle, "sweep")
    figure, axis = plt.subplots(figsize=(6.8, 4.8), layout="constrained")
    metric_label = with_unit(metric_name, metric_unit)
    if y_name is None:
        if colour is None:
            axis.plot(x[ok], metric[ok], "o", markersize=4)
        else:
            values = np.unique(colour[ok])
            if colour_names is not None or len(values) <= DISCRETE_VALUES:
                shades = plt.get_cmap("viridis")
                for k, value in enumerate(values):
                    chosen = ok & (colour == value)
                    order = np.argsort(x[chosen])
                    shown = (colour_names[int(value)] if colour_names is not None
                             else f"{value:.3g}" + (f" {colour_unit}" if colour_unit else ""))
                    axis.plot(x[chosen][order], metric[chosen][order], "o-", markersize=4,
                              linewidth=0.7, color=shades(k / max(len(values) - 1, 1)), label=shown)
                axis.legend(title=colour_name, fontsize=8, title_fontsize=8)
            else:
                points = axis.scatter(x[ok], metric[ok], c=colour[ok], cmap="viridis", s=18)
                figure.colorbar(points, ax=axis, label=with_unit(colour_name, colour_unit))
        if x_names:
            axis.set_xticks(range(len(x_names)), x_names)
        scale_axis(axis, "x", x[ok], x_names)
        scale_axis(axis, "y", metric[ok], None)
        axis.set_ylabel(metric_label)
        axis.grid(True, which="both", alpha=0.3)
    else:
        values = np.where(ok, metric, np.nan)
        image = heat_map(axis, x, y, values, x_names, y_names)
        if image is None:  # not a grid over these two (Latin hypercube, zipped, random)
            image = axis.scatter(x[ok], y[ok], c=metric[ok], cmap="viridis")
            scale_axis(axis, "x", x[ok], x_names)
            scale_axis(axis, "y", y[ok], y_names)
            if x_names:
                axis.set_xticks(range(len(x_names)), x_names)
            if y_names:
                axis.set_yticks(range(len(y_names)), y_names)
        figure.colorbar(image, ax=axis, label=metric_label)
        axis.set_ylabel(with_unit(y_name, y_unit))
    axis.set_xlabel(with_unit(x_name, x_unit))
    left_out = int((~ok).sum())
    axis.set_title(f"{name}: {metric_name}"
                   + (f"\n({left_out} runs without a value left out)" if left_out else ""))
    return figure


def plot_sweep(path, x_name, y_name, metric_name, output, colour_name=None):
    save(sweep_figure(path, x_name, y_name, metric_name, colour_name), output)
