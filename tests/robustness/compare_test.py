#!/usr/bin/env python3
"""bench/robustness/compare.py: flips counted per run, the sign test against its closed
form, and bad input named by file, line and field. Standard library only."""
import importlib.util
import math
import os
import subprocess
import sys
import tempfile
import unittest

SCRIPT = os.path.join(os.path.dirname(__file__), "..", "..", "bench", "robustness", "compare.py")
spec = importlib.util.spec_from_file_location("compare", SCRIPT)
compare = importlib.util.module_from_spec(spec)
spec.loader.exec_module(compare)

HEADER = "log,condition,mode,seed,success\n"


def suite(root, name, rows):
    d = os.path.join(root, name)
    os.makedirs(d)
    with open(os.path.join(d, "runs.csv"), "w") as f:
        f.write(HEADER + "".join(f"{r}\n" for r in rows))
    return d


def run(*args):
    return subprocess.run([sys.executable, SCRIPT, *args], capture_output=True, text=True)


class Compare(unittest.TestCase):
    def test_sign_test_matches_the_binomial_tail(self):
        self.assertEqual(compare.sign_test(0, 0), 1.0)
        self.assertAlmostEqual(compare.sign_test(0, 10), 2.0 / 1024.0)
        self.assertAlmostEqual(compare.sign_test(10, 0), 2.0 / 1024.0)
        # 13 against 27: twice P(X <= 13) for X ~ Binomial(40, 1/2).
        tail = sum(math.comb(40, k) for k in range(14)) / 2.0 ** 40
        self.assertAlmostEqual(compare.sign_test(13, 27), 2.0 * tail)
        self.assertEqual(compare.sign_test(5, 5), 1.0)

    def test_counts_flips_on_the_runs_both_sides_share(self):
        with tempfile.TemporaryDirectory() as root:
            base = suite(root, "base", ["intel,glitch,tracking,1,True", "intel,glitch,global,1,False",
                                        "aces,slip,tracking,2,True", "aces,slip,global,2,True"])
            variant = suite(root, "variant", ["intel,glitch,tracking,1,False", "intel,glitch,global,1,True",
                                              "aces,slip,tracking,2,True", "aces,slip,global,2,False",
                                              "aces,slip,global,3,True"])
            p = run("--base", base, "--variant", variant, "--list")
            self.assertEqual(p.returncode, 0, p.stderr)
            self.assertIn("1 runs only in variant, left out", p.stdout)
            self.assertIn("4 runs: base 3 succeed, variant 2", p.stdout)
            self.assertIn("by log (base/variant): aces 2/1 of 2, intel 1/1 of 2", p.stdout)
            self.assertIn("changed outcome: 1 gained, 2 lost; sign test p = 1.000", p.stdout)
            self.assertIn("  + intel glitch global seed 1", p.stdout)
            self.assertIn("  - aces slip global seed 2", p.stdout)
            self.assertIn("  - intel glitch tracking seed 1", p.stdout)

    def test_bad_input_is_named(self):
        with tempfile.TemporaryDirectory() as root:
            good = suite(root, "good", ["intel,glitch,tracking,1,True"])
            bad = suite(root, "bad", ["intel,glitch,tracking,1,True", "intel,glitch,global,1,yes"])
            p = run("--base", good, "--variant", bad)
            self.assertNotEqual(p.returncode, 0)
            self.assertIn(os.path.join(bad, "runs.csv") + ":3: field success: 'yes'", p.stderr)
            p = run("--base", good, "--variant", os.path.join(root, "missing"))
            self.assertNotEqual(p.returncode, 0)
            self.assertIn("missing/runs.csv: no such file", p.stderr)
            with open(os.path.join(bad, "runs.csv"), "w") as f:
                f.write("log,condition,mode,success\nintel,glitch,tracking,True\n")
            p = run("--base", good, "--variant", bad)
            self.assertIn(os.path.join(bad, "runs.csv") + ":1: no field seed in the header", p.stderr)
            with open(os.path.join(bad, "runs.csv"), "w") as f:
                f.write(HEADER + "intel,glitch,tracking,one,True\n")
            p = run("--base", good, "--variant", bad)
            self.assertIn(os.path.join(bad, "runs.csv") + ":2: field seed: 'one'", p.stderr)
            again = suite(root, "again", ["intel,glitch,global,2,True", "intel,glitch,tracking,1,False"])
            p = run("--base", good, "--variant", good, again)
            self.assertNotEqual(p.returncode, 0)
            self.assertIn(os.path.join(again, "runs.csv") + ":3: run intel-glitch-tracking-1 is also in "
                          + os.path.join(good, "runs.csv") + ":2", p.stderr)
            other = suite(root, "other", ["fr079,noisy,tracking,4,True"])
            p = run("--base", good, "--variant", other)
            self.assertNotEqual(p.returncode, 0)
            self.assertIn("share no run", p.stderr)


if __name__ == "__main__":
    unittest.main()
