#!/usr/bin/python3
"""The hidden-effect matrix of `tcpmsim discover` on independently generated data.

scripts/discover_matrix.py makes its "measured" data with tcpmsim's own components, so an effect
hidden there follows the very law discover's candidate attaches. Here the data come from
scripts/independent_effects.py: the chapter-7 protocol, the truth model of section 7.2 and every
effect written in Python (numpy, SciPy) with forms of their own (a Prandtl-Ishlinskii staircase,
Bouc-Wen, Prony series, power-law cooling, radiation, a transport delay, ...), including the
two the real measurement showed (a ratchet, a heat-transfer coefficient that rises with the
heating). An effect discover offers no candidate for has `unexplained` as its right verdict. For every case it writes DIR/<case>/measured.csv and case.json, runs

  tcpmsim discover --model configs/discover/ch7_base.yaml --data measured.csv
      --inputs power,deflection --outputs force,inductance_measure --validate-from 400 ...

and tabulates per hidden effect: recovery (the verdict names it; for none: false alarms), how
many verdicts are `unexplained` and `none`, and the median share of the above-noise gap closed
on the force, (rmse_base - rmse_aug) / (rmse_base - floor), the floor being discovery.json's
`noise_floor` where it has one and the case's true noise (normal noise and 0.5 mN rounding)
otherwise.

  scripts/independent_matrix.py --out results/independent_matrix                    # full
  scripts/independent_matrix.py --effects none,hysteresis --noise 2 --seeds 1 --threads 1
  scripts/independent_matrix.py --effects hysteresis:prandtl_ishlinskii ...          # one form
  scripts/independent_matrix.py --resume ...   # go on with an interrupted matrix
"""
import json
import os
import statistics
import sys
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import independent_effects as ie  # noqa: E402
from matrix_runs import (acceptance, declared_families, finished_case, finish,  # noqa: E402
                         keep_case, parse, parser_for, run, run_cases)

# --cases-at-once runs cases on threads; their data are generated one case at a time.
GENERATOR_LOCK = threading.Lock()

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BASE = os.path.join(ROOT, "configs/discover/ch7_base.yaml")
def parse_effect(entry):
    """'name' or 'name:form'."""
    name, _, form = entry.partition(":")
    return name, (form or None)


def case_name(effect, form, noise_mn, seed):
    return f"{effect}{'-' + form if form else ''}_{noise_mn}mN_seed{seed}"


def expected_verdict(effect, found, families):
    """The right verdict: the effect when discover has a family for it, `unexplained` when it
    has none, `none` for data without an effect. The families are those the run ranked (a family
    the base model cannot take is skipped), else those the kinds declare."""
    if effect == "none":
        return "none"
    offered = {c["effect"] for c in (found or {}).get("ranking", [])}
    return effect if effect in (offered or families) else "unexplained"


def floor_of(found, channel, true_floor):
    """The output's noise floor [SI] and where it came from: discovery.json's `noise_floor`
    (per output, or one number for the force) when present, else the case's true noise."""
    given = found.get("noise_floor")
    if isinstance(given, dict) and isinstance(given.get(channel), (int, float)):
        return given[channel], "discovery.json"
    if isinstance(given, (int, float)) and channel == "force":
        return given, "discovery.json"
    return true_floor, "true noise"


def gap_closed(found, channel, true_floor):
    """(rmse_base - rmse_aug) / (rmse_base - floor) on the validation window, or None when the
    base model leaves no gap above the floor (less than 5 % of it)."""
    try:
        base = found["baseline"]["validation_rmse"][channel]
        augmented = found["augmented"]["validation_rmse"][channel]
    except (KeyError, TypeError):
        return None, None
    floor, source = floor_of(found, channel, true_floor)
    if base is None or augmented is None or base - floor <= 0.05 * floor:
        return None, source
    return (base - augmented) / (base - floor), source


def comparable(definition):
    """A definition as --resume compares it: everything but the equation's wording."""
    if not definition or not definition.get("hidden"):
        return definition
    return {**definition, "hidden": {k: v for k, v in definition["hidden"].items()
                                     if k != "equation"}}


def one_case(arguments, effect, form, noise_mn, seed):
    name = case_name(effect, form, noise_mn, seed)
    directory = os.path.join(arguments.out, name)
    outputs = "force,inductance_measure" if arguments.inductance else "force"
    definition, _, _ = ie.define_case(effect, seed, noise_mn, form=form,
                                      controls=arguments.controls, style=arguments.protocol)
    definition["outputs"] = outputs
    finished = os.path.join(directory, "case.json")
    if arguments.resume:
        wanted = comparable(json.loads(json.dumps(definition)))
        result = finished_case(arguments, name, lambda stored: comparable(stored) == wanted)
        if result is not None:
            return result
    if arguments.table_only:
        return None
    os.makedirs(directory, exist_ok=True)
    start = time.time()
    with GENERATOR_LOCK:  # SciPy's LSODA solves one problem at a time in a process
        case = ie.make_case(effect, seed, noise_mn, form=form, controls=arguments.controls,
                            style=arguments.protocol)
        data = os.path.join(directory, "measured.csv")
        ie.write_case(case, data, truth_path=os.path.join(directory, "truth.npz"))
        size = ie.effect_size(case)
    result = {"case": name, "effect": effect, "form": definition["form"], "noise_mN": noise_mn,
              "seed": seed, "definition": definition, "effect_size": size,
              "generate_seconds": time.time() - start}
    with open(finished, "w", encoding="utf-8") as file:
        json.dump(result, file, indent=1)

    log = os.path.join(directory, "log.txt")
    open(log, "w", encoding="utf-8").close()
    out = os.path.join(directory, "discover")
    report = os.path.join(out, "discovery.json")
    if os.path.exists(report):
        os.remove(report)   # a stale report must not pass for this run's
    command = [os.path.join(arguments.build, "tcpmsim"), "discover", "--model", BASE,
               "--data", data, "--inputs", "power,deflection", "--outputs", outputs,
               "--validate-from", "400", "--out", out, "-q", "-j", str(arguments.threads)]
    if not arguments.plots:
        command.append("--no-plots")
    code = run(command, log)
    # A verdict may come with its own exit code (0 for an effect named, others for none or
    # unexplained): what counts is that discover wrote its report.
    if not os.path.exists(report):
        result["error"] = f"discover exited {code} without discovery.json: see {log}"
        return result
    with open(report, encoding="utf-8") as file:
        found = json.load(file)
    true_floor = ie.force_noise_floor(noise_mn * 1e-3)
    shrink_force, source = gap_closed(found, "force", true_floor)
    shrink_coil, coil_source = (gap_closed(found, "inductance_measure", ie.COIL_NOISE)
                                if arguments.inductance else (None, None))
    result.update({
        "verdict": found["verdict"], "expected": expected_verdict(effect, found, arguments.families),
        "verdict_kind": found.get("verdict_kind"), "exit_code": code,
        "gap_shrink": found.get("gap_shrink"),
        "noise_floor_force_mN": (1e3 * floor_of(found, "force", true_floor)[0]),
        "gap_closed_force": shrink_force, "floor_source": source,
        "gap_closed_inductance": shrink_coil, "floor_source_inductance": coil_source,
        "rmse_force_mN": {k: 1e3 * found[k]["validation_rmse"]["force"]
                          for k in ("baseline", "augmented")
                          if found.get(k, {}).get("validation_rmse", {}).get("force") is not None},
        "true_floor_force_mN": 1e3 * true_floor,
        "seconds": found.get("seconds"),
        "ranking": [(c["effect"], c.get("delta_bic"), c.get("signature_z"), c.get("significant"))
                    for c in found.get("ranking", [])]})
    keep_case(arguments, result, found)
    return result


def closed_to_true_floor(result):
    """The force's gap closed against the case's true noise floor, whatever discover estimated."""
    rmse, floor = result.get("rmse_force_mN", {}), result.get("true_floor_force_mN")
    if "baseline" not in rmse or "augmented" not in rmse or floor is None:
        return None
    base, augmented = rmse["baseline"], rmse["augmented"]
    return None if base - floor <= 0.05 * floor else (base - augmented) / (base - floor)


def percent(values):
    values = [v for v in values if v is not None]
    return f"{100 * statistics.median(values):.0f} %" if values else "-"


def table(results):
    """Per hidden effect: the right verdicts (for none: the false alarms), the `unexplained` and
    `none` verdicts, and the median share of the force's above-noise gap closed (against the
    floor discover reports where it does, and against the true floor), overall and per noise
    level. A case whose base model leaves no gap above the floor has no share."""
    sources = {r.get("floor_source") for r in results if r.get("floor_source")}
    floor = ("true noise" if sources == {"true noise"} else "discovery.json noise_floor"
             if sources == {"discovery.json"} else "noise_floor where given, else true noise")
    noises = sorted({r["noise_mN"] for r in results})
    header = (f"| hidden effect | forms | right verdict | recovery | unexplained | none | "
              f"median gap closed, force (floor: {floor}) | median gap closed, force (true floor) | " +
              " | ".join(f"{n} mN: right, closed" for n in noises) + " | other verdicts |")
    lines = [header, "|" + "---|" * (9 + len(noises))]
    for effect in dict.fromkeys(r["effect"] for r in results):
        cases = [r for r in results if r["effect"] == effect]
        done = [r for r in cases if "verdict" in r]
        right = [r for r in done if r["verdict"] == r["expected"]]
        expected = sorted({r["expected"] for r in done}) or ["?"]
        if effect == "none":
            rate = f"false alarms {len(done) - len(right)}/{len(done)}"
        else:
            rate = f"{len(right)}/{len(done)} ({100 * len(right) / max(1, len(done)):.0f} %)"
        closed = percent([r.get("gap_closed_force") for r in done])
        if effect == "inductance_temperature":
            closed += f" (L*: {percent([r.get('gap_closed_inductance') for r in done])})"
        columns = []
        for noise in noises:
            at = [r for r in done if r["noise_mN"] == noise]
            columns.append(f"{sum(r['verdict'] == r['expected'] for r in at)}/{len(at)}, "
                           f"{percent([r.get('gap_closed_force') for r in at])}")
        forms = "; ".join(sorted({r["form"] for r in cases}))
        others = sorted({r["verdict"] for r in done if r["verdict"] != r["expected"]})
        failed = len(cases) - len(done)
        lines.append(
            f"| {effect} | {forms} | {', '.join(expected)} | {rate} | "
            f"{sum(r['verdict'] == 'unexplained' for r in done)} | "
            f"{sum(r['verdict'] == 'none' for r in done)} | {closed} | "
            f"{percent([closed_to_true_floor(r) for r in done])} | " + " | ".join(columns) +
            f" | {', '.join(others) or '-'}{f' ({failed} failed)' if failed else ''} |")
    return "\n".join(lines)


def main():
    parser = parser_for(__doc__, ROOT, "results/independent_matrix",
                        "hidden effects, each NAME or NAME:FORM (scripts/independent_effects.py "
                        "--list)")
    parser.add_argument("--controls", action="store_true",
                        help="draw the forms that are tcpmsim's own laws too")
    parser.add_argument("--protocol", choices=("brief", "thesis"), default="brief",
                        help="log-spaced multisines and uniform-level steps (brief), or the "
                        "thesis' equally spaced frequencies and bounded increments (thesis)")
    parser.add_argument("--check", action="store_true",
                        help="exit 1 unless every verdict is the right one (the hidden effect; "
                        "unexplained for one without a candidate; none for none)")
    arguments = parse(parser)
    families = declared_families(os.path.join(arguments.build, "tcpmsim"))
    arguments.families = set(families)
    for family in families:
        if family not in ie.FORMS:
            print(f"independent_matrix: note: discover tries {family}, which "
                  "scripts/independent_effects.py cannot hide yet", file=sys.stderr)
    if arguments.effects is None:
        arguments.effects = ",".join(["none"] + [name for name in ie.FORMS if name != "none"])
    for entry in arguments.effects.split(","):
        effect, form = parse_effect(entry)
        if effect not in ie.FORMS:
            sys.exit(f"independent_matrix: unknown effect '{effect}'; one of {', '.join(ie.FORMS)}")
        if form and form not in {f.form for f in ie.FORMS[effect]}:
            sys.exit(f"independent_matrix: effect '{effect}' has no form '{form}'; its forms: "
                     + ", ".join(f.form for f in ie.FORMS[effect]))
    os.makedirs(arguments.out, exist_ok=True)
    cases = [(*parse_effect(entry), float(noise) if "." in noise else int(noise), seed)
             for entry in arguments.effects.split(",") for noise in arguments.noise.split(",")
             for seed in arguments.seeds]
    results = run_cases([(arguments, *case) for case in cases], one_case, arguments.cases_at_once,
                        ("case", "form", "verdict", "expected", "gap_shrink", "gap_closed_force",
                         "seconds", "error"))
    text = table(results) + "\n\n" + acceptance(
        arguments.out, results, lambda r: r["expected"],
        lambda r: (r.get("gap_closed_force") if r.get("gap_closed_force") is not None
                   else r.get("gap_closed_inductance")))
    finish("independent_matrix", arguments.out, results, text, lambda r: r["expected"],
           arguments.check)

if __name__ == "__main__":
    main()
