#!/usr/bin/python3
"""The hidden-effect matrix of `tcpmsim discover` (issue 12).

For every named effect (and for none), "measured" data are made from the chapter-7 model with
that effect attached, under the chapter-7 protocol (400 s identification, 220 s validation,
16 Hz), read by the bench's instruments (load cell 0.5 mN resolution plus noise, L* jitter and
spikes: configs/discover/ch7_bench.yaml) at several noise levels and seeds. Each seed moves
the base parameters by up to +-20 % and draws the effect's size; the effect's functional form
varies too, so that the library never models the data with its own law exactly. `discover`
then runs with the base model, which lacks the effect. The table gives, per hidden effect, how
often the verdict names it (recovery; for none, how often it names anything: false alarms)
and the median validation gap shrink.

  scripts/discover_matrix.py --build build --out results/discover_matrix            # full
  scripts/discover_matrix.py --noise 2 --seeds 1 --out results/discover_matrix_ci   # reduced
  scripts/discover_matrix.py --resume ...   # go on with an interrupted matrix
"""
import json
import os
import random
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from matrix_runs import (acceptance, declared_families, finished_case, finish,  # noqa: E402
                         keep_case, parse, parser_for, run, run_cases)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BASE = os.path.join(ROOT, "configs/discover/ch7_base.yaml")
PROTOCOL = os.path.join(ROOT, "configs/discover/ch7_protocol.yaml")

# The base model's values (Table 7.2), SI, that each seed moves by up to +-20 %.
BASE_PARAMETERS = {
    "muscle.thermal_force.kappa_P": (7.2e-3, "N/J"),
    "muscle.thermal_force.kappa_c": (131.6e-3, "1/s"),
    "muscle.mechanics.k1": (10.8, "N/m"),
    "muscle.mechanics.k2": (2.7, "N/m"),
    "muscle.mechanics.damping": (4.3, "N*s/m"),
    "muscle.mechanics.force_offset": (106.9e-3, "N"),
}

def effect_forms(name, rng):
    """The hidden effect as `muscle.effects` entries or overrides, in one of its forms; the
    form and the size drawn from `rng`. Returns (form name, overrides)."""
    size = rng.uniform(0.7, 1.3)

    def effects(*entries):
        return ["muscle.effects=[" + ", ".join(entries) + "]"]

    if name == "slow_relaxation":
        forms = [
            ("one branch, tau 300 s", effects(
                f"{{type: maxwell_branch, stiffness: {0.8 * size} N/m, time_constant: 300 s}}")),
            ("two branches, tau 120 s and 900 s", effects(
                f"{{type: maxwell_branch, name: a, stiffness: {0.5 * size} N/m, time_constant: 120 s}}",
                f"{{type: maxwell_branch, name: b, stiffness: {0.5 * size} N/m, time_constant: 900 s}}")),
        ]
    elif name == "hysteresis":
        forms = [
            ("Dahl", effects(f"{{type: hysteresis, stiffness: 50 N/m, force: {6e-3 * size} N}}")),
            ("two Dahl elements (a Prandtl-Ishlinskii-like staircase)", effects(
                f"{{type: hysteresis, name: h1, stiffness: 200 N/m, force: {2.5e-3 * size} N}}",
                f"{{type: hysteresis, name: h2, stiffness: 15 N/m, force: {5e-3 * size} N}}")),
        ]
    elif name == "nonlinear_convection":
        forms = [
            ("free convection, 5/4 law", effects(
                f"{{type: free_convection, conductance: {0.03 * size} W/K, reference_difference: 50 K}}")),
            ("free convection, referred to 20 K", effects(
                f"{{type: free_convection, conductance: {0.01 * size} W/K, reference_difference: 20 K}}")),
        ]
    elif name == "thermal_lag":
        forms = [
            ("wire node, tau_w 1 s", effects(
                f"{{type: thermal_lag, heat_capacity: {0.05 * size} J/K, conductance: 0.05 W/K}}")),
            ("wire node, tau_w 3 s", effects(
                f"{{type: thermal_lag, heat_capacity: {0.15 * size} J/K, conductance: 0.05 W/K}}")),
        ]
    elif name == "nonlinear_stiffness":
        forms = [
            ("soft knee", effects(
                f"{{type: nonlinear_stiffness, stiffness: {4 * size} N/m, knee_deflection: 24 mm, knee_width: 1 mm}}")),
            ("sharp knee", effects(
                f"{{type: nonlinear_stiffness, stiffness: {6 * size} N/m, knee_deflection: 26 mm, knee_width: 0.2 mm}}")),
        ]
    elif name == "temperature_dependent_stiffness":
        forms = [
            ("softening", effects(
                f"{{type: thermal_softening, reference_stiffness: 5 N/m, temperature_coefficient: {-0.01 * size} 1/K, reference_temperature: 23 degC}}")),
        ]
    elif name == "inductance_temperature":
        # The coil law's section whole: a temperature term is assembled only when the scenario
        # states it.
        forms = [("lambda_T (T - T_ref)", [
            "muscle.inductance={quantity: measure, lambda_l: 2.81 mm, lambda_x: 28.8 mm, "
            f"lambda_0: 0.433, lambda_T: {-1.5e-3 * size} 1/K, reference_temperature: 23 degC}}"])]
    elif name == "viscoelastic_relaxation":
        forms = [
            ("a second SLS branch, tau 8 s", effects(
                f"{{type: maxwell_branch, stiffness: {1.5 * size} N/m, time_constant: 8 s}}")),
        ]
    elif name == "ratchet":
        forms = [
            ("ratchet above 33 degC", effects(
                f"{{type: ratchet, rate: {1e-5 * size} N/(K*s), threshold: 33 degC}}")),
            ("ratchet above 38 degC", effects(
                f"{{type: ratchet, rate: {2e-5 * size} N/(K*s), threshold: 38 degC}}")),
        ]
    elif name == "heating_dependent_convection":
        forms = [
            ("boost at once", effects(
                f"{{type: heating_convection, conductance: {0.04 * size} W/K, "
                "reference_power: 3.12 W}")),
            ("boost through a 10 s spin-up", effects(
                f"{{type: heating_convection, conductance: {0.05 * size} W/K, "
                "reference_power: 3.12 W, time_constant: 10 s}")),
        ]
    elif name == "none":
        forms = [("none", [])]
    else:
        sys.exit(f"discover_matrix: no hidden forms of '{name}' (a family discover tries): add "
                 "them to effect_forms")
    return forms[rng.randrange(len(forms))]


def bench_file(directory, noise_mn, seed):
    path = os.path.join(directory, "bench.yaml")
    with open(path, "w", encoding="utf-8") as file:
        file.write(f"""seed: {seed}
channels:
  - {{channel: power, output: drive.power, unit: W}}
  - {{channel: deflection, output: load.deflection, unit: mm}}
  - {{channel: force, output: load.force, unit: mN, resolution: 0.5 mN, noise: {noise_mn} mN}}
  - channel: inductance_measure
    output: muscle.inductance_measure
    unit: "1"
    noise: 0.0005
    spikes: {{probability: 0.005, size: 0.02}}
""")
    return path


def one_case(arguments, inputs, effect, noise_mn, seed):
    name = f"{effect}_{noise_mn}mN_seed{seed}"
    directory = os.path.join(arguments.out, name)
    rng = random.Random(f"{effect} {noise_mn} {seed}")
    truth = [f"{path}={value * rng.uniform(0.8, 1.2):.10g} {unit}"
             for path, (value, unit) in BASE_PARAMETERS.items()]
    form, hidden = effect_forms(effect, rng)
    outputs = "force,inductance_measure" if arguments.inductance else "force"
    # What defines the case: a finished case with the same definition is reused by --resume.
    definition = {"truth": truth, "hidden": hidden, "noise_mN": noise_mn, "seed": seed,
                  "outputs": outputs}
    if arguments.resume:
        result = finished_case(arguments, name, lambda stored: stored == definition)
        if result is not None:
            return result
    if arguments.table_only:
        return None
    os.makedirs(directory, exist_ok=True)
    log = os.path.join(directory, "log.txt")
    open(log, "w", encoding="utf-8").close()
    tool = os.path.join(arguments.build, "tcpmsim")
    data = os.path.join(directory, "measured.csv")
    command = [tool, "measure", BASE, "--set", f"measurement.file={inputs}",
               "--bench", bench_file(directory, noise_mn, seed), "-o", data, "-q"]
    for override in truth + hidden:
        command += ["--set", override]
    if run(command, log) != 0:
        return {"case": name, "effect": effect, "form": form, "error": "measure failed: see " + log}
    command = [tool, "discover", "--model", BASE, "--data", data, "--inputs", "power,deflection",
               "--outputs", outputs, "--validate-from", "400", "--out",
               os.path.join(directory, "discover"), "-q", "-j", str(arguments.threads)]
    if not arguments.plots:
        command.append("--no-plots")
    # 0: an effect named, 10: none, 11: unexplained; anything else failed.
    if run(command, log) not in (0, 10, 11):
        return {"case": name, "effect": effect, "form": form, "error": "discover failed: see " + log}
    with open(os.path.join(directory, "discover", "discovery.json"), encoding="utf-8") as file:
        found = json.load(file)
    result = {"case": name, "effect": effect, "form": form, "noise_mN": noise_mn, "seed": seed,
              "verdict": found["verdict"], "gap_shrink": found["gap_shrink"],
              "gap_closed": found.get("gap_closed"), "member": found.get("member"),
              "seconds": found["seconds"], "definition": definition,
              "ranking": [(c["effect"], c.get("delta_bic")) for c in found["ranking"]]}
    keep_case(arguments, result, found)
    return result


def table(results):
    """Per hidden effect: the verdicts that name it (for none: that name nothing) and the median
    validation gap shrink, overall and per noise level."""
    noises = sorted({r["noise_mN"] for r in results if "noise_mN" in r})
    header = "| hidden effect | forms | recovery | median gap shrink | " + " | ".join(
        f"{n} mN: named, shrink" for n in noises) + " | other verdicts |"
    lines = [header, "|" + "---|" * (5 + len(noises))]

    def summary(cases, effect):
        done = [r for r in cases if "verdict" in r]
        named = [r for r in done if r["verdict"] == effect]
        shrinks = [r["gap_shrink"] for r in named]
        shrink = f"{100 * statistics.median(shrinks):.0f} %" if shrinks and effect != "none" else "-"
        return done, named, shrink

    for effect in dict.fromkeys(r["effect"] for r in results):
        cases = [r for r in results if r["effect"] == effect]
        done, named, shrink = summary(cases, effect)
        if effect == "none":
            rate = f"false alarms {len(done) - len(named)}/{len(done)}"
        else:
            rate = f"{len(named)}/{len(done)} ({100 * len(named) / max(1, len(done)):.0f} %)"
        columns = []
        for noise in noises:
            at = [r for r in cases if r.get("noise_mN") == noise]
            at_done, at_named, at_shrink = summary(at, effect)
            columns.append(f"{len(at_named)}/{len(at_done)}, {at_shrink}")
        forms = "; ".join(sorted({r["form"] for r in cases}))
        others = sorted({r["verdict"] for r in done if r["verdict"] != effect})
        failed = len(cases) - len(done)
        lines.append(f"| {effect} | {forms} | {rate} | {shrink} | " + " | ".join(columns) +
                     f" | {', '.join(others) or '-'}{f' ({failed} failed)' if failed else ''} |")
    return "\n".join(lines)


def main():
    parser = parser_for(__doc__, ROOT, "results/discover_matrix", "hidden effects")
    parser.add_argument("--check", action="store_true",
                        help="exit 1 unless every case's verdict is its hidden effect (none: none)")
    arguments = parse(parser)
    if arguments.effects is None:
        families = declared_families(os.path.join(arguments.build, "tcpmsim"))
        arguments.effects = ",".join(["none"] + families)
    os.makedirs(arguments.out, exist_ok=True)
    inputs = os.path.join(arguments.out, "protocol.h5")
    if run([os.path.join(arguments.build, "tcpmsim"), "run", PROTOCOL, "-o", inputs, "-q"],
           os.path.join(arguments.out, "protocol.log")) != 0:
        sys.exit("discover_matrix: the protocol run failed")
    cases = [(effect, float(noise) if "." in noise else int(noise), seed)
             for effect in arguments.effects.split(",") for noise in arguments.noise.split(",")
             for seed in arguments.seeds]
    results = run_cases([(arguments, inputs, *case) for case in cases], one_case,
                        arguments.cases_at_once,
                        ("case", "form", "verdict", "gap_shrink", "gap_closed", "seconds", "error"))
    text = table(results) + "\n\n" + acceptance(arguments.out, results, lambda r: r["effect"],
                                                 lambda r: r.get("gap_closed"))
    finish("discover_matrix", arguments.out, results, text, lambda r: r["effect"],
           arguments.check)

if __name__ == "__main__":
    main()
