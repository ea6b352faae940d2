"""panelrad.view_factors: the cube's faces against their closed forms (Howell C-11 and C-14), a
convex body inside a room (F_box,room = 1, reciprocity), groups named per facet, the files written,
and bad arguments refused."""
import numpy as np
import pytest

import panelrad
from conftest import room_with_box

OPPOSITE = 0.19982489569838732  # unit squares facing each other at distance 1
ADJACENT = 0.20004377607540316  # unit squares at right angles sharing an edge


def test_cube_faces_match_the_closed_forms():
    vf = panelrad.view_factors(panelrad.paper_cube(), level=4)
    assert vf.F.shape == (6, 6)
    assert vf.names == [f"facet {k}" for k in range(6)]
    assert vf.enclosed
    np.testing.assert_allclose(vf.area, np.ones(6), atol=1e-14)
    # Opposite faces: their centres are the farthest apart.
    cube = panelrad.paper_cube()
    centres = np.array([cube.vertices[cube.triangles[cube.facets == k]].reshape(-1, 3).mean(axis=0) for k in range(6)])
    distance = np.linalg.norm(centres[:, None, :] - centres[None, :, :], axis=2)
    exact = np.where(distance > 1.2, OPPOSITE, ADJACENT)
    np.fill_diagonal(exact, 0.0)
    assert vf.error is not None
    assert np.all(np.abs(vf.F - exact) <= vf.error + 1e-12)
    assert np.abs(vf.F - exact).max() < 2e-4  # 1.4e-4 at n = 3,072 (the paper's diagonals)
    assert np.abs(vf.uncovered).max() <= vf.uncovered_error.max() + 1e-12


def test_a_body_in_a_room_by_named_groups():
    vertices, triangles, facets = room_with_box()
    scene = panelrad.Scene(vertices, triangles, facets=facets)
    names = ["room"] * 6 + ["box"] * 6
    vf = panelrad.view_factors(scene, names, level=3)
    assert vf.names == ["room", "box"]
    assert vf.F[1, 1] == 0.0  # a convex body's faces do not see each other
    assert vf.F[1, 0] == pytest.approx(1.0, abs=max(vf.error[1, 0], 1e-6))
    area_box = 2 * (1.5 * 1 + 1.5 * 1 + 1 * 1)
    assert vf.area[1] == pytest.approx(area_box, rel=1e-13)
    assert vf.F[0, 1] == pytest.approx(area_box / vf.area[0], abs=vf.error[0, 1])
    assert vf.reciprocity_pair == ("room", "box")


def test_files_and_no_estimate(tmp_path):
    vf = panelrad.view_factors(panelrad.paper_cube(), level=2, estimate_error=False, block_columns=2)
    assert vf.error is None and vf.uncovered_error is None
    paths = vf.write(tmp_path / "cube")
    assert [p.split("/")[-1] for p in paths] == ["cube.csv", "cube.npy"]
    np.testing.assert_array_equal(np.load(tmp_path / "cube.npy"), vf.F)
    header = (tmp_path / "cube.csv").read_text().splitlines()[0]
    assert header == "group,area," + ",".join(vf.names) + ",closure_defect"


def test_bad_arguments():
    cube = panelrad.paper_cube()
    with pytest.raises(panelrad.ArgumentError, match="'solid' is not"):
        panelrad.view_factors(cube, "solid")
    with pytest.raises(panelrad.ArgumentError, match="names no object"):
        panelrad.view_factors(cube, "object")
    with pytest.raises(panelrad.ArgumentError, match="no materials"):
        panelrad.view_factors(cube, "material")
    with pytest.raises(panelrad.ArgumentError, match="5 facets"):
        panelrad.view_factors(cube, ["a"] * 5)
    with pytest.raises(panelrad.ArgumentTypeError):
        panelrad.view_factors(cube, [1, 2, 3, 4, 5, 6])
    with pytest.raises(panelrad.ArgumentTypeError, match="did you mean 'level'"):
        panelrad.view_factors(cube, levels=2)


def test_stl_from_python(tmp_path):
    """An ASCII STL of the room with a box, one solid each: read as geometry only, grouped by its
    solids, the same factors as the arrays' scene grouped by name."""
    vertices, triangles, facets = room_with_box()
    lines = []
    for name, wanted in (("room", range(6)), ("box", range(6, 12))):
        lines.append(f"solid {name}")
        for t, f in zip(triangles, facets):
            if f in wanted:
                lines.append("facet normal 0 0 0\nouter loop")
                lines += [f"vertex {x!r} {y!r} {z!r}" for x, y, z in vertices[t]]
                lines.append("endloop\nendfacet")
        lines.append(f"endsolid {name}")
    path = tmp_path / "room.stl"
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(panelrad.SceneFileError, match="geometry only"):
        panelrad.load_scene(path)
    stl = panelrad.load_scene(path, geometry_only=True)
    assert stl.num_facets == 24
    a = panelrad.view_factors(stl, "object", level=2, estimate_error=False)
    arrays = panelrad.Scene(vertices, triangles, facets=np.arange(24))  # each triangle a face, as in the STL
    b = panelrad.view_factors(arrays, ["room"] * 12 + ["box"] * 12, level=2, estimate_error=False)
    assert a.names == ["room", "box"]
    np.testing.assert_array_equal(a.F, b.F)


def test_reciprocal_and_closed():
    vertices, triangles, facets = room_with_box()
    scene = panelrad.Scene(vertices, triangles, facets=facets)
    vf = panelrad.view_factors(scene, level=2, reciprocal=True, estimate_error=False)
    assert vf.correction > 0
    AF = vf.area[:, None] * vf.F
    np.testing.assert_allclose(AF, AF.T, atol=1e-13)
    np.testing.assert_allclose(vf.F.sum(axis=1), np.ones(12), atol=1e-12)


def test_element_sky_of_an_open_scene():
    """A unit floor alone under the sky: every element sees only sky; with a wall, less."""
    floor = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=float)
    alone = panelrad.Scene(floor, [[0, 1, 2], [0, 2, 3]], facets=[0, 0])
    vf = panelrad.view_factors(alone, level=2, elements=True, estimate_error=False)
    assert vf.element_sky.shape == (32,)
    np.testing.assert_array_equal(vf.element_sky, np.ones(32))
    assert vf.element_centroids.shape == (32, 3)
    np.testing.assert_allclose(vf.element_areas.sum(), 1.0, rtol=1e-14)
    assert set(vf.element_groups) == {0}
    vertices = np.vstack([floor, [[1, 1, 1], [0, 1, 1]]])
    walled = panelrad.Scene(vertices, [[0, 1, 2], [0, 2, 3], [3, 2, 4], [3, 4, 5]], facets=[0, 0, 1, 1])
    vf = panelrad.view_factors(walled, level=2, elements=True, estimate_error=False)
    assert vf.element_sky.max() < 1 and vf.element_sky.min() > 0.5
    vf = panelrad.view_factors(walled, level=2, elements_to=["facet 1", "facet 0"], estimate_error=False)
    assert vf.element_factors.shape == (64, 2)
    on_floor = np.asarray(vf.element_groups) == 0
    np.testing.assert_array_equal(vf.element_factors[on_floor, 1], 0)  # the floor does not see itself
    np.testing.assert_allclose(vf.element_factors.sum(axis=1) + vf.element_sky, 1, atol=1e-13)
    mean = (vf.element_areas[on_floor] * vf.element_factors[on_floor, 0]).sum() / vf.area[0]
    np.testing.assert_allclose(mean, vf.F[0, 1], rtol=1e-13)
    assert panelrad.view_factors(walled, level=1, estimate_error=False).element_sky is None


def test_two_sided_sheet():
    """A fin across a floor's middle: its back is the group 'facet 2 (back)', seen alike."""
    vertices = np.array([[-1, 0, 0], [0, 0, 0], [0, 1, 0], [-1, 1, 0], [1, 0, 0], [1, 1, 0],
                         [0, 1, 1], [0, 0, 1]], dtype=float)
    triangles = [[0, 1, 2], [0, 2, 3], [1, 4, 5], [1, 5, 2], [1, 2, 6], [1, 6, 7]]
    scene = panelrad.Scene(vertices, triangles, facets=[0, 0, 0, 0, 1, 1])
    one = panelrad.view_factors(scene, level=3, estimate_error=False)
    two = panelrad.view_factors(scene, level=3, estimate_error=False, two_sided=["facet 1"])
    assert two.names == ["facet 0", "facet 1", "facet 1 (back)"]
    np.testing.assert_allclose(two.F[0, 1], one.F[0, 1], rtol=1e-12)
    np.testing.assert_allclose(two.F[0, 2], two.F[0, 1], rtol=1e-12)
    assert two.F[1, 2] == 0 and two.F[2, 1] == 0
    with pytest.raises(panelrad.ArgumentError, match="'roof' is not a group"):
        panelrad.view_factors(scene, level=1, two_sided=["roof"])
