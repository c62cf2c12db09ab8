"""tcpmsim discover's pictures: the residuals before and after, and the diagnostic that gave the
effect away."""
import json
import os

import numpy as np

from tcpmsim_plot.common import PlotError, dataset, display_difference, open_file, plt, save, texts, units

# The feature of the base residual each named effect should correlate with (its signature).
SIGNATURE_FEATURE = {
    "hysteresis": "last direction of motion",
    "viscoelastic_relaxation": "deflection rate",
    "nonlinear_convection": "temperature rise",
    "inductance_temperature": "temperature rise",
    "nonlinear_stiffness": "deflection^2",
    "temperature_dependent_stiffness": "temperature rise x deflection",
    "ratchet": "temperature rise",
    "heating_dependent_convection": "power",
}


def read_summary(directory):
    path = os.path.join(directory, "discovery.json")
    try:
        with open(path, encoding="utf-8") as file:
            return json.load(file)
    except (OSError, ValueError) as error:
        raise PlotError(f"cannot read {path}: {error}") from error


def plot_residuals(handle, path, summary, output):
    time = dataset(handle, path, "time")[()]
    channels = list(dataset(handle, path, "measured").keys())
    window = dataset(handle, path, "validation_window")[()]
    figure, axes = plt.subplots(len(channels), 1, figsize=(9, 2.8 * len(channels)), squeeze=False)
    effect = summary["augmented"]["effect"]
    for axis, channel in zip(axes[:, 0], channels):
        before = handle[f"residual/baseline/{channel}"]
        after = handle[f"residual/augmented/{channel}"]
        # a residual is a difference: a temperature's in degC without the offset
        values, unit = display_difference(before[()], units(before))
        axis.plot(time, values, lw=0.6, color="tab:red", label="base model")
        if effect:
            values, _ = display_difference(after[()], units(after))
            axis.plot(time, values, lw=0.6, color="tab:blue", label=f"with {effect}")
        axis.axvspan(window[0], window[1], color="0.92", zorder=0, label="validation")
        axis.set_ylabel(f"{channel} residual [{unit}]")
        axis.legend(loc="upper left", fontsize=8)
    axes[-1, 0].set_xlabel("time [s]")
    closed = summary.get("gap_closed")
    axes[0, 0].set_title(f"measured - simulated; verdict: {summary['verdict']}"
                         + (f" ({100 * closed:.0f} % of the gap above the noise floor closed)"
                            if effect and closed is not None else ""))
    save(figure, output)


def plot_diagnostic(handle, path, summary, output):
    channels = list(dataset(handle, path, "diagnostics").keys())
    channel = channels[0]
    verdict = summary["verdict"]
    if verdict == "inductance_temperature":
        channel = next((c for c in channels if "inductance" in c or "decay" in c), channel)
    group = handle[f"diagnostics/{channel}"]
    bound = summary["diagnostics"]["white_noise_bound"]
    figure, axes = plt.subplots(1, 3, figsize=(13, 3.8))
    names = texts(group["feature_names"][()])
    values = group["feature_correlation"][()]
    wanted = SIGNATURE_FEATURE.get(verdict)
    colours = ["tab:orange" if name == wanted else "tab:gray" for name in names]
    axes[0].barh(range(len(names)), values, color=colours)
    axes[0].set_yticks(range(len(names)), names, fontsize=8)
    for edge in (-bound, bound):
        axes[0].axvline(edge, color="k", ls=":", lw=0.8)
    axes[0].set_xlabel(f"correlation with the {channel} residual")
    frequency = group["loop_frequency"][()]
    quadrature, quadrature_unit = display_difference(group["loop_quadrature"][()],
                                                     units(group["loop_quadrature"]))
    if len(frequency):
        axes[1].loglog(frequency, np.abs(quadrature), "o-")
        exponent = summary["diagnostics"]["outputs"][channel]["loop"]["exponent"]
        title = "loop area against frequency" + (f" ~ f^{exponent:.2f}" if exponent is not None else "")
        axes[1].set_title(title, fontsize=9)
    axes[1].set_xlabel("frequency [Hz]")
    axes[1].set_ylabel(f"|quadrature residual| [{quadrature_unit}]")
    if "cross_correlation" in group:
        for name, series in group["cross_correlation"].items():
            lags = np.arange(len(series)) - (len(series) - 1) // 2
            axes[2].plot(lags, series[()], label=name)
        axes[2].axhspan(-bound, bound, color="0.9")
        axes[2].legend(fontsize=8)
    axes[2].set_xlabel("lag [samples]")
    axes[2].set_ylabel("input-residual cross-correlation")
    evidence = next((c.get("evidence", "") for c in summary["ranking"] if c["effect"] == verdict), "")
    figure.suptitle(f"base model's validation residual; verdict: {verdict}" +
                    (f"\n{evidence}" if evidence else ""), fontsize=9)
    save(figure, output)


def plot_discovery(directory, output_directory):
    summary = read_summary(directory)
    path = os.path.join(directory, "traces.h5")
    output_directory = output_directory or directory
    with open_file(path, required="residual") as handle:
        plot_residuals(handle, path, summary, os.path.join(output_directory, "residuals.png"))
        plot_diagnostic(handle, path, summary, os.path.join(output_directory, "diagnostic.png"))
