#!/usr/bin/env python3
"""Robustness benchmark: the conditions of unseen real logs, built from the shared ones.

    bench/robustness/run.py [--data DIR] [--pgmcl BIN] [--seeds N] [--jobs N]
                            [--logs intel,aces,fr079,csail-raw] [--conditions a,b,...]
                            [--modes tracking,global] [--out DIR] [--set KEY=VALUE]...
                            [--filter-seed-offset K]

For every log, condition, mode and seed it makes a case with `pgmcl perturb` /
`pgmcl perturb-map` (seeded, so a seed reproduces a case exactly), runs
`pgmcl localize` with engine defaults (no --config: settings derived from the log only),
and scores it from metrics.yaml:
  tracking  success = ATE RMSE <= 0.10 m and never more than 1 m off;
  global    success = locked on (within 1 m from then on) within 60 s of log time or
            30 m of travel, then ATE RMSE <= 0.10 m and never more than 1 m off;
  with odometry glitches, an excursion that is back within 5 updates (heading) or 10
  (2 m slip) is allowed and left out of the ATE (ALLOWANCE).
It writes runs.csv (one row per run) and summary.md (one row per condition and mode) to
--out (default results/bench/robustness). Standard library only.

Seed s makes the case and, by default, also seeds the filter. --filter-seed-offset K
seeds the filter with s + K on the same cases: the runs that then change outcome measure
how much of a success rate is the filter's own random draws, the margin a change to the
engine must clear before it counts.
"""
import argparse
import concurrent.futures
import csv
import os
import shutil
import statistics
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))

# Radish / Freiburg SLAM-benchmark logs with SLAM-corrected poses (truth), and csail with
# its raw wheel odometry (data README of the shared folder).
CORRECTED = {
    "intel": "intel-corrected.log.gz",
    "aces": "aces-corrected.log.gz",
    "fr079": "freiburg-079-corrected.log.gz",
}

# Wheel odometry: about 7 % of rotation, 1.3 deg/m and 7 % of distance (variance form).
REALISTIC = ["--odom-noise", "0.005,0.0005,0.005,0.0005"]

# Conditions of the held-out logs (issue 13). Each is (perturb options, map variant, logs).
# A glitch puts the odometry off at once; the filter must absorb a heading glitch within
# 5 updates and a 2 m slip within 10 (ALLOWANCE): those excursions are scored apart.
# Map variants: map (5 cm), map10 (10 cm), fuzzy (walls thickened by a cell and blurred,
# a probability map), stale (a tenth of the wall blocks erased).
CONDITIONS = {
    "realistic": (REALISTIC, "map", None),
    # 1. heading glitches: Table 5.6 sampled literally (rot1 ~ 180 deg on reversals) plus
    #    2 % of the steps with a 24-30 deg heading error. The held-out logs keep about a scan
    #    per metre, so steps are at least 0.3 m or 15 deg (this thins only fr079's 4 Hz log,
    #    where Table 5.6 on a robot standing still would random-walk its heading).
    "glitch": (REALISTIC + ["--odom-model", "textbook", "--glitch", "0.02,30",
                            "--min-scan-travel", "0.3,15"], "map", None),
    # A 2 m wheel slip on 1 % of the steps (steps as above).
    "slip": (REALISTIC + ["--translation-glitch", "0.01,2", "--min-scan-travel", "0.3,15"],
             "map", None),
    # Odometry noisier than the filter's default model (= REALISTIC) assumes, as the held-out
    # logs' synthetic odometry is (rotation noise 5x wider made them track): rotation
    # variances 5x, translation 2x; and, noisier, 10x and 4x (22 % of rotation, 4 deg/m, 14 %
    # of distance).
    "noisy": (["--odom-noise", "0.025,0.0025,0.01,0.001"], "map", None),
    "noisier": (["--odom-noise", "0.05,0.005,0.02,0.002"], "map", None),
    # 2. systematic bias: 1.5 % distance scale, 0.4 deg/m yaw drift.
    "bias": (REALISTIC + ["--scale-bias", "0.015", "--yaw-drift", "0.4"], "map", None),
    # 3. sparse scans: at least 1.2 m or 35 deg between scans, and 2 s.
    "sparse": (REALISTIC + ["--min-scan-travel", "1.2,35", "--min-scan-gap", "2"], "map", None),
    # All of 1-3 at once, as in the held-out logs.
    "heldout": (REALISTIC + ["--odom-model", "textbook", "--glitch", "0.02,30", "--scale-bias",
                             "0.015", "--yaw-drift", "0.4", "--min-scan-travel", "1.2,35"],
                "map", None),
    # 4. outdoor-campus-like: sparse structure (60 % of each scan open space, in three
    #    sectors) on the 360-beam log.
    "campus": (REALISTIC + ["--beam-dropout", "0.6,3"], "map", None),
    # 5. maps: 10 cm, and a hand-made-looking probability map with fuzzy walls.
    "map10": (REALISTIC, "map10", None),
    "fuzzy": (REALISTIC, "fuzzy", None),
    # 6. a laser 25 cm ahead of the base.
    "offset": (REALISTIC + ["--laser-offset", "0.25"], "map", ["intel", "aces"]),
    # Not among the held-out conditions, so not run by default: a stale map with a tenth
    # of its wall blocks missing (the scans still see them).
    "stale": (REALISTIC, "stale", None),
}
DEFAULT_CONDITIONS = [c for c in CONDITIONS if c != "stale"] + ["real"]
ALLOWANCE = {"glitch": 5, "heldout": 5, "slip": 10}
# csail-raw: real odometry, so only the map conditions apply.
REAL_CONDITIONS = {"real": "map", "map10": "map10", "fuzzy": "fuzzy"}


def run(cmd, log_path=None):
    p = subprocess.run(cmd, capture_output=True, text=True)
    if log_path:
        with open(log_path, "w") as f:
            f.write(" ".join(cmd) + "\n" + p.stdout + p.stderr)
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({p.returncode}):\n{p.stderr[-2000:]}")
    return p


def read_metrics(path):
    out = {}
    with open(path) as f:
        for line in f:
            if line.startswith("#") or ":" not in line:
                continue
            k, v = line.split(":", 1)
            v = v.strip()
            try:
                out[k.strip()] = float(v)
            except ValueError:
                out[k.strip()] = None if v == "null" else v
    return out


def prepare_maps(pgmcl, base, map_source, out):
    """map.yaml (5 cm), map10.yaml, fuzzy.yaml and sparse.yaml in `out`."""
    os.makedirs(out, exist_ok=True)
    done = os.path.join(out, ".done")
    if os.path.exists(done):
        return
    run([pgmcl, "map", "--log", map_source, "--resolution", "0.05", "--out",
         os.path.join(out, "map.yaml"), "--quiet"])
    run([pgmcl, "map", "--log", map_source, "--resolution", "0.10", "--out",
         os.path.join(out, "map10.yaml"), "--quiet"])
    run([pgmcl, "perturb-map", "--map", os.path.join(out, "map.yaml"), "--out",
         os.path.join(out, "fuzzy.yaml"), "--thicken", "1", "--blur", "1", "--quiet"])
    run([pgmcl, "perturb-map", "--map", os.path.join(out, "map.yaml"), "--out",
         os.path.join(out, "stale.yaml"), "--erase", "0.1,2", "--seed", "1", "--quiet"])
    open(done, "w").close()


def read_tum(path):
    out = []
    with open(path) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            v = line.split()
            out.append((float(v[0]), float(v[1]), float(v[2])))
    return out


def run_dir(out, log, cond, seed, mode):
    """Where a run's outputs (console.txt, metrics.yaml, updates.csv) go under --out."""
    return os.path.join(out, "runs", f"{log}-{cond}-s{seed}-{mode}")


def excursions(e, cond):
    """Runs of updates more than 0.25 m off, as [begin, end) indices into the errors `e`,
    and those of them that count as lost: past 1 m, and longer than ALLOWANCE[cond]."""
    runs, i = [], 0
    while i < len(e):
        if e[i] > 0.25:
            j = i
            while j < len(e) and e[j] > 0.25:
                j += 1
            runs.append((i, j))
            i = j
        else:
            i += 1
    allowance = ALLOWANCE.get(cond, 0)
    return runs, [(b, k) for (b, k) in runs if k - b > allowance and max(e[b:k]) > 1.0]


def score(mode, cond, updates_csv, truth):
    """(success, lock-on s, lock-on travel m, longest run more than 1 m off, scored ATE).

    Per-update errors come from updates.csv. An excursion is a run of updates more than
    0.25 m off; one that is back within ALLOWANCE[cond] updates (an odometry glitch being
    absorbed) does not count as lost and is left out of the ATE. Lock-on is the first
    update from which no excursion past 1 m lasts longer than that allowance."""
    with open(updates_csv) as f:
        rows = [r for r in csv.DictReader(f) if r["error_m"] not in ("nan", "")]
    if not rows:
        return False, None, None, None, None
    t = [float(r["stamp"]) for r in rows]
    e = [float(r["error_m"]) for r in rows]
    allowance = ALLOWANCE.get(cond, 0)
    runs, lost = excursions(e, cond)
    lock = lost[-1][1] if lost else 0
    if lock >= len(e):
        return False, None, None, max(k - b for b, k in lost), None
    keep = [True] * len(e)
    for b, k in runs:
        if k - b <= allowance:
            keep[b:k] = [False] * (k - b)
    kept = [x for x, k in zip(e[lock:], keep[lock:]) if k]
    ate = (sum(x * x for x in kept) / len(kept)) ** 0.5 if kept else float("nan")
    lock_s = t[lock] - t[0]
    tr = [p for p in truth if t[0] <= p[0] <= t[lock]]
    travel = sum(((b[1] - a[1]) ** 2 + (b[2] - a[2]) ** 2) ** 0.5 for a, b in zip(tr, tr[1:]))
    longest = max((k - b for b, k in runs if max(e[b:k]) > 1.0 and b >= lock), default=0)
    if mode == "tracking":
        ok = lock == 0 and ate <= 0.10
    else:
        ok = (lock_s <= 60.0 or travel <= 30.0) and ate <= 0.10
    return ok, lock_s, travel, longest, ate


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--data", default=os.path.join(ROOT, "..", "shared", "data"))
    ap.add_argument("--pgmcl", default=os.path.join(ROOT, "build", "release", "pgmcl"))
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "bench", "robustness"))
    ap.add_argument("--seeds", type=int, default=5, help="how many seeds")
    ap.add_argument("--first-seed", type=int, default=1, help="seeds first-seed .. first-seed + seeds - 1")
    ap.add_argument("--filter-seed-offset", type=int, default=0, metavar="K",
                    help="seed the filter with seed + K (the cases keep seed): the draws' share of the result")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--logs", default="intel,aces,fr079,csail-raw")
    ap.add_argument("--conditions", default=",".join(DEFAULT_CONDITIONS))
    ap.add_argument("--modes", default="tracking,global")
    ap.add_argument("--set", action="append", default=[], help="passed to pgmcl localize")
    ap.add_argument("--tag", default="", help="suffix of the output files")
    ap.add_argument("--ci", action="store_true",
                    help="exit with status 1 naming every run that misses its bound")
    ap.add_argument("--known-failure", action="append", default=[], metavar="LOG:CONDITION:MODE:SEED",
                    help="with --ci: a run listed in the README as failing; it does not fail the "
                         "suite, and is reported once it passes")
    a = ap.parse_args()
    if not os.access(a.pgmcl, os.X_OK):
        sys.exit(f"run.py: {a.pgmcl} is not an executable (build it: cmake --build build/release --target pgmcl)")
    logs = [x for x in a.logs.split(",") if x]
    conds = [x for x in a.conditions.split(",") if x]
    modes = [x for x in a.modes.split(",") if x]
    cases_dir = os.path.join(a.out, "cases")

    # Maps per log (once), then the perturbed cases per (log, condition, seed).
    jobs = []
    for log in logs:
        if log == "csail-raw":
            raw = os.path.join(a.data, "logs", "csail-raw.clf.gz")
            corrected = os.path.join(a.data, "logs", "csail-corrected.log.gz")
            if not (os.path.exists(raw) and os.path.exists(corrected)):
                print(f"run.py: csail logs not in {a.data}, skipping csail-raw", file=sys.stderr)
                continue
            case = os.path.join(cases_dir, log)
            prepare_maps(a.pgmcl, a.data, corrected, case)
            truth = os.path.join(case, "truth.tum")  # the corrected poses, as TUM
            if not os.path.exists(truth):
                run([a.pgmcl, "perturb", "--log", corrected, "--odom-noise", "0,0,0,0", "--seed", "1",
                     "--out", os.path.join(case, "corrected-copy.log.gz"), "--truth-out", truth,
                     "--quiet"])
            for cond in conds:
                if cond in REAL_CONDITIONS:
                    jobs.append((log, cond, REAL_CONDITIONS[cond], None, raw, truth))
            continue
        source = os.path.join(a.data, "logs", CORRECTED[log])
        if not os.path.exists(source):
            print(f"run.py: {source} not found, skipping {log}", file=sys.stderr)
            continue
        prepare_maps(a.pgmcl, a.data, source, os.path.join(cases_dir, log))
        for cond in conds:
            if cond not in CONDITIONS:
                continue
            opts, variant, only = CONDITIONS[cond]
            if only and log not in only:
                continue
            jobs.append((log, cond, variant, opts, source, None))

    def one(job, seed, mode):
        log, cond, variant, opts, source, truth_log = job
        case = os.path.join(cases_dir, log)
        if opts is None:  # real odometry
            raw, truth = source, truth_log
        else:
            raw = os.path.join(case, f"{cond}-s{seed}.log.gz")
            truth = os.path.join(case, f"{cond}-s{seed}.tum")
            # A case is made again when its condition's options changed since.
            stamp = os.path.join(case, f"{cond}-s{seed}.options")
            made_with = open(stamp).read() if os.path.exists(stamp) else None
            if made_with != " ".join(opts) or not os.path.exists(truth):
                run([a.pgmcl, "perturb", "--log", source, "--seed", str(seed), "--out", raw,
                     "--truth-out", truth, "--quiet"] + opts)
                with open(stamp, "w") as f:
                    f.write(" ".join(opts))
        out = run_dir(a.out, log, cond, seed, mode)
        cmd = [a.pgmcl, "localize", "--map", os.path.join(case, variant + ".yaml"), "--log", raw,
               "--truth", truth, "--seed", str(seed + a.filter_seed_offset), "--out", out, "--quiet"]
        if mode == "global":
            cmd.append("--global")
        for s in a.set:
            cmd += ["--set", s]
        os.makedirs(out, exist_ok=True)
        run(cmd, os.path.join(out, "console.txt"))
        m = read_metrics(os.path.join(out, "metrics.yaml"))
        ok, lock, travel, lost_run, ate = score(mode, cond, os.path.join(out, "updates.csv"),
                                                read_tum(truth))
        return {"log": log, "condition": cond, "mode": mode, "seed": seed, "success": ok,
                "scored_ate_m": ate, "lock_s": lock, "lock_travel_m": travel,
                "lost_run": lost_run, **{k: m.get(k) for k in (
                    "ate_rmse_m", "ate_max_m", "false_converged",
                    "false_converged_run", "converged_fraction", "fit_mean", "update_ms_mean",
                    "particles_mean", "rotation_noise_factor", "translation_noise_factor")}}

    # Perturbed logs are shared by both modes: make them first, then run everything.
    seeds = range(a.first_seed, a.first_seed + a.seeds)
    tasks = [(j, s, mode) for j in jobs for s in seeds for mode in modes]
    rows = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as pool:
        firsts = [pool.submit(one, j, s, modes[0]) for j in jobs for s in seeds]
        rows += [f.result() for f in firsts]
        rest = [pool.submit(one, j, s, mode) for (j, s, mode) in tasks if mode != modes[0]]
        rows += [f.result() for f in rest]

    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.out, f"runs{a.tag}.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    write_summary(rows, os.path.join(a.out, f"summary{a.tag}.md"), a)
    known = set(a.known_failure)
    key = lambda r: f"{r['log']}:{r['condition']}:{r['mode']}:{r['seed']}"
    for r in rows:
        if key(r) in known:
            print(f"known failure {key(r)}: {'still fails' if not r['success'] else 'now PASSES: drop it from the list'}")
    failed = [r for r in rows if not r["success"] and key(r) not in known]
    if a.ci and failed:
        for r in failed:
            print(f"FAILED: {r['log']} {r['condition']} {r['mode']} seed {r['seed']}: "
                  f"ATE {fmt(r['scored_ate_m'])} m, lock-on {fmt(r['lock_s'], 1)} s, "
                  f"longest stretch more than 1 m off {r['lost_run']} updates "
                  f"(console: {run_dir(a.out, r['log'], r['condition'], r['seed'], r['mode'])})",
                  file=sys.stderr)
        sys.exit(1)


def fmt(v, digits=3):
    return "—" if v is None else f"{v:.{digits}f}"


def write_summary(rows, path, a):
    groups = {}
    for r in rows:
        groups.setdefault((r["condition"], r["mode"]), []).append(r)
    order = list(CONDITIONS) + ["real"]
    lines = ["| condition | mode | logs | success | ATE median (worst) m | lock-on median (worst) s |"
             " wrongly converged (longest run) | ms/update | particles | noise factors |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    total = ok = 0
    for (cond, mode) in sorted(groups, key=lambda k: (order.index(k[0]) if k[0] in order else 99, k[1])):
        g = groups[(cond, mode)]
        n, k = len(g), sum(1 for r in g if r["success"])
        total, ok = total + n, ok + k
        ates = [r["scored_ate_m"] for r in g if r["scored_ate_m"] is not None]
        locks = [r["lock_s"] if r["lock_s"] is not None else float("inf") for r in g]
        fc = sum(int(r["false_converged"] or 0) for r in g)
        fr = max(int(r["false_converged_run"] or 0) for r in g)
        ms = statistics.mean(r["update_ms_mean"] for r in g)
        parts = statistics.mean(r["particles_mean"] for r in g)
        logs = ",".join(sorted({r["log"] for r in g}))
        # The motion-noise factors (rotation, translation) the runs ended with, medians.
        rot = statistics.median(r["rotation_noise_factor"] or 1.0 for r in g)
        trans = statistics.median(r["translation_noise_factor"] or 1.0 for r in g)
        lines.append(f"| {cond} | {mode} | {logs} | {k}/{n} | {fmt(statistics.median(ates)) if ates else '—'}"
                     f" ({fmt(max(ates)) if ates else '—'}) | {statistics.median(locks):.1f} ({max(locks):.1f}) |"
                     f" {fc} ({fr}) | {ms:.2f} | {parts:.0f} | {rot:.1f}, {trans:.1f} |")
    lines.append("")
    lines.append(f"All: {ok}/{total} runs succeed ({100.0 * ok / max(1, total):.1f} %). "
                 f"Seeds {a.first_seed}..{a.first_seed + a.seeds - 1}"
                 + (f" (filter seeded with seed + {a.filter_seed_offset})" if a.filter_seed_offset else "")
                 + f"; extra settings: {' '.join(a.set) or 'none (engine defaults)'}.")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
