#!/usr/bin/env python3
"""Where and how a robustness suite's runs fail: the excursion that lost each one.

    bench/robustness/failures.py DIR [DIR...] [--window N] [--low-fit F] [--list]

Each DIR is an --out directory of run.py (runs.csv and runs/*/updates.csv); several may be
given, one per seed set or per filter seed. For every failing run it finds the excursion
that lost it, as run.py scores it (more than 0.25 m off, past 1 m, longer than the
condition's allowance): the first one after the run was first within 1 m, so that a global
search is no loss. It then looks at the updates from `window` before that excursion up
to the first one more than 1 m off, and names a cause:
  switch   the competing hypotheses switched the set there (to a wrong place, or back);
  misfit   the scan fitted the estimate below --low-fit there (people, clutter, a slip);
  other    neither: the set drifted off while the scans fitted it;
  none     no excursion was lost: the ATE missed its bound, or a global search took too long.
It prints the failures per cause and condition, and how many cases failed in every DIR
that holds them. Standard library only.
"""
import argparse
import collections
import csv
import importlib.util
import os
import sys

_spec = importlib.util.spec_from_file_location(
    "robustness_run", os.path.join(os.path.dirname(os.path.abspath(__file__)), "run.py"))
robustness_run = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(robustness_run)

CAUSES = ("switch", "misfit", "other", "none")


def seed_order(seed):
    """A seed as a number for sorting (runs.csv's seeds are whole numbers)."""
    return int(seed) if seed.isdigit() else 0


def fail(msg):
    sys.exit(f"failures.py: {msg}")


def number(path, line, row, field):
    try:
        return float(row[field])
    except (KeyError, TypeError, ValueError):
        fail(f"{path}:{line}: field {field}: {row.get(field)!r}, expected a number")


def csv_rows(path, fields, what):
    """(line number, row) of a CSV file whose header holds `fields`; `what` it should be."""
    if not os.path.exists(path):
        fail(f"{path}: no such file ({what})")
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        for field in fields:
            if field not in (reader.fieldnames or []):
                fail(f"{path}:1: no field {field} in the header")
        yield from enumerate(reader, start=2)


def read_updates(path):
    """The updates with a ground-truth error (run.py scores only those), as dicts."""
    out = []
    for line, r in csv_rows(path, ("stamp", "fit", "switched", "error_m"), "the run's updates.csv"):
        if r["error_m"] in ("nan", ""):
            continue
        out.append({"stamp": number(path, line, r, "stamp"), "fit": number(path, line, r, "fit"),
                    "error": number(path, line, r, "error_m"), "switched": r["switched"] == "1"})
    return out


def diagnose(updates, cond, window, low_fit):
    """(cause, seconds from the first update to the excursion, its length in updates, its
    worst error, the lowest fit over the span looked at)."""
    e = [u["error"] for u in updates]
    _, lost = robustness_run.excursions(e, cond)
    # A global search is far off until it first gets within 1 m: that is no loss.
    found = next((i for i, x in enumerate(e) if x <= 1.0), len(e))
    loss = None
    for b, k in lost:
        past_1m = next((i for i in range(max(b, found + 1), k) if e[i] > 1.0), None)
        if past_1m is not None:
            loss = (max(b, found), k, past_1m)
            break
    if loss is None:
        return "none", None, None, None, None
    begin, end, past_1m = loss
    span = updates[max(found, begin - window):past_1m + 1]
    fit = min(u["fit"] for u in span)
    if any(u["switched"] for u in span):
        cause = "switch"
    elif fit < low_fit:
        cause = "misfit"
    else:
        cause = "other"
    return cause, updates[begin]["stamp"] - updates[0]["stamp"], end - begin, max(e[begin:end]), fit


def load(dirs, window, low_fit):
    found = []  # (dir, log, condition, mode, seed, success, diagnosis or None)
    for d in dirs:
        path = os.path.join(d, "runs.csv")
        fields = ("log", "condition", "mode", "seed", "success")
        for line, r in csv_rows(path, fields, "an --out directory of run.py?"):
            if r["success"] not in ("True", "False"):
                fail(f"{path}:{line}: field success: {r['success']!r}, expected True or False")
            ok = r["success"] == "True"
            diagnosis = None
            if not ok:
                run = robustness_run.run_dir(d, r["log"], r["condition"], r["seed"], r["mode"])
                updates = read_updates(os.path.join(run, "updates.csv"))
                diagnosis = diagnose(updates, r["condition"], window, low_fit)
            found.append((d, r["log"], r["condition"], r["mode"], r["seed"], ok, diagnosis))
    return found


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dirs", nargs="+", metavar="DIR")
    ap.add_argument("--window", type=int, default=5,
                    help="updates before the excursion that count towards its cause (default 5)")
    ap.add_argument("--low-fit", type=float, default=0.4,
                    help="a fit below this counts as a misfit (default 0.4)")
    ap.add_argument("--list", action="store_true", help="one line per failing run")
    a = ap.parse_args()
    if a.window < 0 or not (0.0 <= a.low_fit <= 1.0):
        fail("--window must be >= 0 and --low-fit within [0, 1]")
    found = load(a.dirs, a.window, a.low_fit)
    failed = [x for x in found if not x[5]]
    print(f"{len(failed)} of {len(found)} runs fail")
    by_cause = collections.Counter(x[6][0] for x in failed)
    print("by cause: " + ", ".join(f"{c} {by_cause[c]}" for c in CAUSES))
    by_condition = collections.defaultdict(collections.Counter)
    for x in failed:
        by_condition[x[2]][x[6][0]] += 1
    for cond in sorted(by_condition):
        print(f"  {cond}: " + ", ".join(f"{c} {by_condition[cond][c]}" for c in CAUSES
                                        if by_condition[cond][c]))
    outcomes = collections.defaultdict(list)
    for x in found:
        outcomes[x[1:5]].append(x[5])
    always = sorted((k for k, v in outcomes.items() if not any(v)),
                    key=lambda k: (*k[:3], seed_order(k[3])))
    print(f"{len(outcomes)} cases, {len(always)} fail in every directory that holds them")
    if a.list:
        def order(x):
            return x[6][0], x[1], x[2], x[3], seed_order(x[4])

        for d, log, cond, mode, seed, _, diagnosis in sorted(failed, key=order):
            cause, t, length, worst, fit = diagnosis
            where = ("" if t is None else
                     f" at {t:.1f} s, {length} updates, worst {worst:.2f} m, fit {fit:.2f}")
            print(f"  {cause:6s} {log} {cond} {mode} seed {seed}{where} ({d})")
        print("failing in every directory that holds them:")
        for log, cond, mode, seed in always:
            print(f"  {log} {cond} {mode} seed {seed}")


if __name__ == "__main__":
    main()
