"""A sweep's summary (tcpmsim sweep's file): a metric as a heat map over two parameters of a grid
(a coloured scatter when they do not form one), or against one parameter as a scatter, its
points coloured by another column if asked."""
import numpy as np

from tcpmsim_plot.common import PlotError, open_file, plt, save, texts, units


def column(summary, path, name):
    if name not in summary:
        raise PlotError(f"{path} has no summary column '{name}' (it has: {', '.join(summary)})")
    return summary[name][:], units(summary[name])


def plot_sweep(path, x_name, y_name, metric_name, output, colour_name=None):
    handle = open_file(path, required="summary")
    summary = handle["summary"]
    x, x_unit = column(summary, path, x_name)
    metric, metric_unit = column(summary, path, metric_name)
    ok = np.array([s == "ok" for s in texts(summary["status"][:])])
    figure, axis = plt.subplots(figsize=(6.4, 4.8))
    if y_name is None:
        if colour_name is None:
            axis.plot(x[ok], metric[ok], "o", markersize=4)
        else:
            colour, colour_unit = column(summary, path, colour_name)
            points = axis.scatter(x[ok], metric[ok], c=colour[ok], cmap="viridis", s=18)
            figure.colorbar(points, ax=axis, label=f"{colour_name} [{colour_unit}]")
        if (~ok).any():
            axis.plot(x[~ok], np.zeros((~ok).sum()), "x", color="red", label="failed runs")
            axis.legend(fontsize=8)
        axis.set_xlabel(f"{x_name} [{x_unit}]")
        axis.set_ylabel(f"{metric_name} [{metric_unit}]")
        axis.grid(True, alpha=0.3)
    else:
        y, y_unit = column(summary, path, y_name)
        xs, ys = np.unique(x), np.unique(y)
        if len(xs) * len(ys) != len(x):
            # Not a grid over these two (a Latin hypercube, random draws): a coloured scatter.
            points = axis.scatter(x, y, c=metric, cmap="viridis")
            figure.colorbar(points, ax=axis, label=f"{metric_name} [{metric_unit}]")
        else:
            grid = np.full((len(ys), len(xs)), np.nan)
            for value, a, b in zip(metric, x, y):
                grid[np.searchsorted(ys, b), np.searchsorted(xs, a)] = value
            image = axis.pcolormesh(np.arange(len(xs) + 1), np.arange(len(ys) + 1), grid,
                                    cmap="viridis", shading="flat")
            figure.colorbar(image, ax=axis, label=f"{metric_name} [{metric_unit}]")
            for j in range(len(ys)):
                for i in range(len(xs)):
                    axis.text(i + 0.5, j + 0.5, f"{grid[j, i]:.3g}", ha="center", va="center",
                              fontsize=7, color="white")
            axis.set_xticks(np.arange(len(xs)) + 0.5, [f"{v:.3g}" for v in xs])
            axis.set_yticks(np.arange(len(ys)) + 0.5, [f"{v:.3g}" for v in ys])
        axis.set_xlabel(f"{x_name} [{x_unit}]")
        axis.set_ylabel(f"{y_name} [{y_unit}]")
    axis.set_title(f"{handle.attrs.get('sweep', '')}: {metric_name}")
    save(figure, output)
