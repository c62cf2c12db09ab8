"""Checks that tcpmsim files carry their provenance and units (issue 14): the root attributes
tcpmsim_version, git_commit and command_line, the configs they read with their seeds (a record:
config and seed; another file: configs and seeds, when it read any), and a `units` attribute on
every numeric dataset, those under /inputs included.

Usage: check_provenance.py FILE... ; prints one line per problem and exits 1 if there is any.
Files that are not HDF5 are passed over."""
import sys

import h5py
import numpy as np


def problems(path):
    found = []
    with h5py.File(path, "r") as file:
        for attribute in ("tcpmsim_version", "git_commit", "command_line"):
            if not str(file.attrs.get(attribute, "")):
                found.append(f"{path}: no {attribute}")
        is_record = "time" in file and "config" in file.attrs
        if is_record and "seed" not in file.attrs:
            found.append(f"{path}: a record without its seed")
        if not is_record and "configs" in file.attrs:
            if len(file.attrs["configs"]) != len(file.attrs["seeds"]):
                found.append(f"{path}: configs and seeds differ in number")

        def visit(name, item):
            if isinstance(item, h5py.Dataset) and np.issubdtype(item.dtype, np.number):
                if "units" not in item.attrs:
                    found.append(f"{path}: /{name} has no units")
        file.visititems(visit)
    return found


def main():
    # Files that are not HDF5 at all (inputs the tests planted to be refused) are not tcpmsim's.
    files = [path for path in sys.argv[1:] if h5py.is_hdf5(path)]
    found = [problem for path in files for problem in problems(path)]
    for problem in found:
        print(problem)
    print(f"checked {len(files)} file(s): {len(found)} problem(s)")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
