"""What every picture shares: opening a file, display units, saving."""
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402,F401  (re-exported for the plot modules)

# Display conversions: SI unit in the file -> (offset, scale, display unit).
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
        raise PlotError(f"{path} has no '{required}': is it the right kind of tcpmsim file?")
    return handle


def dataset(handle, path, name):
    if name not in handle:
        raise PlotError(f"{path} has no dataset '{name}'")
    return handle[name]


def display(values, unit):
    offset, scale, shown = DISPLAY.get(unit, (0.0, 1.0, unit))
    return (values + offset) * scale, shown


def units(item):
    value = item.attrs.get("units", "")
    return value.decode() if isinstance(value, bytes) else value


def texts(values):
    return [v.decode() if isinstance(v, bytes) else str(v) for v in values]


def save(figure, output):
    if not output.lower().endswith((".png", ".svg")):
        raise PlotError(f"{output}: the output must end in .png or .svg")
    figure.tight_layout()
    figure.savefig(output, dpi=110)
    print(f"wrote {output}")


def fail(error):
    sys.exit(f"tcpmsim-plot: {error}")
