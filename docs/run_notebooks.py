#!/usr/bin/python3
"""Executes the documentation's notebooks, so that the site shows real output (issue 30).

    docs/run_notebooks.py [--build BUILD] [--out DIR | --site DIR] [--timeout S] [NOTEBOOK ...]

The notebooks in docs/notebooks/ are stored without outputs; this script is the only thing
that runs them. Default notebooks: every docs/notebooks/*.ipynb. Each runs in a fresh python3
kernel (ipykernel's kernel spec, /usr/bin/python3) through nbclient, with

- the source tree's root as the working directory, so that `configs/...` resolves; the
  notebooks write under results/notebooks/;
- BUILD and tools/ first on PATH (`tcpmsim` and `tcpmsim-plot` are the ones just built) and
  BUILD/python and tools/ on PYTHONPATH (`import tcpmsim`); MPLBACKEND unset, so that figures
  are drawn inline into the notebook;
- a time limit per cell (--timeout, default 120 s).

The executed notebooks are written to --out (default BUILD/docs-notebooks/). With --site DIR,
the whole docs/ tree is first copied to DIR (replacing DIR) and the executed notebooks are
written over the copies in DIR/notebooks/; Sphinx then builds the site from DIR. docs/conf.py
has nbsphinx_execute = "never": nbsphinx renders a notebook as stored, so building from docs/
itself would show the notebooks without output. CI's docs stage:

    /usr/bin/python3 docs/run_notebooks.py --build build --site build/docs-src
    /usr/bin/python3 -m sphinx -W --keep-going -b html build/docs-src build/docs

A notebook fails the script (exit status 1) if a cell raises, if a cell runs past the time
limit, or if the stored notebook holds outputs (clear them before committing: outputs belong
to the executed copy only). Each notebook's wall time is printed; over --budget seconds
(default 40) it is reported as too slow, but does not fail."""

import argparse
import os
import re
import shutil
import sys
import time
from pathlib import Path

import nbformat
from nbclient import NotebookClient
from nbclient.exceptions import CellExecutionError, CellTimeoutError

SOURCE = Path(__file__).resolve().parent.parent
DOCS = SOURCE / "docs"


def shown(path):
    return path.relative_to(SOURCE) if SOURCE in path.parents else path


def stored_outputs(notebook):
    """The indices of the code cells that hold outputs or an execution count."""
    return [index for index, cell in enumerate(notebook.cells)
            if cell.cell_type == "code" and (cell.get("outputs") or cell.get("execution_count"))]


def environment(build):
    env = dict(os.environ)
    env["PATH"] = f"{build}:{SOURCE / 'tools'}:{env.get('PATH', '')}"
    env["PYTHONPATH"] = os.pathsep.join(
        [str(build / "python"), str(SOURCE / "tools")] +
        ([env["PYTHONPATH"]] if env.get("PYTHONPATH") else []))
    env["TCPMSIM_PLOT_TOOL"] = str(SOURCE / "tools" / "tcpmsim-plot")
    env.pop("MPLBACKEND", None)  # ipykernel then draws figures inline
    env["PYDEVD_DISABLE_FILE_VALIDATION"] = "1"  # no debugger warning about frozen modules
    return env


def execute(path, out, timeout):
    """Runs one notebook; returns (seconds, problem or None)."""
    notebook = nbformat.read(path, as_version=4)
    dirty = stored_outputs(notebook)
    if dirty:
        return 0.0, (f"the stored notebook holds outputs (code cells {dirty}); clear them "
                     f"(Jupyter's Clear All Outputs, or jupyter nbconvert --clear-output "
                     f"--inplace {path}) and save it again")
    client = NotebookClient(notebook, timeout=timeout, kernel_name="python3",
                            resources={"metadata": {"path": str(SOURCE)}})
    started = time.monotonic()
    try:
        client.execute()
    except CellTimeoutError as error:
        return time.monotonic() - started, f"a cell ran longer than {timeout} s: {error}"
    except CellExecutionError as error:  # without the terminal colours of IPython's traceback
        return time.monotonic() - started, re.sub(r"\x1b\[[0-9;]*m", "", str(error))
    seconds = time.monotonic() - started
    out.mkdir(parents=True, exist_ok=True)
    nbformat.write(notebook, out / path.name)
    return seconds, None


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("notebooks", nargs="*", type=Path)
    parser.add_argument("--build", type=Path, default=SOURCE / "build",
                        help="the build tree: its tcpmsim and python/ are used (default: build)")
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--out", type=Path, help="where the executed notebooks go "
                       "(default: BUILD/docs-notebooks)")
    where.add_argument("--site", type=Path, help="copy docs/ here and put the executed notebooks "
                       "into its notebooks/: the tree Sphinx builds")
    parser.add_argument("--timeout", type=int, default=120, help="seconds per cell (default 120)")
    parser.add_argument("--budget", type=float, default=40.0,
                        help="seconds a notebook should take at most; reported, not enforced")
    args = parser.parse_args()

    build = args.build.resolve()
    if not (build / "tcpmsim").is_file() or not (build / "python" / "tcpmsim").is_dir():
        sys.exit(f"run_notebooks: {build} holds no built tcpmsim and python/tcpmsim "
                 "(build the targets tcpmsim and tcpmsim_python, or pass --build)")
    notebooks = [p.resolve() for p in args.notebooks] or sorted((DOCS / "notebooks").glob("*.ipynb"))
    if not notebooks:
        sys.exit("run_notebooks: no notebooks in docs/notebooks/")

    if args.site:
        site = args.site.resolve()
        if site == DOCS or DOCS in site.parents or site in DOCS.parents:
            sys.exit(f"run_notebooks: --site {site} must lie outside docs/ and not contain it")
        shutil.rmtree(site, ignore_errors=True)
        shutil.copytree(DOCS, site, ignore=shutil.ignore_patterns(
            "_build", ".ipynb_checkpoints", "__pycache__"))
        out = site / "notebooks"
    else:
        out = (args.out or build / "docs-notebooks").resolve()

    os.environ.clear()
    os.environ.update(environment(build))
    (SOURCE / "results" / "notebooks").mkdir(parents=True, exist_ok=True)

    failures, slow = [], []
    for path in notebooks:
        print(f"notebooks: {shown(path)} ...", flush=True)
        seconds, problem = execute(path, out, args.timeout)
        if problem:
            failures.append((path, problem))
            print(f"notebooks: FAILED {path.name} after {seconds:.1f} s", flush=True)
            continue
        print(f"notebooks: {path.name} ran in {seconds:.1f} s -> {out / path.name}", flush=True)
        if seconds > args.budget:
            slow.append(f"{path.name} ({seconds:.1f} s)")
    if slow:
        print(f"notebooks: slower than {args.budget:g} s: {', '.join(slow)}")
    for path, problem in failures:
        print(f"notebooks: FAILED {shown(path)}:\n{problem}", file=sys.stderr)
    print(f"notebooks: {len(notebooks) - len(failures)} of {len(notebooks)} executed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
