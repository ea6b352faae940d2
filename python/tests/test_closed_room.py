"""The exact oracle of a closed scene: in a room with a box inside it every ray from a front side
ends on a front side, the visible form factors at each collocation point sum to 1, and with
E = c (1 - rho) the collocation system (I - K) u = E has the solution u = c exactly, for any rho
per facet.

Bound (tests/solve/test_occluded_oracle.cpp): the row sums of H are 1 up to the rounding of the
closed-form factors over clipped polygons (~1e-14 each) and the slivers of relative size 1e-12
the shadow tests drop, far below 1e-10 over n <= 1024 entries; with rho <= 0.7 the error is
below c * 0.7e-10 / 0.3 = 2.4e-10 c, and the iteration's tolerance 1e-13 adds at most 1e-13/0.3.
So max |u_i - c| / c < 1e-9.
"""
import numpy as np
import pytest

import panelrad
from conftest import room_with_box


@pytest.fixture(scope="module")
def room():
    v, t, f = room_with_box()
    rho = np.linspace(0.2, 0.7, 12, endpoint=False)  # varies by facet: a wrong row cannot hide
    c = 3.5
    scene = panelrad.Scene(v, t, rho=rho, E=c * (1 - rho), facets=f)
    return scene, c


def test_scene_is_general_and_closed(room):
    scene, _ = room
    assert scene.shape == "general"
    assert scene.closed
    assert scene.num_facets == 12


@pytest.mark.parametrize("level", [1, 2])
def test_constant_solution(room, level):
    scene, c = room
    solver = panelrad.Solver(scene, level=level, method="dense", tolerance=1e-13)
    assert solver.info["visibility"] == "occluded"
    (result,) = solver.solve()
    result.require_converged()
    assert np.max(np.abs(result.u - c)) / c < 1e-9
    # The same from per-element data: solve(rho, E) with the solver's own values.
    rho, E = solver.channel_values(0)
    other = solver.solve(rho, E)
    np.testing.assert_array_equal(other.u, result.u)


def test_energy_balance_of_solve_scene(room):
    scene, c = room
    solution = panelrad.solve_scene(scene, level=1, method="dense", tolerance=1e-13)
    solution.require_converged()
    ch = solution["value"]
    assert np.max(np.abs(ch.radiosity - c)) / c < 1e-9
    # Closed scene: emitted = absorbed up to the same bound.
    assert ch.energy_mismatch < 1e-9
    assert solution.closed
