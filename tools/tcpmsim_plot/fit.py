"""tcpmsim fit's result (its --out directory: fit.json and fit.h5): per compared output, the
measured channel with the model's output before (the initial values) and after the fit over time,
the identification and validation windows shaded, and below it the residual, measured - fitted
(and measured - initial, faint). The windows' RMSE and R2 and the estimates come from fit.json."""
import json
import os

import numpy as np

from tcpmsim_plot.common import (PlotError, dataset, display, display_difference, open_file, plt,
                                 save, units)

WINDOWS = {"identification": ("identification_window", "tab:blue"),
           "validation": ("validation_window", "tab:orange")}


def fit_files(location):
    """The fit's directory, fit.json and fit.h5 from a directory or either file's path."""
    directory = location if os.path.isdir(location) else os.path.dirname(location) or "."
    paths = [os.path.join(directory, name) for name in ("fit.json", "fit.h5")]
    missing = [p for p in paths if not os.path.isfile(p)]
    if missing:
        raise PlotError(f"{location} is no tcpmsim fit --out directory: no {', '.join(missing)}")
    return directory, paths[0], paths[1]


def read_json(path):
    try:
        with open(path, encoding="utf-8") as file:
            return json.load(file)
    except (OSError, ValueError) as error:
        raise PlotError(f"cannot read {path}: {error}") from error


def _window(handle, name):
    if name not in handle:
        return None
    window = np.ravel(handle[name][()]).astype(float)
    usable = len(window) == 2 and np.all(np.isfinite(window)) and window[1] > window[0]
    return window if usable else None


def _quality(summary, channel, unit):
    parts = []
    for window in WINDOWS:
        scores = (summary.get(window) or {}).get(channel)
        if scores and scores.get("rmse") is not None:
            rmse, shown = display_difference(np.float64(scores["rmse"]), unit)
            text = f"{window} RMSE {rmse:.3g} {shown}"
            if scores.get("r2") is not None:
                text += f", R2 {scores['r2']:.6g}"
            parts.append(text)
    return "; ".join(parts)


def _estimates(summary):
    texts = []
    for p in summary.get("parameters", []):
        text = f"{p['path'].rsplit('.', 1)[-1]} = {p['estimate']:.4g}"
        if p.get("standard_error") is not None:
            text += f" +- {p['standard_error']:.2g}"
        text += f" {p.get('unit', '')}".rstrip()
        if p.get("identifiable") is False:
            text += " (poor)"
        texts.append(text)
    return "\n".join("; ".join(texts[k:k + 3]) for k in range(0, len(texts), 3))


def fit_figure(location):
    """The figure of a fit's measured and fitted outputs with their residuals."""
    directory, json_path, h5_path = fit_files(location)
    summary = read_json(json_path)
    with open_file(h5_path, required="measured") as handle:
        time = dataset(handle, h5_path, "time")[()]
        channels = list(handle["measured"].keys())
        if not channels:
            raise PlotError(f"{h5_path} holds no measured channel")
        windows = {name: _window(handle, key) for name, (key, _) in WINDOWS.items()}
        series = {}
        for channel in channels:
            measured = handle[f"measured/{channel}"]
            unit = units(measured)
            series[channel] = {
                "unit": unit,
                **{kind: handle[f"{kind}/{channel}"][()].astype(float)
                   for kind in ("measured", "fitted", "initial") if f"{kind}/{channel}" in handle}}
            if "fitted" not in series[channel]:
                raise PlotError(f"{h5_path} has no fitted output of '{channel}'")
    figure, axes = plt.subplots(2 * len(channels), 1, sharex=True, squeeze=False,
                                layout="constrained", figsize=(10, 1.6 + 4.2 * len(channels)),
                                gridspec_kw={"height_ratios": [2.4, 1.0] * len(channels)})
    for k, channel in enumerate(channels):
        top, bottom = axes[2 * k, 0], axes[2 * k + 1, 0]
        data, unit = series[channel], series[channel]["unit"]
        measured, shown = display(data["measured"], unit)
        top.plot(time, measured, color="black", linewidth=0.6, label="measured")
        if "initial" in data:
            top.plot(time, display(data["initial"], unit)[0], color="tab:gray", linewidth=0.8,
                     linestyle="--", label="initial model")
        top.plot(time, display(data["fitted"], unit)[0], color="tab:red", linewidth=0.9,
                 label="fitted model")
        residual, difference = display_difference(data["measured"] - data["fitted"], unit)
        if "initial" in data:
            bottom.plot(time, display_difference(data["measured"] - data["initial"], unit)[0],
                        color="tab:gray", linewidth=0.5, alpha=0.7, label="measured - initial")
        bottom.plot(time, residual, color="tab:red", linewidth=0.6, label="measured - fitted")
        bottom.axhline(0.0, color="black", linewidth=0.5)
        for axis in (top, bottom):
            for name, window in windows.items():
                if window is not None:
                    axis.axvspan(window[0], window[1], color=WINDOWS[name][1], alpha=0.08,
                                 zorder=0, label=f"{name} window" if axis is top else None)
            axis.grid(True, alpha=0.3)
        top.set_ylabel(f"{channel}\n[{shown}]" if shown else channel, fontsize=9)
        bottom.set_ylabel(f"residual\n[{difference}]" if difference else "residual", fontsize=9)
        top.legend(fontsize=7, loc="best", ncol=2)
        bottom.legend(fontsize=7, loc="best")
        top.set_title(f"{channel}: {_quality(summary, channel, unit)}", fontsize=9)
    axes[-1, 0].set_xlabel("time [s]")
    model = os.path.basename(str(summary.get("model", "")))
    data_name = os.path.basename(str(summary.get("data", "")))
    heading = f"fit of {model} to {data_name}" if model or data_name else f"fit in {directory}"
    estimates = _estimates(summary)
    figure.suptitle(heading + (f"\n{estimates}" if estimates else ""), fontsize=10)
    return figure


def plot_fit(location, output=None):
    if output is None:
        output = os.path.join(fit_files(location)[0], "fit.png")
    save(fit_figure(location), output)
