#!/usr/bin/env python3
"""bench/robustness/failures.py: each failing run's lost excursion found as run.py scores
it, its cause named from the updates before it, and bad input named by file, line and
field. Standard library only."""
import os
import subprocess
import sys
import tempfile
import unittest

SCRIPT = os.path.join(os.path.dirname(__file__), "..", "..", "bench", "robustness", "failures.py")
HEADER = "stamp,converged,fit,switched,error_m\n"


def suite(root, name, runs):
    """runs: (log, condition, mode, seed, success, [(fit, switched, error_m), ...])."""
    d = os.path.join(root, name)
    os.makedirs(d)
    with open(os.path.join(d, "runs.csv"), "w") as f:
        f.write("log,condition,mode,seed,success\n")
        for log, cond, mode, seed, ok, updates in runs:
            f.write(f"{log},{cond},{mode},{seed},{ok}\n")
            run_dir = os.path.join(d, "runs", f"{log}-{cond}-s{seed}-{mode}")
            os.makedirs(run_dir)
            with open(os.path.join(run_dir, "updates.csv"), "w") as u:
                u.write(HEADER + "".join(f"{i * 0.5},1,{fit},{sw},{e}\n"
                                         for i, (fit, sw, e) in enumerate(updates)))
    return d


def run(*args):
    return subprocess.run([sys.executable, SCRIPT, *args], capture_output=True, text=True)


GOOD = (0.9, 0, 0.05)
# A switch as the set leaves, two updates before it is 1.5 m off for three updates.
SWITCHED = [GOOD] * 4 + [(0.9, 1, 0.3), (0.9, 0, 0.6)] + [(0.9, 0, 1.5)] * 3 + [GOOD]
# The scan fits 0.2 of the beams three updates before the set drifts off: within a window
# of 5 updates before the excursion, not within one of 2.
MISFIT = [GOOD] * 3 + [(0.2, 0, 0.1)] + [GOOD] * 2 + [(0.9, 0, 0.3)] * 3 + [(0.9, 0, 2.0)] + [GOOD]
# Off by 0.15 m throughout: the ATE misses its bound without any excursion.
BIASED = [(0.9, 0, 0.15)] * 10
# 1.2 m off for 3 updates: within the glitch condition's allowance (5 updates), so no
# excursion is lost (the run failed on its ATE, say).
ABSORBED = [GOOD] * 3 + [(0.9, 0, 1.2)] * 3 + [GOOD] * 3

# A global search 20 m off for three updates, which is no loss, then 3 m off for two; the
# search's low fit is not in the window before the loss.
SEARCH_THEN_LOST = [(0.1, 0, 20.0)] * 3 + [GOOD] * 3 + [(0.9, 0, 3.0)] * 2 + [GOOD]


class Failures(unittest.TestCase):
    def test_causes_and_the_cases_that_always_fail(self):
        with tempfile.TemporaryDirectory() as root:
            a = suite(root, "a", [("intel", "noisier", "tracking", 1, False, SWITCHED),
                                  ("intel", "noisy", "tracking", 2, False, MISFIT),
                                  ("aces", "bias", "global", 3, False, BIASED),
                                  ("aces", "glitch", "tracking", 4, False, ABSORBED),
                                  ("aces", "noisy", "global", 5, False, SEARCH_THEN_LOST)])
            b = suite(root, "b", [("intel", "noisier", "tracking", 1, False, SWITCHED),
                                  ("intel", "noisy", "tracking", 2, True, [GOOD] * 5)])
            p = run(a, b, "--list")
            self.assertEqual(p.returncode, 0, p.stderr)
            self.assertIn("6 of 7 runs fail", p.stdout)
            self.assertIn("by cause: switch 2, misfit 1, other 1, none 2", p.stdout)
            self.assertIn("5 cases, 4 fail in every directory that holds them", p.stdout)
            self.assertIn("switch intel noisier tracking seed 1 at 2.0 s, 5 updates, worst 1.50 m, "
                          f"fit 0.90 ({a})", p.stdout)
            self.assertIn("misfit intel noisy tracking seed 2 at 3.0 s, 4 updates, worst 2.00 m, "
                          f"fit 0.20 ({a})", p.stdout)
            self.assertIn(f"none   aces bias global seed 3 ({a})", p.stdout)
            self.assertIn(f"none   aces glitch tracking seed 4 ({a})", p.stdout)
            self.assertIn("other  aces noisy global seed 5 at 3.0 s, 2 updates, worst 3.00 m, "
                          f"fit 0.90 ({a})", p.stdout)
            self.assertIn("failing in every directory that holds them:\n  aces bias global seed 3\n"
                          "  aces glitch tracking seed 4\n  aces noisy global seed 5\n"
                          "  intel noisier tracking seed 1\n", p.stdout)
            p = run(a, "--window", "2")
            self.assertIn("by cause: switch 1, misfit 0, other 2, none 2", p.stdout)

    def test_bad_input_is_named(self):
        with tempfile.TemporaryDirectory() as root:
            a = suite(root, "a", [("intel", "noisier", "tracking", 1, False, SWITCHED)])
            updates = os.path.join(a, "runs", "intel-noisier-s1-tracking", "updates.csv")
            with open(updates, "a") as f:
                f.write("9.0,1,high,0,0.05\n")
            p = run(a)
            self.assertNotEqual(p.returncode, 0)
            self.assertIn(f"{updates}:12: field fit: 'high', expected a number", p.stderr)
            with open(updates, "w") as f:
                f.write("stamp,converged,switched,error_m\n0.0,1,0,0.05\n")
            p = run(a)
            self.assertIn(f"{updates}:1: no field fit in the header", p.stderr)
            os.remove(updates)
            p = run(a)
            self.assertIn(f"{updates}: no such file", p.stderr)
            p = run(os.path.join(root, "missing"))
            self.assertIn("missing/runs.csv: no such file", p.stderr)
            p = run(a, "--low-fit", "2")
            self.assertIn("--low-fit within [0, 1]", p.stderr)


if __name__ == "__main__":
    unittest.main()
