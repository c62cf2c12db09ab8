#!/usr/bin/env python3
"""Compares two sweep files (tcpmsim sweep) dataset by dataset, bit for bit: the summary and
every stored trace. /timing (wall-clock times) and the root attributes are not compared.
Exit status 0 if identical, 1 with the first differences listed otherwise.
Usage: compare_sweeps.py A.h5 B.h5"""
import sys

import h5py
import numpy as np


def datasets(group, prefix=""):
    found = {}
    for name, item in group.items():
        path = f"{prefix}/{name}"
        if path == "/timing":
            continue
        if isinstance(item, h5py.Group):
            found.update(datasets(item, path))
        else:
            found[path] = item[()]
    return found


def same(a, b):
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape or a.dtype.kind != b.dtype.kind:
        return False
    if a.dtype.kind == "f":  # bit for bit, NaN equal to NaN
        return a.tobytes() == b.tobytes()
    return bool(np.all(a == b))


def main():
    with h5py.File(sys.argv[1], "r") as first, h5py.File(sys.argv[2], "r") as second:
        a, b = datasets(first), datasets(second)
    problems = [f"only in {sys.argv[1]}: {p}" for p in sorted(set(a) - set(b))]
    problems += [f"only in {sys.argv[2]}: {p}" for p in sorted(set(b) - set(a))]
    problems += [f"differs: {p}" for p in sorted(set(a) & set(b)) if not same(a[p], b[p])]
    if problems:
        print("\n".join(problems[:20]))
        sys.exit(1)
    print(f"identical: {len(a)} datasets")


if __name__ == "__main__":
    main()
