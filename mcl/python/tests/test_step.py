"""The step API: pgmcl.Localizer fed scan by scan gives the trajectory of the C++ engine
(`pgmcl localize`, trajectory.tum) for the same config and seed, and its results carry the
engine's fields."""

import numpy as np
import pytest

import pgmcl
from conftest import run_cli

SIGMA = (0.25, 0.25, 0.1)  # pgmcl localize --init X,Y,THETA's default spread (m, m, rad)


def step_through(loc, log):
    """Feeds every scan with odometry in time order, as pgmcl::replay does."""
    rows, results = [], []
    for i in np.flatnonzero(log.usable):
        r = loc.update(**log.scan(i))
        rows.append((log.stamps[i],) + r.estimate)
        results.append(r)
    return np.array(rows), results


@pytest.fixture(scope="module")
def stepped(intel):
    """The Intel case stepped from Python with a non-default config, seed 5, one thread."""
    config = pgmcl.Config({"filter.particles": 800, "likelihood.selection.max_beams": 90,
                           "motion.noise": {"a1": 0.01, "a3": 0.01}, "seed": 5})
    log = pgmcl.read_carmen(intel / "raw.log.gz")
    start = tuple(float(v) for v in pgmcl.read_tum(intel / "truth.tum")[0, 1:])
    loc = pgmcl.Localizer(intel / "map.yaml", config)
    loc.set_pose(start, np.diag(np.square(SIGMA)))
    trajectory, results = step_through(loc, log)
    return config, start, trajectory, results, loc


def test_same_trajectory_as_pgmcl_localize_for_the_same_seed(intel, tmp_path, stepped):
    config, start, trajectory, _, _ = stepped
    config.save(tmp_path / "filter.yaml")
    # Two threads on the command line: one seed gives one trajectory for any thread count.
    run_cli("localize", "--map", intel / "map.yaml", "--log", intel / "raw.log.gz",
            "--config", tmp_path / "filter.yaml", "--init", ",".join(repr(v) for v in start),
            "--threads", "2", "--out", tmp_path / "cli", "--quiet")
    cli = pgmcl.read_tum(tmp_path / "cli" / "trajectory.tum")
    assert cli.shape == trajectory.shape and len(cli) > 900
    # TUM keeps stamps and positions exactly (shortest round-trip text); the heading goes
    # through a quaternion.
    assert np.array_equal(cli[:, :3], trajectory[:, :3])
    assert np.max(np.abs(np.angle(np.exp(1j * (cli[:, 3] - trajectory[:, 3]))))) < 1e-12


def test_same_trajectory_as_localize_in_memory(intel, stepped):
    config, start, trajectory, _, _ = stepped
    with pytest.warns(RuntimeWarning, match="skipped 4 scan"):
        # seed=None keeps the config's seed 5 instead of localize's default 1.
        run = pgmcl.localize(intel / "map.yaml", intel / "raw.log.gz", init=start,
                             config=config, seed=None)
    assert np.array_equal(run.trajectory, trajectory)  # bit for bit


def test_results_carry_the_engines_fields(stepped):
    config, _, trajectory, results, loc = stepped
    skipped = {r.skipped for r in results}
    assert None in skipped and skipped <= {None, "not_moved", "no_valid_beams"}
    full = [r for r in results if r.skipped is None]
    assert all(r.measured and r.beams_used == 90 and r.beams_total == 180 for r in full)
    assert np.mean([r.converged for r in full]) > 0.95
    assert all(0.0 <= r.fit <= 1.0 for r in full) and np.mean([r.fit for r in full]) > 0.9
    assert all(isinstance(r.alternative_evidence, float) for r in full)
    last = full[-1]
    assert last.covariance.shape == (3, 3) and np.allclose(last.covariance, last.covariance.T)
    assert set(last.timings) == {"motion_ms", "measurement_ms", "hypotheses_ms", "free_space_ms",
                                 "resample_ms", "estimate_ms", "total_ms"}
    assert 0 <= last.timings["hypotheses_ms"] <= last.timings["measurement_ms"]
    assert 0 <= last.timings["free_space_ms"] <= last.timings["measurement_ms"]
    assert 0 < last.n_eff <= last.particles
    poses, weights = loc.particles()
    assert poses.shape == (loc.last_result.particles, 3) and weights.shape == (len(poses),)
    assert weights.sum() == pytest.approx(1.0)
    # The cloud sits around the estimate.
    assert np.hypot(*(np.average(poses[:, :2], axis=0, weights=weights) -
                      loc.last_result.estimate[:2])) < 0.2
    assert loc.config == config


def test_set_pose_draws_the_given_gaussian_and_global_localize_spreads():
    cells = np.zeros((100, 100), np.int8)
    cells[[0, -1], :] = cells[:, [0, -1]] = 100
    loc = pgmcl.Localizer(pgmcl.Map(cells, 0.1), {"filter.particles": 20000, "seed": 3})
    cov = np.diag([0.01, 0.04, 0.0025])
    loc.set_pose((4.0, 5.0, 0.3), cov)
    poses, _ = loc.particles()
    assert len(poses) == 20000
    assert poses.mean(axis=0) == pytest.approx([4.0, 5.0, 0.3], abs=0.01)
    assert np.cov(poses.T) == pytest.approx(cov, abs=0.0015)
    loc.global_localize()
    poses, weights = loc.particles()
    assert len(poses) == loc.config["filter.global_particles"]
    assert np.all((poses[:, :2] > 0.1) & (poses[:, :2] < 9.9)) and poses[:, 0].std() > 2.5


def test_skip_reasons():
    cells = np.zeros((60, 60), np.int8)
    cells[[0, -1], :] = cells[:, [0, -1]] = 100
    loc = pgmcl.Localizer(pgmcl.Map(cells, 0.1), pgmcl.Config(seed=1))
    loc.set_pose((3.0, 3.0, 0.0), np.diag([0.01, 0.01, 0.001]))
    scan = dict(angle_min=-np.pi / 2, angle_increment=np.pi / 179, range_max=30.0)
    ranges = np.full(180, 2.9, np.float32)
    assert loc.update((0, 0, 0), ranges, stamp=0.0, **scan).skipped is None
    assert loc.update((0.01, 0, 0), ranges, stamp=0.1, **scan).skipped == "not_moved"
    nothing = np.full(180, np.nan, np.float32)
    r = loc.update((0.5, 0, 0), nothing, stamp=0.2, **scan)
    assert (r.skipped, r.beams_invalid, r.beams_used) == ("no_valid_beams", 180, 0)
