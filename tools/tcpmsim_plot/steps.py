"""Step responses with their rise-time marks, as analysis/control_tasks.h measures them.

A step is a change of the reference between consecutive samples; y0 is the response at the step
and r the new reference; the rise runs from the first time the response reaches
y0 + lower (r - y0) to the first time it reaches y0 + upper (r - y0), crossings interpolated
linearly, before the next step (else it never rose: marked with a cross)."""
import numpy as np

from tcpmsim_plot.common import PlotError, dataset, display, open_file, plt, save, units


def crossing(time, values, begin, end, level, rising):
    """First time in samples [begin, end) at which values reach `level`, or None."""
    segment = values[begin:end] >= level if rising else values[begin:end] <= level
    hits = np.nonzero(segment)[0]
    if len(hits) == 0:
        return None
    k = begin + hits[0]
    if k == begin:
        return time[k]
    t0, t1, y0, y1 = time[k - 1], time[k], values[k - 1], values[k]
    return t0 + (level - y0) / (y1 - y0) * (t1 - t0) if y1 != y0 else t1


def rises(time, reference, response, lower, upper):
    steps = np.nonzero(np.diff(reference) != 0)[0] + 1
    found = []
    for n, k in enumerate(steps):
        end = steps[n + 1] if n + 1 < len(steps) else len(time)
        start, target = response[k], reference[k]
        rising = target > start
        low = crossing(time, response, k, end, start + lower * (target - start), rising)
        high = crossing(time, response, k, end, start + upper * (target - start), rising)
        found.append((time[k], low, high))
    return found


def plot_steps(path, reference_name, response_name, output, lower=0.1, upper=0.9):
    record = open_file(path, required="time")
    time = record["time"][:]
    reference = dataset(record, path, reference_name)
    response = dataset(record, path, response_name)
    r, shown = display(reference[:], units(reference))
    y, _ = display(response[:], units(response))
    if len(np.nonzero(np.diff(r) != 0)[0]) == 0:
        raise PlotError(f"'{reference_name}' in {path} has no step")
    figure, axis = plt.subplots(figsize=(10, 3.8))
    axis.plot(time, r, color="grey", linewidth=0.9, drawstyle="steps-post", label=reference_name)
    axis.plot(time, y, linewidth=0.9, label=response_name)
    times = []
    for step, low, high in rises(time, r, y, lower, upper):
        if low is None or high is None:
            axis.plot(step, np.interp(step, time, y), "x", color="red")
            continue
        times.append(high - low)
        axis.plot([low, high], np.interp([low, high], time, y), "o", markersize=3, color="black")
        axis.annotate(f"{high - low:.1f} s", (high, np.interp(high, time, y)), fontsize=7,
                      xytext=(3, 3), textcoords="offset points")
    axis.set_xlabel("time [s]")
    axis.set_ylabel(f"[{shown}]")
    axis.grid(True, alpha=0.3)
    axis.legend(fontsize=8)
    median = f", median rise time {np.median(times):.2f} s" if times else ""
    axis.set_title(f"{record.attrs.get('scenario', '')}: {lower:.0%}-{upper:.0%} rise times{median}")
    save(figure, output)
