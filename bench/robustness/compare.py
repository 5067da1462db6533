#!/usr/bin/env python3
"""Compare two robustness suites run on the same cases: which runs changed outcome.

    bench/robustness/compare.py --base DIR [DIR...] --variant DIR [DIR...] [--list]

Each DIR is an --out directory of run.py (its runs.csv); several per side are merged (one
per seed set, say; a run may appear on one side only once). Runs are matched by log,
condition, mode and seed. It prints each side's successes, per log and per condition, the
runs gained and lost, and the exact two-sided sign test (McNemar's) on those flips: the
chance that the filter's random draws alone would split them at least this unevenly.
Standard library only.
"""
import argparse
import csv
import math
import os
import sys

COLUMNS = ("log", "condition", "mode", "seed", "success")


def load(dirs):
    runs, where = {}, {}
    for d in dirs:
        path = os.path.join(d, "runs.csv")
        if not os.path.exists(path):
            sys.exit(f"compare.py: {path}: no such file (an --out directory of run.py?)")
        with open(path, newline="") as f:
            reader = csv.DictReader(f)
            missing = [c for c in COLUMNS if c not in (reader.fieldnames or [])]
            if missing:
                sys.exit(f"compare.py: {path}:1: no field {missing[0]} in the header")
            for line, r in enumerate(reader, start=2):
                if r["success"] not in ("True", "False"):
                    sys.exit(f"compare.py: {path}:{line}: field success: {r['success']!r}, "
                             "expected True or False")
                if not (r["seed"] or "").isdigit():
                    sys.exit(f"compare.py: {path}:{line}: field seed: {r['seed']!r}, expected a whole number")
                key = (r["log"], r["condition"], r["mode"], int(r["seed"]))
                if key in where:  # overlapping seed sets on one side: which one counts?
                    sys.exit(f"compare.py: {path}:{line}: run {'-'.join(map(str, key))} "
                             f"is also in {where[key]}")
                where[key] = f"{path}:{line}"
                runs[key] = r["success"] == "True"
    return runs


def sign_test(gained, lost):
    """Exact two-sided binomial test of gained against lost at p = 1/2."""
    n = gained + lost
    if n == 0:
        return 1.0
    tail = sum(math.comb(n, k) for k in range(0, min(gained, lost) + 1)) / 2.0 ** n
    return min(1.0, 2.0 * tail)


def tally(runs, keys, field):
    out = {}
    for k in keys:
        ok, n = out.get(k[field], (0, 0))
        out[k[field]] = (ok + runs[k], n + 1)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--base", nargs="+", required=True, metavar="DIR")
    ap.add_argument("--variant", nargs="+", required=True, metavar="DIR")
    ap.add_argument("--list", action="store_true", help="name every run that changed outcome")
    a = ap.parse_args()
    base, variant = load(a.base), load(a.variant)
    common = sorted(set(base) & set(variant))
    if not common:
        sys.exit("compare.py: the two sides share no run (same logs, conditions, modes, seeds?)")
    for name, keys in (("only in base", set(base) - set(variant)),
                       ("only in variant", set(variant) - set(base))):
        if keys:
            print(f"{len(keys)} runs {name}, left out")
    b_ok = sum(base[k] for k in common)
    v_ok = sum(variant[k] for k in common)
    print(f"{len(common)} runs: base {b_ok} succeed, variant {v_ok}")
    for field, label in ((0, "log"), (1, "condition"), (2, "mode")):
        bt, vt = tally(base, common, field), tally(variant, common, field)
        cells = ", ".join(f"{g} {bt[g][0]}/{vt[g][0]} of {bt[g][1]}" for g in sorted(bt))
        print(f"  by {label} (base/variant): {cells}")
    gained = [k for k in common if not base[k] and variant[k]]
    lost = [k for k in common if base[k] and not variant[k]]
    print(f"changed outcome: {len(gained)} gained, {len(lost)} lost; "
          f"sign test p = {sign_test(len(gained), len(lost)):.3f}")
    if a.list:
        for sign, keys in (("+", gained), ("-", lost)):
            for log, cond, mode, seed in keys:
                print(f"  {sign} {log} {cond} {mode} seed {seed}")


if __name__ == "__main__":
    main()
