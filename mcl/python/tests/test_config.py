"""pgmcl.Config and load_config against the command line: the same fields (the schema),
the same YAML after the same overrides, the same error messages with the field path."""

import copy

import pytest

import pgmcl
from conftest import cli_error, run_cli, REPO


def flat(d, prefix=""):
    for k, v in d.items():
        if isinstance(v, dict):
            yield from flat(v, prefix + k + ".")
        else:
            yield prefix + k, v


def test_every_field_of_the_reference_and_nothing_else():
    keys = pgmcl.Config().keys()
    reference = (REPO / "configs" / "reference.md").read_text()
    listed = [line.split("`")[1] for line in reference.splitlines() if line.startswith("| `")]
    assert keys == listed  # the schema's order; configs/reference.md is its output
    assert [k for k, _ in flat(pgmcl.Config().to_dict())] == keys
    assert pgmcl.Config.reference() == run_cli("config", "--reference")[1]


def test_defaults_and_types_are_the_structs():
    c = pgmcl.Config().to_dict()
    assert c["filter"]["particles"] == 2000 and c["seed"] == 42 and c["threads"] == 1
    assert c["motion"]["kind"] == "differential_drive"
    assert c["filter"]["kld"]["enabled"] is True
    assert isinstance(c["likelihood"]["beam"]["sigma_along"], float)
    assert isinstance(c["likelihood"]["table"]["max_table_bytes"], int)


OVERRIDES = {
    "filter.kld.max_particles": 5000,
    "likelihood.table.kind": "oriented",
    "gating.enabled": False,
    "motion.noise.a1": 0.0123,
    "seed": 7,
}


def test_overrides_give_the_yaml_of_pgmcl_config_set():
    sets = [a for k, v in OVERRIDES.items()
            for a in ("--set", f"{k}={str(v).lower() if isinstance(v, bool) else v}")]
    cli_yaml = run_cli("config", *sets)[1]
    assert pgmcl.Config(OVERRIDES).to_yaml() == cli_yaml
    assert pgmcl.Config(**OVERRIDES).to_yaml() == cli_yaml
    nested = pgmcl.Config(filter={"kld": {"max_particles": 5000}},
                          likelihood={"table": {"kind": "oriented"}}, gating={"enabled": False},
                          motion={"noise": {"a1": 0.0123}}, seed=7)
    assert nested == pgmcl.Config(OVERRIDES)
    assert nested["filter.kld.max_particles"] == 5000 and nested["likelihood.table.kind"] == "oriented"


def test_yaml_round_trip_and_load_config(tmp_path):
    c = pgmcl.Config(OVERRIDES)
    c.save(tmp_path / "c.yaml")
    assert pgmcl.load_config(tmp_path / "c.yaml") == c
    assert pgmcl.load_config(tmp_path / "c.yaml", {"seed": 8})["seed"] == 8
    tracking = REPO / "configs" / "filters" / "tracking.yaml"
    assert pgmcl.load_config(tracking).to_yaml() == run_cli("config", "--config", tracking)[1]


def test_setitem_update_and_copy_validate_like_set():
    c = pgmcl.Config()
    c["filter.particles"] = 500
    d = copy.deepcopy(c)
    d["filter.particles"] = 600
    assert (c["filter.particles"], d["filter.particles"]) == (500, 600)
    with pytest.raises(pgmcl.InputError):
        c.update({"filter.particles": 700, "filter.kld.epsilon": -1.0})
    assert c["filter.particles"] == 500  # all or nothing
    with pytest.raises(KeyError):
        c["filter.nope"]
    assert repr(pgmcl.Config(seed=3)) == "pgmcl.Config({'seed': 3})"


@pytest.mark.parametrize("key, value", [
    ("filter.particles", 0),             # out of range
    ("filter.particle", 5),              # unknown key: the nearest one is suggested
    ("likelihood.table.kind", "round"),  # bad enumeration name
    ("filter.kld.min_particles", 30000), # a rule across fields
    ("gating.d_min", "abc"),             # not a number
    ("motion.noise.a1", float("inf")),   # not finite
])
def test_errors_are_the_command_lines(key, value):
    text = {float("inf"): ".inf"}.get(value, value)
    expected = cli_error("config", "--set", f"{key}={text}")
    with pytest.raises(pgmcl.InputError) as e:
        pgmcl.Config({key: value})
    assert str(e.value) == expected
    assert isinstance(e.value, ValueError)
    assert e.value.file == f"--set {key}={text}" and e.value.line == 0
    assert e.value.field and e.value.field.split(".")[0] == key.split(".")[0]


def test_file_errors_name_file_line_and_key(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("filter:\n  particles: 100\n  kld:\n    epsilon: -2\n")
    with pytest.raises(pgmcl.InputError) as e:
        pgmcl.load_config(bad)
    assert str(e.value) == cli_error("config", "--config", bad)
    assert (e.value.file, e.value.line, e.value.field) == (str(bad), 4, "filter.kld.epsilon")


def test_wrong_python_types_and_missing_files():
    with pytest.raises(TypeError, match="filter.particles"):
        pgmcl.Config({"filter.particles": None})
    with pytest.raises(TypeError):
        pgmcl.Config(["filter.particles"])
    with pytest.raises(FileNotFoundError) as e:
        pgmcl.load_config("no/such/config.yaml")
    assert e.value.filename == "no/such/config.yaml"
