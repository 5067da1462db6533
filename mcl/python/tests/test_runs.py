"""Whole runs from Python: read_carmen, localize (pgmcl::replay) on the bundled Intel case
with an ATE bound and the CLI's metrics.yaml, simulate, evaluate from arrays and files;
numpy results that view the run's memory."""

import os
import signal
import threading

import numpy as np
import pytest

import pgmcl
from conftest import run_cli, REPO

INTEL_RELATIONS = REPO / "data" / "relations" / "intel.relations.gz"
INTEL_OFFSET = 976052857.338  # intel log time -> relations time (data/README.md)


def read_metrics_yaml(path):
    """metrics.yaml is flat `key: value` lines, then the `warnings:` list (left out here)."""
    out = {}
    for line in path.read_text().splitlines():
        if line == "warnings:":
            break
        if line and not line.startswith("#"):
            key, value = line.split(": ", 1)
            flags = {"true": True, "false": False}
            out[key] = None if value == "null" else flags[value] if value in flags else float(value)
    return out


def test_read_carmen_gives_the_scans_as_arrays(intel):
    log = pgmcl.read_carmen(REPO / "data" / "logs" / "intel-corrected.log.gz")
    assert len(log) == 910  # `pgmcl map`: 910 scans
    assert log.ranges.shape == (910, 180) and log.ranges.dtype == np.float32
    assert np.all(np.diff(log.stamps[:100]) > 0)
    assert log.angle_min[0] == pytest.approx(-np.pi / 2)
    assert log.angle_increment[0] == pytest.approx(np.pi / 180)
    assert log.range_max[0] == pytest.approx(81.83)
    assert log.has_odometry.all() and log.has_odometry.dtype == bool
    # The corrected log's poses are the truth `pgmcl perturb --truth-out` wrote.
    truth = pgmcl.read_tum(intel / "truth.tum")
    assert np.allclose(log.truth(), truth, atol=1e-9)
    assert np.allclose(log.poses, truth[:, 1:], atol=1e-9)
    assert log.report["malformed"] == 0 and log.report["records"]["FLASER"] == 910


def test_log_arrays_are_views(intel):
    log = pgmcl.read_carmen(intel / "raw.log.gz")
    for name in ("ranges", "stamps", "odometry", "range_max", "has_odometry", "usable"):
        a, b = getattr(log, name), getattr(log, name)
        assert np.shares_memory(a, b), name
        assert not a.flags.owndata and not a.flags.writeable, name
    # 4 scans of the raw log are stamped before their predecessor: localize skips them.
    assert log.usable.sum() == len(log) - 4 and np.all(np.diff(log.stamps[log.usable]) >= 0)
    scan = log.scan(3)
    assert np.array_equal(scan["ranges"], log.ranges[3])
    assert scan["odom"] == tuple(log.odometry[3]) and scan["stamp"] == log.stamps[3]


@pytest.fixture(scope="module")
def intel_run(intel, tmp_path_factory):
    """The README's run: defaults, truth at the first scan, seed 1; and the same on the
    command line."""
    out = tmp_path_factory.mktemp("cli")
    run_cli("localize", "--map", intel / "map.yaml", "--log", intel / "raw.log.gz",
            "--truth", intel / "truth.tum", "--relations", INTEL_RELATIONS,
            "--time-offset", INTEL_OFFSET, "--seed", 1, "--out", out, "--quiet")
    with pytest.warns(RuntimeWarning, match="skipped 4 scan"):
        run = pgmcl.localize(intel / "map.yaml", intel / "raw.log.gz",
                             truth=intel / "truth.tum", relations=INTEL_RELATIONS,
                             time_offset=INTEL_OFFSET, seed=1)
    return run, out


def test_localize_tracks_the_intel_case(intel_run):
    run, _ = intel_run
    m = run.metrics
    # The front page reports 0.031 m for intel; defaults with KLD here, a bound with margin.
    assert m["ate_rmse_m"] < 0.06 and m["ate_max_m"] < 0.3
    assert m["heading_rmse_deg"] < 1.5 and m["lock_on_s"] == 0.0
    assert m["relations_used"] > 100 and m["relations_trans_m"] < 0.1
    assert run.complete and run.start.startswith("ground truth at the first scan")
    assert run.trajectory.shape == (m["truth_matched"], 4)
    assert run.errors.shape == (m["truth_matched"], 3)
    assert np.sqrt(np.mean(run.errors[:, 1] ** 2)) == pytest.approx(m["ate_rmse_m"])
    assert run.config["seed"] == 1


def test_metrics_are_metrics_yaml(intel_run):
    run, out = intel_run
    cli = read_metrics_yaml(out / "metrics.yaml")
    assert list(run.metrics) == list(cli)  # same keys, same order
    timing = {"update_ms_mean", "update_ms_p95", "update_ms_median", "update_ms_max", "wall_s"}
    for key, value in run.metrics.items():
        if key in timing:
            continue
        if value is None:
            assert cli[key] is None, key
        else:
            assert float(f"{value:.6g}") == cli[key], key  # metrics.yaml writes %.6g
    assert isinstance(run.metrics["updates"], int) and isinstance(run.metrics["fit_mean"], float)


def test_run_arrays_are_views_and_match_the_cli(intel_run):
    run, out = intel_run
    t1, t2 = run.trajectory, run.trajectory
    assert np.shares_memory(t1, t2) and not t1.flags.owndata and not t1.flags.writeable
    assert np.shares_memory(run.errors, run.errors)
    assert np.shares_memory(run.particles, run.particles)
    assert run.weights.sum() == pytest.approx(1.0) and len(run.weights) == len(run.particles)
    cli = pgmcl.read_tum(out / "trajectory.tum")
    assert np.array_equal(cli[:, :3], run.trajectory[:, :3])
    u = run.updates
    assert len(u["stamp"]) == len(run.trajectory)
    assert np.array_equal(u["x"], run.trajectory[:, 1])
    assert set(u["skipped"]) <= {None, "not_moved", "no_valid_beams"}
    assert u["converged"].dtype == bool and u["particles"].min() >= 1000  # KLD's lower bound
    header = (out / "updates.csv").read_text().splitlines()[0].split(",")
    assert list(u) == [c for c in header if c not in ("error_m", "error_deg")]
    assert u["rotation_noise_factor"].min() >= 1.0 and u["translation_noise_factor"].min() >= 1.0
    assert u["rotation_noise_factor"][-1] == pytest.approx(run.metrics["rotation_noise_factor"])


def test_evaluate_from_arrays_and_files_equals_pgmcl_eval(intel, intel_run, tmp_path):
    run, out = intel_run
    truth = pgmcl.read_tum(intel / "truth.tum")
    a = pgmcl.evaluate(run.trajectory, truth)
    b = pgmcl.evaluate(out / "trajectory.tum", intel / "truth.tum")
    run_cli("eval", "--estimate", out / "trajectory.tum", "--truth", intel / "truth.tum",
            "--out", tmp_path / "eval.yaml")
    cli = read_metrics_yaml(tmp_path / "eval.yaml")
    assert list(a.metrics) == list(cli)
    for key in cli:
        assert float(f"{b.metrics[key]:.6g}") == cli[key], key
        assert a.metrics[key] == pytest.approx(b.metrics[key], abs=1e-9), key
    assert a.metrics["ate_rmse_m"] == pytest.approx(run.metrics["ate_rmse_m"], abs=1e-12)
    # Oracles: truth against itself, and moved by 0.1 m.
    assert pgmcl.evaluate(truth, truth).metrics["ate_rmse_m"] == 0.0
    moved = truth.copy()
    moved[:, 1] += 0.1
    e = pgmcl.evaluate(moved, truth)
    assert e.metrics["ate_rmse_m"] == pytest.approx(0.1) and e.metrics["ate_max_m"] == pytest.approx(0.1)
    assert e.matched == len(truth) and np.allclose(e.errors[:, 1], 0.1)
    rel = pgmcl.evaluate(truth, truth, relations=INTEL_RELATIONS, time_offset=INTEL_OFFSET)
    assert rel.metrics["relations_used"] > 100


def test_tum_round_trip_is_exact(tmp_path):
    t = np.array([[1.5, 0.1, -2.25, 0.3], [2.0, 1e-7, 3.0, -3.0]])
    pgmcl.write_tum(tmp_path / "t.tum", t)
    back = pgmcl.read_tum(tmp_path / "t.tum")
    assert np.array_equal(back[:, :3], t[:, :3]) and np.allclose(back[:, 3], t[:, 3], atol=1e-15)


def test_simulate_and_localize_a_scenario():
    lab = REPO / "configs" / "scenarios" / "lab.yaml"
    sim = pgmcl.simulate(lab, duration=15.0)
    assert sim.name == "lab" and len(sim.log) == len(sim.truth) > 100
    assert sim.log.ranges.shape[1] == 1081  # the UTM-30LX
    assert np.array_equal(sim.log.stamps, sim.truth[:, 0])
    again = pgmcl.simulate(lab, duration=15.0)
    assert np.array_equal(again.log.ranges, sim.log.ranges)  # deterministic for a seed
    other = pgmcl.simulate(lab, duration=15.0, seed=12)
    assert not np.array_equal(other.log.ranges, sim.log.ranges)
    run = pgmcl.localize(sim.map, sim.log, truth=sim.truth, seed=1)
    assert run.metrics["ate_rmse_m"] < 0.05 and run.complete


def test_ctrl_c_stops_a_run_with_keyboard_interrupt(intel):
    # 20000 particles without KLD: about 10 ms per update, some 10 s for the log; the run
    # looks for signals every 64 updates.
    heavy = {"filter.particles": 20000, "filter.kld.enabled": False}
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            pgmcl.localize(intel / "map.yaml", intel / "raw.log.gz", truth=intel / "truth.tum",
                           config=heavy)
    finally:
        timer.cancel()
