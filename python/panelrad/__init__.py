"""panelrad: the radiosity equation u - K u = E on polyhedral scenes.

Centroid collocation (section 3) with the dense matrix or the fast matrix-vector product of
section 4 of K. Atkinson and D. Chien, "A fast matrix-vector multiplication method for solving
the radiosity equation", Adv. Comput. Math. 12 (2000). The compiled module is panelrad._panelrad;
everything is re-exported here. See docs/python.md.
"""
from ._panelrad import (
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
    __version__,
    load_scene,
    max_threads,
    paper_cube,
    set_threads,
    solve_scene,
    write_outputs,
)

# The classes print as panelrad.Scene, panelrad.MeshError, ... (defined in panelrad._panelrad).
for _name in ("ChannelSolution", "EnergyBalanceError", "Error", "MeshError", "Operator", "ResourceError", "Scene", "SceneFileError",
              "Solution", "SolveResult", "Solver", "SolverError", "TextFileError"):
    globals()[_name].__module__ = __name__
del _name

__all__ = [
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
    "__version__",
    "load_scene",
    "max_threads",
    "paper_cube",
    "set_threads",
    "solve_scene",
    "write_outputs",
]
