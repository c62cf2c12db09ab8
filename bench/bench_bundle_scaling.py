#!/usr/bin/env python3
"""Scaling of a bundle with its size (issue 10): time per simulated second and peak memory for
n = 1, 10, 100 and 1000 muscles, each on its own averaged Muscle Drive (bench/bundle_scaling.yaml),
with GMRES preconditioned within members (KLU on each member's block), KLU on the whole sparse
matrix and the dense solver, and the growth exponents fitted from n = 10 to 1000.

Every case runs in its own process (bench_integration: the integration alone, timed in-process;
the minimum of the repeats) so that its peak resident memory is its own (wait4). Both solvers use
warm restarts, so the comparison is of the linear algebra alone. The dense solver factors a
2n x 2n matrix at every setup, so its larger cases simulate a shorter time; the rate is per
simulated second either way. Outputs are kept every 10 s only, so that the peak memory is the
model's and the solver's rather than the samples'. No assertions: the figures are printed for
the README."""
import math
import os
import subprocess
import sys

SIZES = (1, 10, 100, 1000)
# Simulated seconds per case: the whole scenario (100 s), but for the dense solver's large cases,
# whose rate comes from the first 10 s or 50 ms (its start, with the first Jacobian and factors).
DENSE_DURATION = {1: 100, 10: 100, 100: 10, 1000: 0.05}
# "uncoupled": KLU on the bundle without contact conduction (its Jacobian block-diagonal), to
# separate the 2-D thermal network's fill from everything else that grows with n.
NO_CONTACT = "bundle.thermal={shielding: 0.6}"
# The minimum of several repeats: the small cases take milliseconds, and this VM's timings of
# them vary by half.
REPEATS = {1: 9, 10: 9, 100: 5, 1000: 3}


def run_case(bench, config, solver, n):
    duration = DENSE_DURATION[n] if solver == "dense" else 100
    repeats = 1 if solver == "dense" and n == 1000 else REPEATS[n]
    linear_solver = {"dense": "dense", "gmres": "gmres"}.get(solver, "klu")
    command = [bench, config, str(repeats), f"bundle.count={n}",
               f"solver.linear_solver={linear_solver}", "solver.restart=warm",
               f"scenario.duration={duration} s", "output.rate=0.1 Hz"]
    if solver == "uncoupled":
        command.append(NO_CONTACT)
    process = subprocess.Popen(command, stdout=subprocess.PIPE, text=True)
    output = process.stdout.read()
    _, status, usage = os.wait4(process.pid, 0)
    if status != 0:
        sys.exit(f"{' '.join(command)} failed (status {status})")
    fields = dict(item.split("=") for item in output.split())
    return {"per_second": float(fields["min_seconds"]) / duration,
            "states": int(fields["states"]),
            "jacobians": int(fields["jacobians"]),
            "peak_mb": usage.ru_maxrss / 1024.0}


def slope(xs, ys):
    """Least-squares slope of log y against log x."""
    lx = [math.log(x) for x in xs]
    ly = [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sum((a - mx) ** 2 for a in lx)


def main():
    build = sys.argv[1] if len(sys.argv) > 1 else "build"
    config = sys.argv[2] if len(sys.argv) > 2 else "bench/bundle_scaling.yaml"
    bench = os.path.join(build, "bench", "bench_integration")
    solvers = ("gmres", "klu", "uncoupled", "dense")
    results = {solver: {n: run_case(bench, config, solver, n) for n in SIZES} for solver in solvers}
    print("| muscles | states | GMRES: s per simulated s | KLU | dense | dense / GMRES "
          "| GMRES peak memory (MB) | KLU peak memory (MB) | KLU without contact conduction |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for n in SIZES:
        gmres, klu, dense = results["gmres"][n], results["klu"][n], results["dense"][n]
        print(f"| {n} | {klu['states']} | {gmres['per_second']:.3g} | {klu['per_second']:.3g} "
              f"| {dense['per_second']:.3g} | {dense['per_second'] / gmres['per_second']:.3g} "
              f"| {gmres['peak_mb']:.1f} | {klu['peak_mb']:.1f} "
              f"| {results['uncoupled'][n]['per_second']:.3g} |")
    large = SIZES[1:]
    for solver in solvers:
        exponent = slope(large, [results[solver][n]["per_second"] for n in large])
        print(f"{solver}: time per simulated second grows as n^{exponent:.2f} from n = 10 to 1000")
    peaks = [results["gmres"][n]["peak_mb"] for n in SIZES]
    print("GMRES peak memory per added muscle (kB): " + ", ".join(
        f"{SIZES[k - 1]} to {SIZES[k]}: {(peaks[k] - peaks[k - 1]) / (SIZES[k] - SIZES[k - 1]) * 1024:.0f}"
        for k in range(2, len(SIZES))) + " (the first includes the allocator's start-up)")
    for solver in ("gmres", "klu"):
        thousand = results[solver][1000]["per_second"] * 100
        print(f"{solver}: 1000 muscles, 100 s simulated: {thousand:.2f} s of integration "
              "(target < 10 s)")


if __name__ == "__main__":
    main()
