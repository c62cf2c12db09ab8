#!/usr/bin/env python3
"""Times the default scenario's integration with this build's bench_integration and with the
same benchmark built from an earlier commit, interleaved round by round so that the machine's
drift cancels, and prints the ratio (this build / reference).

Usage: compare_with_commit.py THIS_BENCH REFERENCE_BENCH CONFIG [ROUNDS]
"""
import statistics
import subprocess
import sys


def median_seconds(binary, config, repeats=30):
    out = subprocess.run([binary, config, str(repeats)], check=True, capture_output=True,
                         text=True).stdout
    fields = dict(item.split("=") for item in out.split())
    return float(fields["median_seconds"]), int(fields["steps"])


def main():
    this, reference, config = sys.argv[1:4]
    rounds = int(sys.argv[4]) if len(sys.argv) > 4 else 7
    ratios = []
    for _ in range(rounds):
        ours, our_steps = median_seconds(this, config)
        theirs, their_steps = median_seconds(reference, config)
        ratios.append(ours / theirs)
    print(f"default scenario integration, this build / reference: median ratio "
          f"{statistics.median(ratios):.3f} (range {min(ratios):.3f}-{max(ratios):.3f} over "
          f"{rounds} rounds; {our_steps} steps here, {their_steps} there; target <= 1.05: "
          f"{'met' if statistics.median(ratios) <= 1.05 else 'missed'})")


if __name__ == "__main__":
    main()
