"""Shared fixtures: the built `pgmcl` binary, the repository, and the Intel case made from
the bundled log exactly as cmake/demo.sh makes it (once per pytest session)."""

import os
import pathlib
import subprocess
import sys
import warnings

import pytest

REPO = pathlib.Path(os.environ.get("PGMCL_SOURCE_DIR",
                                   pathlib.Path(__file__).resolve().parents[3]))
PGMCL_BIN = os.environ.get("PGMCL_BIN", str(REPO / "build" / "release" / "pgmcl"))

sys.path.insert(0, str(REPO / "mcl" / "python" / "examples"))
from intel_localize import make_intel_case  # noqa: E402  (the example's own recipe)


def run_cli(*args, check=True):
    """Runs the pgmcl binary; returns (exit code, stdout, stderr)."""
    p = subprocess.run([PGMCL_BIN] + [str(a) for a in args], capture_output=True, text=True)
    if check and p.returncode != 0:
        raise AssertionError(f"pgmcl {' '.join(map(str, args))} failed:\n{p.stderr}")
    return p.returncode, p.stdout, p.stderr


def cli_error(*args):
    """The message `pgmcl` prints after 'pgmcl: error: ' for a command that must fail."""
    code, _, err = run_cli(*args, check=False)
    assert code != 0, f"pgmcl {args} should have failed"
    line = [l for l in err.splitlines() if l.startswith("pgmcl: error: ")]
    assert line, err
    return line[-1][len("pgmcl: error: "):]


@pytest.fixture(scope="session")
def repo():
    return REPO


@pytest.fixture(scope="session")
def intel(tmp_path_factory):
    """map.yaml, raw.log.gz (seeded realistic odometry) and truth.tum of the Intel log."""
    return make_intel_case(PGMCL_BIN, tmp_path_factory.mktemp("intel"))


@pytest.fixture
def quiet():
    """Silences pgmcl's RuntimeWarnings (the Intel log has 4 scans out of order)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        yield
