"""solve_scene and write_outputs on the Cornell box (three channels, visibility computed)."""
import numpy as np
import pytest

import panelrad


@pytest.fixture(scope="module")
def cornell(source_dir):
    return panelrad.load_scene(source_dir / "examples" / "scenes" / "cornell_box.obj")


def test_cornell_box(cornell, tmp_path):
    solution = panelrad.solve_scene(cornell, max_elements=1000)
    solution.require_converged()
    assert len(solution) == 3 and solution.channel_names == ["R", "G", "B"]
    assert solution.visibility == "occluded"
    n = solution.n
    for ch in solution.channels:
        assert ch.radiosity.shape == (n,) and not ch.radiosity.flags.writeable
        assert np.all(ch.radiosity >= 0)
        # Radiosity is emission plus reflected light: u = E + rho H u, up to the stopping error.
        np.testing.assert_allclose(ch.radiosity, ch.E + ch.rho * ch.irradiance, rtol=1e-3, atol=1e-3 * ch.radiosity.max())
    assert solution.centroids.shape == (n, 3)
    # The same solve through Solver gives the same bits (one discretization, the same operator choice).
    solver = panelrad.Solver(cornell, max_elements=1000)
    results = solver.solve()
    for r, ch in zip(results, solution.channels):
        np.testing.assert_array_equal(r.u, ch.radiosity)
    paths = panelrad.write_outputs(solution, tmp_path / "cornell", formats=("csv", "png"))
    assert [p.rsplit(".", 1)[1] for p in paths] == ["csv", "png"]
    assert (tmp_path / "cornell.png").stat().st_size > 0
    lines = (tmp_path / "cornell.csv").read_text().splitlines()
    assert len(lines) >= n + 1
    with pytest.raises(ValueError):
        panelrad.write_outputs(solution, tmp_path / "x", formats=("gif",))
