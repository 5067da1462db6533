#!/usr/bin/env python3
"""Localise the Intel Research Lab log from Python and plot truth, estimate and error.

    PYTHONPATH=build/release/python python3 mcl/python/examples/intel_localize.py \\
        [--case out/demo/intel] [--out intel.png]

The case is what `bash cmake/demo.sh` writes to out/demo/intel/: map.yaml (a 5 cm map
from the log's SLAM-corrected poses), raw.log.gz (the scans with seeded realistic wheel
odometry) and truth.tum (the corrected poses). When --case holds no map.yaml (or with
--make-case), the script makes the case there from data/logs/intel-corrected.log.gz with
the `pgmcl` binary (--pgmcl). Without --out the figure is shown in a window.
"""

import argparse
import pathlib
import subprocess
import sys

import numpy as np

import pgmcl

REPO = pathlib.Path(__file__).resolve().parents[3]
INTEL_LOG = REPO / "data" / "logs" / "intel-corrected.log.gz"


def make_intel_case(pgmcl_bin, folder):
    """Writes map.yaml, raw.log.gz and truth.tum into `folder` as cmake/demo.sh does."""
    folder = pathlib.Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    for args in (
        ["map", "--log", INTEL_LOG, "--resolution", "0.05", "--out", folder / "map.yaml"],
        ["perturb", "--log", INTEL_LOG, "--odom-noise", "0.005,0.0005,0.005,0.0005",
         "--seed", "1", "--out", folder / "raw.log.gz", "--truth-out", folder / "truth.tum"],
    ):
        subprocess.run([str(pgmcl_bin)] + [str(a) for a in args], check=True,
                       stdout=subprocess.DEVNULL)
    return folder


def plot(m, run, truth, out):
    import matplotlib.pyplot as plt

    fig = plt.figure(figsize=(12, 6), constrained_layout=True)
    grid = fig.add_gridspec(2, 2, width_ratios=(1.1, 1))
    ax_map = fig.add_subplot(grid[:, 0])
    # Unknown cells grey, free white, occupied black; row 0 is the bottom row.
    shade = np.where(m.cells < 0, 0.8, 1.0 - m.cells / 100.0)
    ax_map.imshow(shade, cmap="gray", vmin=0, vmax=1, origin="lower", extent=m.extent)
    ax_map.plot(truth[:, 1], truth[:, 2], color="tab:green", lw=1.2, label="truth")
    est = run.trajectory
    ax_map.plot(est[:, 1], est[:, 2], color="tab:red", lw=0.8, label="estimate")
    ax_map.set(title="Intel Research Lab", xlabel="x [m]", ylabel="y [m]", aspect="equal")
    ax_map.legend(loc="lower right")

    t, position, heading = run.errors.T
    metrics = run.metrics
    ax_pos = fig.add_subplot(grid[0, 1])
    ax_pos.plot(t - t[0], position, color="tab:red")
    ax_pos.set(title=f"position error (ATE RMSE {metrics['ate_rmse_m']:.3f} m)",
               ylabel="metres")
    ax_head = fig.add_subplot(grid[1, 1], sharex=ax_pos)
    ax_head.plot(t - t[0], heading, color="tab:blue")
    ax_head.set(title=f"heading error (RMSE {metrics['heading_rmse_deg']:.2f} deg)",
                xlabel="time since the first scan [s]", ylabel="degrees")
    if out:
        out.parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(out, dpi=110)
        print(f"wrote {out}")
    else:
        plt.show()


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--case", type=pathlib.Path, default=REPO / "out" / "demo" / "intel",
                        help="folder with map.yaml, raw.log.gz, truth.tum (made if missing)")
    parser.add_argument("--pgmcl", default=REPO / "build" / "release" / "pgmcl",
                        help="pgmcl binary, to make the case")
    parser.add_argument("--make-case", action="store_true",
                        help="make the case in --case even if it is there")
    parser.add_argument("--out", type=pathlib.Path,
                        help="save the figure here (PNG) instead of showing it")
    args = parser.parse_args()

    case = args.case
    if args.make_case or not (case / "map.yaml").exists():
        make_intel_case(args.pgmcl, case)
    m = pgmcl.load_map(case / "map.yaml")
    truth = pgmcl.read_tum(case / "truth.tum")
    # The demo's filter (configs/experiments/intel-demo.yaml): motion noise that covers the
    # odometry perturbation, 1000 particles, one thread, seed 1; start at the truth.
    config = pgmcl.Config({
        "motion.noise": {"a1": 0.01, "a2": 0.001, "a3": 0.01, "a4": 0.001},
        "filter.particles": 1000,
    })
    run = pgmcl.localize(m, case / "raw.log.gz", truth=truth, config=config, seed=1, threads=1)
    print(f"{len(run.trajectory)} poses, ATE RMSE {run.metrics['ate_rmse_m']:.3f} m, "
          f"heading RMSE {run.metrics['heading_rmse_deg']:.2f} deg, "
          f"{run.metrics['update_ms_mean']:.2f} ms per update")
    plot(m, run, truth, args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
