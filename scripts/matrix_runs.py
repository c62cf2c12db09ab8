"""What the two hidden-effect matrices of `tcpmsim discover` share (scripts/discover_matrix.py,
scripts/independent_matrix.py): a command run into a case's log, the cases run a few at a time
with a line printed as each ends, and the results written and checked."""
import argparse
import concurrent.futures
import json
import os
import statistics
import subprocess
import sys


def run(command, log):
    """Runs `command` with its output appended to `log`; its exit code."""
    with open(log, "a", encoding="utf-8") as file:
        file.write("$ " + " ".join(command) + "\n")
        file.flush()
        return subprocess.run(command, stdout=file, stderr=subprocess.STDOUT, check=False).returncode


def declared_families(tool):
    """The effect families discover tries, in its order, as the effect kinds declare them with
    their registration (`tcpmsim kinds --discover-families`)."""
    if not os.access(tool, os.X_OK):
        sys.exit(f"no program {tool} (build tcpmsim first, or --build)")
    listed = subprocess.run([tool, "kinds", "--discover-families"], capture_output=True, text=True,
                            check=True)
    return [line.strip() for line in listed.stdout.splitlines() if line.strip()]


def run_cases(cases, one_case, at_once, printed):
    """`one_case(*case)` for every case, `at_once` at a time, in order; prints the keys
    `printed` of each result as JSON as it ends. A case whose result is None (not run with
    --table-only) is left out."""
    results = []
    with concurrent.futures.ThreadPoolExecutor(at_once) as pool:
        for result in pool.map(lambda case: one_case(*case), cases):
            if result is None:
                continue
            print(json.dumps({k: result.get(k) for k in printed}), flush=True)
            results.append(result)
    return results


def misses_by_twice_the_floor(found, factor=2.0):
    """Whether discover's report (discovery.json, loaded) has the base model miss some output by
    more than `factor` times the noise floor it reports."""
    rmse = found.get("baseline", {}).get("validation_rmse", {})
    return any(rmse.get(output, 0.0) > factor * floor
               for output, floor in found.get("noise_floor", {}).items() if floor)


def base_far_above_floor(out, result):
    """Whether a case's base model misses some output by more than twice the noise floor: as
    its record says, else as its discovery.json in `out` says."""
    if "base_above_twice_floor" in result:
        return result["base_above_twice_floor"]
    path = os.path.join(out, result["case"], "discover", "discovery.json")
    if not os.path.exists(path):
        return False
    with open(path, encoding="utf-8") as file:
        return misses_by_twice_the_floor(json.load(file))


def tool_version(tool):
    """What `tcpmsim --version` prints: the build a case's verdict came from."""
    return subprocess.run([tool, "--version"], capture_output=True, text=True,
                          check=False).stdout.strip()


def finished_case(arguments, name, same_definition):
    """The finished case `name` whose definition passes `same_definition`: from its directory
    in --out, else from --record (the committed records a matrix is resumed from on a new
    machine); None if neither holds it."""
    paths = [os.path.join(arguments.out, name, "case.json")]
    if arguments.record:
        paths.append(os.path.join(arguments.record, name + ".json"))
    for path in paths:
        if not os.path.exists(path):
            continue
        with open(path, encoding="utf-8") as file:
            result = json.load(file)
        if "verdict" in result and same_definition(result.get("definition")):
            return result
    return None


def keep_case(arguments, result, found):
    """Completes a finished case's result with what its acceptance needs from discover's report
    (`found`) and the build, and writes it to its case.json and, with --record, as a record."""
    result["base_above_twice_floor"] = misses_by_twice_the_floor(found)
    result["build"] = tool_version(os.path.join(arguments.build, "tcpmsim"))
    paths = [os.path.join(arguments.out, result["case"], "case.json")]
    if arguments.record:
        os.makedirs(arguments.record, exist_ok=True)
        paths.append(os.path.join(arguments.record, result["case"] + ".json"))
    for path in paths:
        with open(path, "w", encoding="utf-8") as file:
            json.dump(result, file, indent=1)


def acceptance(out, results, expected, share):
    """Issue 28's criteria over the finished cases: effects named right, false alarms on null
    data, `unexplained` verdicts, `none` where the base misses by more than twice the floor,
    and the median share of the above-noise gap closed (`share(result)`, None where no gap)."""
    done = [r for r in results if r.get("verdict")]
    effects = [r for r in done if r["effect"] != "none"]
    nulls = [r for r in done if r["effect"] == "none"]
    right = sum(r["verdict"] == expected(r) for r in effects)
    alarms = sum(r["verdict"] != "none" for r in nulls)
    unexplained = sum(r["verdict"] == "unexplained" for r in done)
    far = [r["case"] for r in done if r["verdict"] == "none" and base_far_above_floor(out, r)]
    shares = [v for v in (share(r) for r in effects) if v is not None]
    median = f"{statistics.median(shares):.2f}" if shares else "-"
    return (f"Acceptance over {len(done)} cases: {right}/{len(effects)} effects named right "
            f"({100 * right / max(1, len(effects)):.1f} %), false alarms {alarms}/{len(nulls)}, "
            f"`unexplained` {unexplained}, `none` with the base above twice the floor "
            f"{len(far)}{' (' + ', '.join(far) + ')' if far else ''}, median share of the "
            f"above-noise gap closed {median} (over {len(shares)} cases with a gap).")


def finish(name, out, results, text, expected, check):
    """Writes results.json and recovery.md (`text`) into `out` and prints the table; exits
    non-zero when a case failed, or with `check` when a verdict is not `expected(result)`."""
    with open(os.path.join(out, "results.json"), "w", encoding="utf-8") as file:
        json.dump(results, file, indent=1)
    with open(os.path.join(out, "recovery.md"), "w", encoding="utf-8") as file:
        file.write(text + "\n")
    print(text)
    if any("error" in r and r["error"] for r in results):
        sys.exit(f"{name}: some cases failed (see their log.txt)")
    wrong = [r["case"] for r in results if r["verdict"] != expected(r)]
    if check and wrong:
        sys.exit(f"{name}: wrong verdicts: " + ", ".join(wrong))


def seed_list(text):
    """The seeds `--seeds` names: "5" is 1 to 5; "2-3,5" is 2, 3 and 5."""
    try:
        if text.isdigit():
            return list(range(1, int(text) + 1))
        seeds = []
        for part in text.split(","):
            first, _, last = part.partition("-")
            seeds += list(range(int(first), int(last or first) + 1))
        return seeds
    except ValueError as error:
        raise argparse.ArgumentTypeError(f"not a seed count or list: {text}") from error


def parse(parser):
    """The arguments, with --table-only implying --resume (it reads what --resume reuses)."""
    arguments = parser.parse_args()
    arguments.resume = arguments.resume or arguments.table_only
    return arguments


def parser_for(doc, root, out, effects_help):
    """The command line both matrices take; each adds its own options."""
    parser = argparse.ArgumentParser(description=doc,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.path.join(root, "build"))
    parser.add_argument("--out", default=os.path.join(root, out))
    parser.add_argument("--noise", default="1,2,4", help="load-cell noise levels [mN]")
    parser.add_argument("--seeds", type=seed_list, default=seed_list("5"),
                        help="N for seeds 1 to N, or a list and ranges such as 2-3 or 2,4")
    parser.add_argument("--effects", default=None,
                        help=effects_help + "; default: none and every family discover tries "
                        "(tcpmsim kinds --discover-families)")
    parser.add_argument("--cases-at-once", type=int, default=1, help="discover runs in parallel")
    parser.add_argument("--threads", type=int, default=2, help="threads of each discover run")
    parser.add_argument("--plots", action="store_true", help="draw each case's pictures")
    parser.add_argument("--resume", action="store_true",
                        help="reuse the cases of --out already finished with the same definition "
                        "(a long matrix can run in pieces)")
    parser.add_argument("--record", default=None,
                        help="also keep each finished case as DIR/CASE.json, and resume from "
                        "there (records small enough to commit, so that a matrix of many "
                        "hours runs in pieces on different machines)")
    parser.add_argument("--table-only", action="store_true",
                        help="run nothing: the table of the cases of --out already finished with "
                        "the same definition (implies --resume)")
    parser.add_argument("--no-inductance", dest="inductance", action="store_false",
                        help="compare the force only (no L* output, no inductance candidate)")
    return parser
