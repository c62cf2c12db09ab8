#!/usr/bin/python3
"""Mutation check of the test suite (issue 15): does a one-line bug in the physics or the
analyses turn the suite red?

Copies the committed tree (git archive of HEAD) to a scratch directory (rewriting only what
changed since the last use, so its build stays incremental), builds it (Release), then for each mutation in tests/mutants/mutants.yaml: applies it, rebuilds
incrementally, runs ctest, records whether a test failed (killed), none did (survived) or the
mutant did not compile (invalid), and restores the file. A mutant that survives but is marked
`equivalent: REASON` in the list (it changes nothing a test could see) is reported as such and
left out of the kill rate. Prints a table and the kill rate, and
writes them as JSON. The source tree is never touched.

    scripts/mutants.py [--scratch DIR] [--only SUBSTRING]... [--tests REGEX] [--json FILE]

Not part of CI: every mutant rebuilds and reruns the suite, minutes each on 2 cores.
"""
import argparse
import json
import os
import pathlib
import shutil
import subprocess
import sys
import time

import yaml

ROOT = pathlib.Path(__file__).resolve().parent.parent


def run(command, cwd, log):
    with open(log, "a") as out:
        out.write(f"$ {' '.join(command)}\n")
        out.flush()
        return subprocess.run(command, cwd=cwd, stdout=out, stderr=subprocess.STDOUT).returncode


def sync_source(scratch):
    """scratch/src becomes HEAD's tree; only files whose content changed are rewritten (with a
    new modification time), so an earlier build of it stays valid for the rest."""
    source, incoming = scratch / "src", scratch / "incoming"
    shutil.rmtree(incoming, ignore_errors=True)
    incoming.mkdir(parents=True)
    archive = subprocess.run(["git", "archive", "HEAD"], cwd=ROOT, check=True,
                             stdout=subprocess.PIPE).stdout
    subprocess.run(["tar", "-x", "-C", str(incoming)], input=archive, check=True)
    wanted = {p.relative_to(incoming) for p in incoming.rglob("*") if p.is_file()}
    for relative in sorted(wanted):
        target = source / relative
        content = (incoming / relative).read_bytes()
        if not target.is_file() or target.read_bytes() != content:
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_bytes(content)
            shutil.copymode(incoming / relative, target)
    if source.exists():
        for path in [p for p in source.rglob("*") if p.is_file()]:
            if path.relative_to(source) not in wanted:
                path.unlink()
    shutil.rmtree(incoming)
    return source


def prepare(scratch, log):
    source = sync_source(scratch)
    build = scratch / "build"
    if run(["cmake", "-S", str(source), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
            "-DTCPMSIM_BUILD_TESTS=ON"], scratch, log) != 0:
        sys.exit(f"mutants: configuring {build} failed; see {log}")
    if build_targets(build, log) != 0:
        sys.exit(f"mutants: the unmutated tree does not build; see {log}")
    return source, build


def build_targets(build, log):
    return run(["cmake", "--build", str(build), f"-j{os.cpu_count()}", "--target", "tcpmsim",
                "tcpmsim_tests", "tcpmsim_allocation_tests", "record_digest"], build, log)


def test(build, regex, log):
    command = ["ctest", "--test-dir", str(build), f"-j{os.cpu_count()}", "--stop-on-failure"]
    if regex:
        command += ["-R", regex]
    return run(command, build, log)


def mutate(source, mutant):
    path = source / mutant["file"]
    original = path.read_text()
    count = original.count(mutant["find"])
    if count != 1:
        return None, f"'find' occurs {count} times in {mutant['file']}"
    path.write_text(original.replace(mutant["find"], mutant["replace"]))
    return original, ""


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scratch", default="/tmp/tcpmsim-mutants", type=pathlib.Path)
    parser.add_argument("--only", action="append",
                        help="only mutants whose file or reason contains this (repeatable)")
    parser.add_argument("--tests", help="ctest -R regular expression (default: the whole suite)")
    parser.add_argument("--json", type=pathlib.Path, help="write the results here too")
    args = parser.parse_args()
    mutants = yaml.safe_load((ROOT / "tests/mutants/mutants.yaml").read_text())
    if args.only:
        mutants = [m for m in mutants
                   if any(only in m["file"] or only in m["why"] for only in args.only)]
    args.scratch.mkdir(parents=True, exist_ok=True)
    log = args.scratch / "mutants.log"
    source, build = prepare(args.scratch, log)
    if test(build, args.tests, log) != 0:
        sys.exit(f"mutants: the unmutated suite fails; see {log}")
    results = []
    for number, mutant in enumerate(mutants, 1):
        started = time.monotonic()
        original, problem = mutate(source, mutant)
        if original is None:
            outcome = "stale"
        else:
            try:
                if build_targets(build, log) != 0:
                    outcome = "invalid"
                else:
                    outcome = "killed" if test(build, args.tests, log) != 0 else "survived"
                    if outcome == "survived" and mutant.get("equivalent"):
                        outcome = "equivalent"
            finally:
                (source / mutant["file"]).write_text(original)
        seconds = time.monotonic() - started
        results.append({**mutant, "outcome": outcome, "problem": problem, "seconds": seconds})
        print(f"[{number}/{len(mutants)}] {outcome:8s} {seconds:6.0f} s  {mutant['file']}: "
              f"{mutant['why']}", flush=True)
    build_targets(build, log)  # leave the scratch build unmutated
    judged = [r for r in results if r["outcome"] in ("killed", "survived")]
    killed = sum(r["outcome"] == "killed" for r in judged)
    print(f"mutants: {killed} of {len(judged)} killed"
          + (f" ({100.0 * killed / len(judged):.0f} %)" if judged else "")
          + f"; {len(results) - len(judged)} stale or invalid")
    for r in results:
        if r["outcome"] != "killed":
            reason = r.get("equivalent", "") if r["outcome"] == "equivalent" else r["problem"]
            print(f"  {r['outcome']}: {r['file']}: {r['why']} {reason}")
    if args.json:
        args.json.write_text(json.dumps(results, indent=1))
    return 0 if killed == len(judged) else 1


if __name__ == "__main__":
    sys.exit(main())
