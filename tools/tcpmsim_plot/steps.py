"""Step responses with their rise and settling marks, as `tcpmsim analyze` measures them
(analysis/step_response.h, step_metrics).

A step is a change of the reference between consecutive samples; its segment lasts until the
next step (or the end of the record). y0 is the response at the sample before the step, the
final value y_f the mean response over the last 10 % of the segment (at least one sample). The
rise runs from the first time the response reaches y0 + lower (y_f - y0) to the first time it
reaches y0 + upper (y_f - y0), crossings interpolated linearly; a step whose response does not
cross both within its segment never rose (a cross). It settles when it enters the band
|y - y_f| <= band |y_f - y0| for good (interpolated); a response outside the band at the
segment's end never settled. So the marks hold for a response in other units than its
reference (power in, force out): the two are then drawn on two panels, each in its unit.

`to_reference` (--to-reference) draws the control tasks' rise times instead
(analysis/control_tasks.h, `tcpmsim control-tasks`, `tcpmsim.control_task`): y0 is the response
at the step's first sample, the levels lie between it and the new reference, and a response
that does not reach the upper level within the step never rose (a cross; the control tasks
charge it the step's hold). The reference and the response must then share a unit."""
import h5py
import numpy as np

from tcpmsim_plot.common import (PlotError, dataset, display, open_file, plt, save, text_attribute,
                                 units)


def first_reaching(time, values, first, last, level, direction):
    """First time in samples [first, last) at which values reach `level` going in `direction`
    (interpolated linearly), or NaN."""
    hits = np.nonzero(direction * (values[first:last] - level) >= 0.0)[0]
    if len(hits) == 0:
        return float("nan")
    i = first + hits[0]
    if i == first:
        return float(time[i])
    fraction = (level - values[i - 1]) / (values[i] - values[i - 1])
    return float(time[i - 1] + fraction * (time[i] - time[i - 1]))


def settling_time(time, values, first, last, final, band):
    """Time from the step until the response stays within `band` of `final`; NaN if the last
    sample is outside."""
    outside = np.nonzero(np.abs(values[first:last] - final) > band)[0]
    if len(outside) == 0:
        return 0.0
    k = first + outside[-1]
    if k + 1 == last:
        return float("nan")
    d0, d1 = abs(values[k] - final), abs(values[k + 1] - final)
    return float(time[k] + (d0 - band) / (d0 - d1) * (time[k + 1] - time[k]) - time[first])


def step_metrics(time, reference, response, lower=0.1, upper=0.9, settling_band=0.02,
                 final_fraction=0.1):
    """Per step of the reference, as `tcpmsim analyze` (step_metrics): dicts with step_time,
    index, last (the segment's end), start (y0), final_value, lower_time, upper_time,
    rise_time, settling_time (NaN where not reached)."""
    time, reference, response = (np.asarray(a, dtype=float) for a in (time, reference, response))
    steps = np.nonzero(np.diff(reference) != 0)[0] + 1
    found = []
    for n, index in enumerate(steps):
        last = int(steps[n + 1]) if n + 1 < len(steps) else len(time)
        samples = last - index
        averaged = max(1, int(np.floor(final_fraction * samples)))
        start = response[index - 1]
        final = float(np.mean(response[last - averaged:last]))
        size = final - start
        direction = 1.0 if size >= 0.0 else -1.0
        low = first_reaching(time, response, index, last, start + lower * size, direction)
        high = first_reaching(time, response, index, last, start + upper * size, direction)
        nan = float("nan")
        found.append({
            "step_time": float(time[index]), "index": int(index), "last": last,
            "start": float(start), "final_value": final,
            "lower_time": low if size != 0.0 else nan, "upper_time": high if size != 0.0 else nan,
            "rise_time": high - low if size != 0.0 else nan,
            "settling_time": (settling_time(time, response, index, last, final,
                                            settling_band * abs(size)) if size != 0.0 else nan)})
    return found


def rises_to_reference(time, reference, response, lower=0.1, upper=0.9):
    """Per step of the reference, as the control tasks (step_rise_times): dicts with step_time,
    index, last, start (the response at the step's first sample), target (the new reference),
    lower_time, upper_time and rise_time (NaN where the upper level is not reached)."""
    time, reference, response = (np.asarray(a, dtype=float) for a in (time, reference, response))
    steps = np.nonzero(np.diff(reference) != 0)[0] + 1
    found = []
    for n, index in enumerate(steps):
        last = int(steps[n + 1]) if n + 1 < len(steps) else len(time)
        start, target = float(response[index]), float(reference[index])
        size = target - start
        if size == 0.0:
            low = high = float(time[index])
        else:
            direction = 1.0 if size > 0.0 else -1.0
            low = first_reaching(time, response, index, last, start + lower * size, direction)
            high = first_reaching(time, response, index, last, start + upper * size, direction)
        found.append({"step_time": float(time[index]), "index": int(index), "last": last,
                      "start": start, "target": target, "lower_time": low, "upper_time": high,
                      "rise_time": high - low if np.isfinite(high) else float("nan")})
    return found


def steps_figure(path, reference_name, response_name, lower=0.1, upper=0.9, settling_band=0.02,
                 to_reference=False):
    """The figure of a record's step responses (the reference on its own panel when its unit
    differs from the response's) and the metrics drawn, as step_metrics gives them."""
    with open_file(path, required="time") as record:
        time = record["time"][:]
        reference = dataset(record, path, reference_name)
        response = dataset(record, path, response_name)
        for name, item in ((reference_name, reference), (response_name, response)):
            if not isinstance(item, h5py.Dataset):
                raise PlotError(f"'{name}' in {path} is a group, not a channel")
        r_si, y_si = reference[:].astype(float), response[:].astype(float)
        r_unit, y_unit = units(reference), units(response)
        scenario = text_attribute(record, "scenario")
    if r_si.ndim != 1 or y_si.ndim != 1:
        raise PlotError(f"{path}: '{reference_name}' and '{response_name}' must be single channels")
    changes = len(np.nonzero(np.diff(r_si) != 0)[0])
    if changes == 0:
        raise PlotError(f"'{reference_name}' in {path} has no step")
    if changes > len(time) // 4:
        raise PlotError(f"'{reference_name}' in {path} changes at {changes} of {len(time)} "
                        "samples: no step reference (a sweep: see its frequency response, "
                        "tcpmsim analyze)")
    if to_reference:
        if r_unit != y_unit:
            raise PlotError(f"--to-reference: '{reference_name}' [{r_unit}] and '{response_name}' "
                            f"[{y_unit}] in {path} do not share a unit")
        metrics = rises_to_reference(time, r_si, y_si, lower, upper)
    else:
        metrics = step_metrics(time, r_si, y_si, lower, upper, settling_band)
    r, r_shown = display(r_si, r_unit)
    y, y_shown = display(y_si, y_unit)

    if r_shown == y_shown:
        figure, axis = plt.subplots(figsize=(10, 4.2), layout="constrained")
        reference_axis = axis
        axis.set_ylabel(f"{response_name}, {reference_name} [{y_shown}]")
    else:
        figure, (reference_axis, axis) = plt.subplots(
            2, 1, sharex=True, figsize=(10, 5.4), layout="constrained",
            gridspec_kw={"height_ratios": [1, 2.4]})
        reference_axis.set_ylabel(f"{reference_name}\n[{r_shown}]", fontsize=9)
        reference_axis.grid(True, alpha=0.3)
        axis.set_ylabel(f"{response_name}\n[{y_shown}]", fontsize=9)
    reference_axis.plot(time, r, color="grey", linewidth=0.9, drawstyle="steps-post",
                        label=reference_name)
    axis.plot(time, y, linewidth=0.9, color="tab:blue", label=response_name)

    def y_at(t):
        return display(np.interp(t, time, y_si), y_unit)[0]

    rises, settlings = [], []
    labelled = set()

    def once(name):  # a legend entry for the first mark of each kind only
        if name in labelled:
            return None
        labelled.add(name)
        return name

    for step in metrics:
        segment = slice(step["index"], step["last"])
        if not to_reference:
            final_shown = display(step["final_value"], y_unit)[0]
            axis.plot([time[segment][0], time[segment][-1]], [final_shown, final_shown], ":",
                      color="tab:green", linewidth=0.8, label=once("final value y_f"))
        if np.isfinite(step["rise_time"]):
            rises.append(step["rise_time"])
            marks = [step["lower_time"], step["upper_time"]]
            axis.plot(marks, y_at(marks), "o", markersize=3, color="black",
                      label=once(f"{lower:.0%}-{upper:.0%} of "
                                 + ("r - y0" if to_reference else "y_f - y0")))
            axis.annotate(f"{step['rise_time']:.3g} s", (marks[1], y_at(marks[1])), fontsize=7,
                          xytext=(3, 3), textcoords="offset points")
        else:
            axis.plot(step["step_time"], y_at(step["step_time"]), "x", color="red",
                      label=once("never rose"))
        if np.isfinite(step.get("settling_time", float("nan"))):
            settlings.append(step["settling_time"])
            settled = step["step_time"] + step["settling_time"]
            axis.plot(settled, y_at(settled), "d", markersize=4, color="tab:purple",
                      label=once(f"settled (+-{settling_band:.0%})"))
    axis.set_xlabel("time [s]")
    axis.grid(True, alpha=0.3)
    axis.legend(fontsize=7, loc="best")
    if reference_axis is not axis:
        reference_axis.legend(fontsize=7, loc="best")
    summary = f", median rise time {np.median(rises):.3g} s" if rises else ", no step rose"
    if settlings:
        summary += f", median settling time {np.median(settlings):.3g} s"
    definition = "to the reference" if to_reference else "of y_f - y0"
    reference_axis.set_title(
        f"{scenario}: {lower:.0%}-{upper:.0%} rise times {definition}{summary}", fontsize=10)
    figure.metrics = metrics  # what was drawn, for a test or a notebook
    return figure


def plot_steps(path, reference_name, response_name, output, lower=0.1, upper=0.9,
               settling_band=0.02, to_reference=False):
    save(steps_figure(path, reference_name, response_name, lower, upper, settling_band,
                      to_reference), output)
