"""A sweep's summary (tcpmsim sweep's file): a metric as a heat map over two parameters of a grid
(a coloured scatter when they do not form one), or against one parameter as a scatter, its
points coloured by another column if asked. Failed runs are left out and counted in the title;
a structural axis (text values) is placed by its values' order."""
import numpy as np

from tcpmsim_plot.common import PlotError, open_file, plt, save, texts, units


def column(summary, path, name):
    """A summary column as numbers (text columns as their values' ranks) with its axis labels."""
    if name not in summary:
        raise PlotError(f"{path} has no summary column '{name}' (it has: {', '.join(summary)})")
    values = summary[name][:]
    if values.dtype.kind in "SOU":  # a structural axis' texts
        labels = texts(values)
        order = sorted(set(labels), key=labels.index)
        return np.array([order.index(v) for v in labels], dtype=float), "", order
    return values.astype(float), units(summary[name]), None


def label(name, unit):
    return f"{name} [{unit}]" if unit else name


def ticks(axis_set, values, names):
    """Tick labels: the texts of a text column, else the values."""
    positions = np.arange(len(values)) + 0.5
    shown = [names[int(v)] for v in values] if names else [f"{v:.3g}" for v in values]
    axis_set(positions, shown)


def heat_map(figure, axis, x, y, metric, x_names, y_names):
    """True if (x, y) is a complete grid of distinct pairs (then drawn as one), else False."""
    xs, ys = np.unique(x), np.unique(y)
    pairs = set(zip(x.tolist(), y.tolist()))
    if len(pairs) != len(x) or len(pairs) != len(xs) * len(ys):
        return False
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


def plot_sweep(path, x_name, y_name, metric_name, output, colour_name=None):
    handle = open_file(path, required="summary")
    summary = handle["summary"]
    x, x_unit, x_names = column(summary, path, x_name)
    metric, metric_unit, _ = column(summary, path, metric_name)
    ok = np.array([s == "ok" for s in texts(summary["status"][:])]) & np.isfinite(metric)
    if not ok.any():
        raise PlotError(f"{path}: no run has a value of '{metric_name}'")
    figure, axis = plt.subplots(figsize=(6.4, 4.8))
    metric_label = label(metric_name, metric_unit)
    if y_name is None:
        if colour_name is None:
            axis.plot(x[ok], metric[ok], "o", markersize=4)
        else:
            colour, colour_unit, _ = column(summary, path, colour_name)
            points = axis.scatter(x[ok], metric[ok], c=colour[ok], cmap="viridis", s=18)
            figure.colorbar(points, ax=axis, label=label(colour_name, colour_unit))
        if x_names:
            axis.set_xticks(range(len(x_names)), x_names)
        axis.set_ylabel(metric_label)
        axis.grid(True, alpha=0.3)
    else:
        y, y_unit, y_names = column(summary, path, y_name)
        values = np.where(ok, metric, np.nan)
        image = heat_map(figure, axis, x, y, values, x_names, y_names)
        if image is False:  # not a grid over these two (Latin hypercube, zipped, random)
            image = axis.scatter(x[ok], y[ok], c=metric[ok], cmap="viridis")
        figure.colorbar(image, ax=axis, label=metric_label)
        axis.set_ylabel(label(y_name, y_unit))
    axis.set_xlabel(label(x_name, x_unit))
    left_out = int((~ok).sum())
    axis.set_title(f"{handle.attrs.get('sweep', '')}: {metric_name}"
                   + (f"\n({left_out} runs without a value left out)" if left_out else ""))
    save(figure, output)
