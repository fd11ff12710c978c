#!/usr/bin/env python3
"""Speed of two gendpde binaries side by side on the benchmark cases of bench.py,
alternating A, B, REPS times (atom-steps/s of the timed run, medians and the ratio B/A).
For checking that a change costs no speed:

    python3 scripts/bench/compare.py OLD_BINARY NEW_BINARY [case-name-filter]
"""
import os
import statistics
import sys

import bench


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    old, new = sys.argv[1], sys.argv[2]
    wanted = sys.argv[3] if len(sys.argv) > 3 else ""
    print("| case | A atom-steps/s (median, min-max) | B atom-steps/s (median, min-max) | B/A |")
    print("|---|---|---|---|")
    for c in bench.cases():
        # the ideal kernel runs no gendpde binary
        if wanted not in c["name"] or c["kind"] == "kernel":
            continue
        rates = {old: [], new: []}
        for _ in range(bench.REPS):
            for binary in (old, new):
                bench.GENDPDE = binary
                rates[binary].append(bench.run("gendpde", c))
        cells = [f"{bench.fmt(statistics.median(r))} ({bench.fmt(min(r))}-{bench.fmt(max(r))})" for r in rates.values()]
        ratio = statistics.median(rates[new]) / statistics.median(rates[old])
        print(f"| {c['name']} | {cells[0]} | {cells[1]} | {ratio:.3f} |", flush=True)


if __name__ == "__main__":
    os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    main()
