"""What every picture shares: opening a file, display units, saving.

Each picture is built by a function that returns its matplotlib Figure (`*_figure`), apart from
the one that writes it (`plot_*`), so that a test or a notebook can look at the figure."""
import re
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402,F401  (re-exported for the plot modules)

# Display conversions: SI unit in the file -> (offset, scale, display unit). Temperatures are
# drawn in degC, lengths in mm.
DISPLAY = {"K": (-273.15, 1.0, "degC"), "m": (0.0, 1e3, "mm")}


class PlotError(Exception):
    """One clear message for the user: the file, what is missing, what was expected."""


def open_file(path, required=None):
    """An HDF5 file opened for reading; `required` names a dataset or group it must hold."""
    try:
        handle = h5py.File(path, "r")
    except OSError as error:
        raise PlotError(f"cannot read {path}: {error}") from error
    if required is not None and required not in handle:
        handle.close()
        raise PlotError(f"{path} has no '{required}': is it the right kind of tcpmsim file?")
    return handle


def dataset(handle, path, name):
    """handle[name] (a dataset, or a group of them), or a PlotError naming the file."""
    if name not in handle:
        raise PlotError(f"{path} has no dataset '{name}'")
    return handle[name]


def display(values, unit):
    """Values of an absolute quantity in display units (a temperature in degC)."""
    offset, scale, shown = DISPLAY.get(unit, (0.0, 1.0, unit))
    return (values + offset) * scale, shown


def display_difference(values, unit):
    """A difference (a residual, an error) in display units: scaled, never offset. A
    temperature difference is the same number in degC as in K."""
    _, scale, shown = DISPLAY.get(unit, (0.0, 1.0, unit))
    return values * scale, shown


def units(item):
    value = item.attrs.get("units", "")
    return value.decode() if isinstance(value, bytes) else value


def text_attribute(handle, name, default=""):
    value = handle.attrs.get(name, default)
    if isinstance(value, bytes):
        return value.decode()
    return value if isinstance(value, str) else str(value)


def texts(values):
    return [v.decode() if isinstance(v, bytes) else str(v) for v in values]


def with_unit(name, unit):
    return f"{name} [{unit}]" if unit else name


def sweep_sections(config):
    """A resolved sweep file's (`/sweep_config`) top-level sections as texts, by key."""
    sections, key = {}, None
    for line in config.splitlines():
        match = re.match(r"^([A-Za-z_]\w*):(.*)$", line)
        if match:
            key = match.group(1)
            sections[key] = match.group(2) + "\n"
        elif key is not None:
            sections[key] += line + "\n"
    return sections


def sweep_axes(handle):
    """The parameter paths of a sweep file's axes (not its derived parameters), in order."""
    axes = sweep_sections(text_attribute(handle, "sweep_config")).get("axes", "")
    return re.findall(r"parameter:\s*([^\s,{}\[\]]+)", axes)


def sweep_metric_types(handle):
    """A sweep's metrics by name: their type (final_value, rmse, ...)."""
    metrics = sweep_sections(text_attribute(handle, "sweep_config")).get("metrics", "")
    found = {}
    for item in re.findall(r"\{([^{}]*)\}", metrics):
        name = re.search(r"(?:^|,)\s*name:\s*([^,\s]+)", item)
        kind = re.search(r"(?:^|,)\s*type:\s*([^,\s]+)", item)
        if name and kind:
            found[name.group(1)] = kind.group(1)
    return found


# Metrics that are a value of their channel (a temperature: absolute); the others in K (an rmse)
# are differences.
ABSOLUTE_METRICS = {"final_value", "maximum", "minimum", "mean"}


def is_absolute_temperature(name, unit, metric_types):
    """Whether a sweep's summary column in K is a temperature (drawn in degC with the offset)
    rather than a temperature difference (the same number in degC)."""
    if unit != "K":
        return False
    if name in metric_types:
        return metric_types[name] in ABSOLUTE_METRICS
    return "temperature" in name.split(".")[-1]


def save(figure, output):
    if not output.lower().endswith((".png", ".svg")):
        plt.close(figure)
        raise PlotError(f"{output}: the output must end in .png or .svg")
    if figure.get_layout_engine() is None:
        figure.tight_layout()
    try:
        figure.savefig(output, dpi=110)
    except OSError as error:
        raise PlotError(f"cannot write {output}: {error.strerror or error}") from error
    finally:
        plt.close(figure)
    print(f"wrote {output}")


def fail(error):
    sys.exit(f"tcpmsim-plot: {error}")
