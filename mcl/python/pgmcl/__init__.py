"""pgmcl: Monte Carlo localisation for 2D laser rangefinders from Python.

The engine (Localizer), whole runs (localize, simulate, evaluate), maps, configs and log
files, with numpy arrays in and out. The API is listed in mcl/python/README.md; every
function and class has a docstring (help(pgmcl.localize)).
"""

from ._core import (
    Config,
    Evaluation,
    InputError,
    Localizer,
    Log,
    Map,
    Run,
    Simulation,
    UpdateResult,
    __version__,
    evaluate,
    load_config,
    load_map,
    localize,
    read_carmen,
    read_tum,
    save_map,
    simulate,
    write_tum,
)

__all__ = [
    "Config",
    "Evaluation",
    "InputError",
    "Localizer",
    "Log",
    "Map",
    "Run",
    "Simulation",
    "UpdateResult",
    "evaluate",
    "load_config",
    "load_map",
    "localize",
    "read_carmen",
    "read_tum",
    "save_map",
    "simulate",
    "write_tum",
]

# Show the classes as pgmcl.X rather than pgmcl._core.X (reprs, help(), tracebacks).
for _name in __all__:
    _obj = globals()[_name]
    if isinstance(_obj, type):
        _obj.__module__ = __name__
del _name, _obj
