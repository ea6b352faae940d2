"""panelrad: the radiosity equation u - K u = E on polyhedral scenes.

Centroid collocation (section 3) with the dense matrix or the fast matrix-vector product of
section 4 of K. Atkinson and D. Chien, "A fast matrix-vector multiplication method for solving
the radiosity equation", Adv. Comput. Math. 12 (2000). The compiled module is panelrad._panelrad;
everything is re-exported here. See docs/python.md.

Every exception the module raises is a panelrad.Error. The functions and methods check their
keyword arguments here first: an unknown keyword is an ArgumentTypeError (a TypeError) naming it,
with the closest accepted one and the list of all of them; arguments of the wrong type, which
pybind11 reports, become an ArgumentTypeError too.
"""
import difflib
import functools
import re

from . import _panelrad
from ._panelrad import (
    ArgumentError,
    ArgumentTypeError,
    ChannelError,
    ChannelSolution,
    EnergyBalanceError,
    Error,
    MeshError,
    Operator,
    ResourceError,
    Scene,
    SceneFileError,
    Solution,
    SolveResult,
    Solver,
    SolverError,
    TextFileError,
    ThermalSolution,
    __version__,
    load_scene,
    max_threads,
    paper_cube,
    set_threads,
    solve_scene,
    thermal_solve,
    view_factors,
    ViewFactors,
    write_outputs,
)

_CLASSES = ("ArgumentError", "ArgumentTypeError", "ChannelError", "ChannelSolution", "EnergyBalanceError", "Error", "MeshError", "Operator",
            "ResourceError", "Scene", "SceneFileError", "Solution", "SolveResult", "Solver", "SolverError",
            "TextFileError", "ThermalSolution", "ViewFactors")
_FUNCTIONS = ("load_scene", "max_threads", "paper_cube", "set_threads", "solve_scene", "thermal_solve", "view_factors",
              "write_outputs")
# The methods that take arguments (properties take none); __init__ is each class's constructor.
_METHODS = {
    "Scene": ("__init__", "set_reflectivity", "set_emission", "set_environment", "reflectivity", "emission",
              "environment"),
    "Solver": ("__init__", "solve", "max_error", "channel_values", "irradiance"),
    "Operator": ("matvec", "matmat", "__matmul__"),
    "Solution": ("__getitem__",),
    "ViewFactors": ("write",),
    "ThermalSolution": ("write",),
}

# A parameter of a pybind11 signature line: its name, before ": type" (and "= default").
_SIGNATURE = re.compile(r"^(?:\d+\. )?\w+\((.*)\) -> ", re.MULTILINE)


def _parameters(signature):
    """The names in a pybind11 parameter list, split at the commas outside brackets and quotes."""
    names, depth, quote, start = [], 0, None, 0
    for i, c in enumerate(signature + ","):
        if quote:
            quote = None if c == quote else quote
        elif c in "'\"":
            quote = c
        elif c in "([{<":
            depth += 1
        elif c in ")]}>":
            depth -= 1
        elif c == "," and depth == 0:
            name = signature[start:i].split(":")[0].split("=")[0].strip()
            if name and name not in ("*", "/", "self"):
                names.append(name)
            start = i + 1
    return names


def _keywords(function):
    """The keyword names of every overload of a pybind11 function, in order, from its signatures."""
    names = []
    for found in _SIGNATURE.finditer(function.__doc__ or ""):
        names += [n for n in _parameters(found[1]) if n not in names]
    return names


def _suggestion(name, accepted):
    """The accepted keyword `name` most likely means: one it begins or abbreviates, else the closest."""
    starts = [a for a in accepted if a.startswith(name) or name.startswith(a)]
    close = difflib.get_close_matches(name, accepted, n=1, cutoff=0.4)
    best = starts[:1] or close
    return f" (did you mean '{best[0]}'?)" if best else ""


def _checked(function, shown):
    """`function` with its keyword arguments checked by name first, and pybind11's TypeError for
    arguments of the wrong type raised as an ArgumentTypeError."""
    accepted = _keywords(function)

    @functools.wraps(function)
    def call(*args, **kwargs):
        unknown = [k for k in kwargs if k not in accepted]
        if unknown:
            bad = unknown[0]
            raise ArgumentTypeError(f"{shown}: unexpected keyword argument '{bad}'{_suggestion(bad, accepted)}; "
                                    f"the keywords are: {', '.join(accepted)}")
        try:
            return function(*args, **kwargs)
        except TypeError as e:
            if isinstance(e, Error) or "incompatible" not in str(e):
                raise
            raise ArgumentTypeError(f"{shown}: an argument of the wrong type ({str(e).strip()})") from None

    return call


for _name in _FUNCTIONS:
    globals()[_name] = _checked(getattr(_panelrad, _name), _name + "()")
for _class, _methods in _METHODS.items():
    for _method in _methods:
        _shown = _class + "()" if _method == "__init__" else f"{_class}.{_method}()"
        setattr(globals()[_class], _method, _checked(getattr(globals()[_class], _method), _shown))
# The classes print as panelrad.Scene, panelrad.MeshError, ... (defined in panelrad._panelrad).
for _name in _CLASSES:
    globals()[_name].__module__ = __name__
del _name, _class, _methods, _method, _shown

__all__ = [
    "ArgumentError",
    "ArgumentTypeError",
    "ChannelError",
    "ChannelSolution",
    "EnergyBalanceError",
    "Error",
    "MeshError",
    "Operator",
    "ResourceError",
    "Scene",
    "SceneFileError",
    "Solution",
    "SolveResult",
    "Solver",
    "SolverError",
    "TextFileError",
    "ThermalSolution",
    "ViewFactors",
    "__version__",
    "load_scene",
    "max_threads",
    "paper_cube",
    "set_threads",
    "solve_scene",
    "thermal_solve",
    "view_factors",
    "write_outputs",
]
