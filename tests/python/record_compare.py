"""Compares two tcpmsim records dataset by dataset and attribute by attribute, bit for bit."""

import h5py
import numpy as np


def record_items(path):
    """{name: value} for every dataset (its bytes, dtype and shape) and every attribute
    ("name@attribute") of the file at `path`."""
    items = {}
    with h5py.File(path, "r") as record:
        def visit(name, obj):
            if isinstance(obj, h5py.Dataset):
                data = obj[()]
                items[name] = (str(obj.dtype), np.shape(data), np.asarray(data).tobytes())
            for attribute, value in obj.attrs.items():
                items[f"{name}@{attribute}"] = repr(value)
        for attribute, value in record.attrs.items():
            items[f"/@{attribute}"] = repr(value)
        record.visititems(visit)
    return items


def differences(first, second, ignore=()):
    """The names whose values differ, or that only one record has."""
    a, b = record_items(first), record_items(second)
    return sorted(name for name in set(a) | set(b)
                  if name not in ignore and a.get(name) != b.get(name))
