"""Errors reach Python as the exceptions a user expects, with the command line's messages:
FileNotFoundError for missing files, InputError (a ValueError) naming file, line and field
for bad input, ValueError for bad arguments, OSError for files that cannot be written."""

import gzip

import numpy as np
import pytest

import pgmcl
from conftest import cli_error, REPO


@pytest.mark.parametrize("call", [
    lambda p: pgmcl.load_map(p),
    lambda p: pgmcl.read_carmen(p),
    lambda p: pgmcl.read_tum(p),
    lambda p: pgmcl.load_config(p),
    lambda p: pgmcl.simulate(p),
    lambda p: pgmcl.Localizer(p),
    lambda p: pgmcl.evaluate(p, np.zeros((1, 4))),
])
def test_missing_files_raise_file_not_found(call, tmp_path):
    missing = str(tmp_path / "missing.yaml")
    with pytest.raises(FileNotFoundError) as e:
        call(missing)
    assert e.value.filename == missing


def test_missing_log_and_truth_in_localize(intel, tmp_path):
    with pytest.raises(FileNotFoundError):
        pgmcl.localize(intel / "map.yaml", tmp_path / "no.log")
    with pytest.raises(FileNotFoundError):
        pgmcl.localize(intel / "map.yaml", intel / "raw.log.gz", truth=tmp_path / "no.tum")


def test_a_map_yaml_naming_a_missing_image(tmp_path):
    (tmp_path / "m.yaml").write_text("image: gone.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n"
                                     "occupied_thresh: 0.65\nfree_thresh: 0.196\nnegate: 0\n")
    with pytest.raises(FileNotFoundError) as e:
        pgmcl.load_map(tmp_path / "m.yaml")
    assert e.value.filename == str(tmp_path / "gone.pgm")


def test_bad_map_yaml_is_the_cli_message(intel, tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text((intel / "map.yaml").read_text().replace("resolution: 0.05",
                                                            "resolution: -1"))
    (tmp_path / "map.pgm").write_bytes((intel / "map.pgm").read_bytes())
    with pytest.raises(pgmcl.InputError) as e:
        pgmcl.load_map(bad)
    assert e.value.field == "resolution" and e.value.line > 0 and e.value.file == str(bad)
    assert str(e.value) == cli_error("localize", "--map", bad, "--log", intel / "raw.log.gz")


def test_save_into_a_missing_folder_is_an_os_error(tmp_path):
    m = pgmcl.Map(np.zeros((4, 4), np.int8), 0.1)
    with pytest.raises(OSError):
        m.save(tmp_path / "no" / "such" / "m.yaml")
    with pytest.raises(OSError):
        pgmcl.Config().save(tmp_path / "no" / "c.yaml")


def test_malformed_log_lines_warn_or_raise_with_file_and_line(tmp_path):
    text = gzip.open(REPO / "data" / "logs" / "intel-corrected.log.gz", "rt").read()
    flaser = [line for line in text.splitlines() if line.startswith("FLASER")][:20]
    flaser[6] = "FLASER 180 1.0 2.0"  # far too short: line 7
    bad = tmp_path / "bad.log"
    bad.write_text("\n".join(flaser) + "\n")
    with pytest.warns(RuntimeWarning, match=r"dropped 1 malformed line.*bad.log:7: "):
        log = pgmcl.read_carmen(bad)
    assert len(log) == 19 and log.report["malformed"] == 1
    assert log.report["malformed_lines"][0][:2] == (7, "FLASER")
    with pytest.raises(pgmcl.InputError) as e:
        pgmcl.read_carmen(bad, strict=True)
    assert (e.value.file, e.value.line) == (str(bad), 7)
    willow = REPO / "data" / "maps" / "willow" / "willow-full-0.05.yaml"
    assert str(e.value) == cli_error("localize", "--map", willow, "--log", bad, "--strict")


def test_bad_tum_line(tmp_path):
    (tmp_path / "t.tum").write_text("1 0 0 0 0 0 0 1\n2 0 0 0 0 0 nan 1\n")
    with pytest.raises(pgmcl.InputError) as e:
        pgmcl.read_tum(tmp_path / "t.tum")
    assert e.value.line == 2


def test_step_api_argument_errors(intel):
    loc = pgmcl.Localizer(intel / "map.yaml", {"filter.global_particles": 1000})
    scan = dict(angle_min=-1.5, angle_increment=0.01, stamp=1.0)
    with pytest.raises(ValueError, match="^Localizer::update: "):
        loc.update((np.nan, 0, 0), np.ones(10), **scan)
    with pytest.raises(ValueError, match="^Localizer::update: "):
        loc.update((0, 0, 0), np.ones(10), **dict(scan, angle_increment=np.inf))
    with pytest.raises(ValueError, match="1-D"):
        loc.update((0, 0, 0), np.ones((2, 5)), **scan)
    with pytest.raises(TypeError, match=r"odom: expected \(x, y, theta\)"):
        loc.update((0, 0), np.ones(10), **scan)
    with pytest.raises(ValueError, match="set_pose"):
        loc.set_pose((0, 0, 0), np.array([[1.0, 0.5, 0], [0, 1, 0], [0, 0, 1]]))
    with pytest.raises(ValueError, match="3x3"):
        loc.set_pose((0, 0, 0), np.eye(2))
    assert loc.update((0, 0, 0), np.ones(10), **scan).skipped is None  # state unharmed


def test_run_errors_name_the_log_line_and_field(intel):
    # A scan the filter rejects: the replay names the log, its line and the message.
    with pytest.raises(pgmcl.InputError) as e:
        pgmcl.localize(intel / "map.yaml", intel / "raw.log.gz",
                       config={"likelihood.expected_beams": 100})
    assert e.value.file == str(intel / "raw.log.gz") and e.value.line > 0
    assert e.value.field == "FLASER" and "rejected by the filter" in e.value.problem
    with pytest.raises(pgmcl.InputError) as e:
        pgmcl.localize(intel / "map.yaml", intel / "raw.log.gz", threads=-1)
    assert e.value.field == "threads"
    with pytest.raises(ValueError, match="init"):
        pgmcl.localize(intel / "map.yaml", intel / "raw.log.gz", init="truth")  # no truth
    with pytest.raises(ValueError, match="init_sigma"):
        pgmcl.localize(intel / "map.yaml", intel / "raw.log.gz", init=(0, 0, 0),
                       init_sigma=(0.1, -1))


def test_a_log_without_odometry(intel, tmp_path):
    (tmp_path / "empty.log").write_text("# nothing\n")
    with pytest.raises(ValueError, match="no laser scan with odometry"):
        pgmcl.localize(intel / "map.yaml", tmp_path / "empty.log")


def test_bad_scenario_names_its_field(tmp_path):
    lab = (REPO / "configs" / "scenarios" / "lab.yaml").read_text()
    bad = tmp_path / "lab.yaml"
    bad.write_text(lab.replace("duration: 30.0", "duration: -3").replace(
        "map: ", f"map: {REPO / 'configs' / 'scenarios'}/"))
    with pytest.raises(pgmcl.InputError) as e:
        pgmcl.simulate(bad)
    assert e.value.field == "duration" and e.value.line == 10
    assert str(e.value) == cli_error("simulate", bad, "--out", tmp_path / "x.log")
