"""The GIL is released while the filter works: two Python threads, each with its own
Localizer, both progress at once, and each gets the trajectory it gets alone."""

import itertools
import sys
import threading

import numpy as np
import pytest

import pgmcl

UPDATES = 8  # per thread
# Heavy updates (a global start with 50000 particles: 30..150 ms each) so that a thread
# woken when the other releases the GIL surely runs while that one is still inside.
HEAVY = {"filter.global_particles": 50000, "filter.particles": 50000,
         "filter.kld.enabled": False}


def scans(log, count=UPDATES):
    return [log.scan(i) for i in range(count)]


def serial(m, log, seed):
    loc = pgmcl.Localizer(m, dict(HEAVY, seed=seed))
    return np.array([loc.update(**s).estimate for s in scans(log)])


@pytest.fixture(scope="module")
def case(intel):
    return pgmcl.load_map(intel / "map.yaml"), pgmcl.read_carmen(intel / "raw.log.gz")


def test_two_localizers_progress_at_once(case):
    m, log = case
    tickets = itertools.count()  # next() is atomic under the GIL
    spans = {1: [], 2: []}
    estimates = {1: [], 2: []}
    localizers = {seed: pgmcl.Localizer(m, dict(HEAVY, seed=seed)) for seed in spans}

    def work(seed):
        loc = localizers[seed]
        for s in scans(log):
            start = next(tickets)
            estimates[seed].append(loc.update(**s).estimate)
            spans[seed].append((start, next(tickets)))

    # With a switch interval of 1000 s, Python never takes the GIL from a running thread:
    # it changes hands only where C++ releases it. Had update() kept it, the first thread
    # would run its whole loop alone and no update of one would overlap one of the other.
    interval = sys.getswitchinterval()
    sys.setswitchinterval(1000.0)
    try:
        threads = [threading.Thread(target=work, args=(seed,)) for seed in spans]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
    finally:
        sys.setswitchinterval(interval)

    def overlapped(a, b):  # updates of `a` during which `b` took a ticket
        taken = sorted(t for span in spans[b] for t in span)
        return sum(any(s < t < e for t in taken) for s, e in spans[a])

    assert len(spans[1]) == len(spans[2]) == UPDATES  # both finished
    assert overlapped(1, 2) >= 1 and overlapped(2, 1) >= 1
    for seed in spans:  # and neither disturbed the other
        assert np.array_equal(np.array(estimates[seed]), serial(m, log, seed))


def test_localize_in_two_threads_gives_the_serial_runs(case, quiet):
    m, log = case
    alone = [pgmcl.localize(m, log, seed=s).trajectory for s in (1, 2)]
    out = {}
    threads = [threading.Thread(target=lambda s=s: out.__setitem__(s, pgmcl.localize(m, log, seed=s)))
               for s in (1, 2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert np.array_equal(out[1].trajectory, alone[0])
    assert np.array_equal(out[2].trajectory, alone[1])


def test_one_localizer_shared_by_two_threads_serialises(case):
    m, log = case
    loc = pgmcl.Localizer(m, {"seed": 3})
    loc.set_pose(tuple(log.poses[0]), np.diag([0.01, 0.01, 0.001]))
    errors = []

    def poke():
        try:
            for _ in range(200):
                loc.particles()
                loc.force_update()
        except Exception as e:  # pragma: no cover - reported below
            errors.append(e)

    t = threading.Thread(target=poke)
    t.start()
    for s in scans(log, 150):
        loc.update(**s)
    t.join()
    assert not errors and loc.last_result.converged
