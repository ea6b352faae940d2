"""Bad input raises the right exceptions, with the library's message."""
import numpy as np
import pytest

import panelrad
from conftest import box


@pytest.fixture
def cube_arrays():
    return box((0, 0, 0), (1, 1, 1), inward=False)


def test_a_valid_cube(cube_arrays):
    v, t, f = cube_arrays
    scene = panelrad.Scene(v, t, rho=0.5, E=1.0, facets=f)
    assert scene.shape == "convex" and scene.closed and scene.num_facets == 6
    assert "convex" in repr(scene)


def test_exception_hierarchy():
    for cls in (panelrad.MeshError, panelrad.SceneFileError, panelrad.TextFileError, panelrad.SolverError,
                panelrad.EnergyBalanceError, panelrad.ResourceError):
        assert issubclass(cls, panelrad.Error)
    assert issubclass(panelrad.Error, RuntimeError)


def test_nan_vertex_is_a_mesh_error(cube_arrays):
    v, t, f = cube_arrays
    v = v.copy()
    v[3, 1] = np.nan
    with pytest.raises(panelrad.MeshError, match="finite|NaN|nan"):
        panelrad.Scene(v, t, facets=f)


def test_a_vertex_index_out_of_range_is_a_mesh_error(cube_arrays):
    v, t, f = cube_arrays
    t = t.copy()
    t[0, 0] = 8
    with pytest.raises(panelrad.MeshError):
        panelrad.Scene(v, t, facets=f)


@pytest.mark.parametrize("shape", [(8,), (8, 2), (8, 3, 1)])
def test_wrong_vertex_shape(cube_arrays, shape):
    v, t, f = cube_arrays
    with pytest.raises(ValueError, match="vertices: expected shape"):
        panelrad.Scene(np.zeros(shape), t, facets=f)


def test_wrong_dtypes(cube_arrays):
    v, t, f = cube_arrays
    with pytest.raises(TypeError, match="vertices"):
        panelrad.Scene(v.astype(np.complex128), t, facets=f)
    with pytest.raises(TypeError, match="triangles"):
        panelrad.Scene(v, t.astype(np.float64), facets=f)
    with pytest.raises(TypeError, match="vertices"):
        panelrad.Scene(v.astype(str), t, facets=f)
    with pytest.raises(ValueError, match="triangles: entry"):
        panelrad.Scene(v, -t, facets=f)
    with pytest.raises(ValueError, match="facets: expected shape"):
        panelrad.Scene(v, t, facets=f[:-1])


def test_other_real_dtypes_and_strides_are_accepted(cube_arrays):
    v, t, f = cube_arrays
    reference = panelrad.Scene(v, t, facets=f)
    wide = np.zeros((8, 6))
    wide[:, ::2] = v
    strided = wide[:, ::2]  # non-contiguous: read through its strides
    assert not strided.flags.c_contiguous
    for vertices, triangles in [(strided, t), (v.astype(np.float32), t.astype(np.uint16)),
                                (v.astype(np.int64), np.asfortranarray(t.astype(np.int32)))]:
        scene = panelrad.Scene(vertices, triangles, facets=f)
        np.testing.assert_array_equal(scene.vertices, reference.vertices)
        np.testing.assert_array_equal(scene.triangles, reference.triangles)


def test_reflectivity_at_or_above_one_is_a_value_error(cube_arrays):
    v, t, f = cube_arrays
    with pytest.raises(ValueError, match=r"\[0, 1\)"):
        panelrad.Scene(v, t, rho=1.0, facets=f)
    scene = panelrad.Scene(v, t, facets=f)
    rho = np.full(6, 0.5)
    rho[4] = 1.5
    with pytest.raises(ValueError, match="facet 4"):
        scene.set_reflectivity(rho)
    with pytest.raises(ValueError):
        scene.set_emissivity(-1.0)
    with pytest.raises(ValueError, match="shape"):
        scene.set_reflectivity(np.zeros(5))


def test_solver_arguments(cube_arrays):
    v, t, f = cube_arrays
    scene = panelrad.Scene(v, t, rho=0.5, facets=f)
    with pytest.raises(ValueError, match="method"):
        panelrad.Solver(scene, level=0, method="fastest")
    with pytest.raises(ValueError, match="need method"):
        panelrad.Solver(scene, level=0, eta=0.3)
    with pytest.raises(ValueError, match="accuracy"):
        panelrad.Solver(scene, level=0, accuracy=0.01)  # tighter than any measured margin
    solver = panelrad.Solver(scene, level=1, method="dense")
    with pytest.raises(ValueError, match=r"E: expected shape \(48,\)"):
        solver.solve(np.ones(47))
    with pytest.raises(ValueError):
        solver.solve(np.full(48, 1.0), np.ones(48))  # rho = 1
    with pytest.raises(TypeError):
        solver.solve(np.ones(48, dtype=bool))


def test_not_converged_is_a_solver_error(cube_arrays):
    v, t, f = cube_arrays
    scene = panelrad.Scene(v, t, rho=0.9, facets=f)
    solver = panelrad.Solver(scene, level=1, method="dense", solver="neumann", max_iterations=2, tolerance=1e-12)
    (result,) = solver.solve()
    assert not result.converged
    with pytest.raises(panelrad.SolverError):
        result.require_converged()


def test_scene_files(tmp_path, source_dir):
    # load_scene reports an unreadable file as the scene's (or, geometry only, the mesh's) error.
    with pytest.raises(panelrad.SceneFileError, match="missing.obj: cannot open"):
        panelrad.load_scene(tmp_path / "missing.obj")
    folder = tmp_path / "folder.obj"
    folder.mkdir()
    with pytest.raises(panelrad.MeshError, match="not a regular file"):
        panelrad.load_scene(folder, geometry_only=True)
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")  # a face before any usemtl
    with pytest.raises(panelrad.SceneFileError):
        panelrad.load_scene(bad)
    scene = panelrad.load_scene(source_dir / "examples" / "scenes" / "cornell_box.obj")
    assert scene.channels == ["R", "G", "B"] and scene.shape == "general"


def test_accuracy_loosens_the_automatic_far_field():
    """accuracy is the far field's error allowed as a fraction of the discretization error: the
    paper's cube at level 5 takes the fast method, and a looser accuracy never asks for a higher
    Taylor degree or a smaller eta than the default 0.05 (choose_parameters' rule is monotone)."""
    cube = panelrad.paper_cube()
    tight = panelrad.Solver(cube, level=5).info
    loose = panelrad.Solver(cube, level=5, accuracy=2.0).info
    assert tight["method"] == "fast"
    assert loose["method"] == "fast"
    assert (loose["degree"], -loose["eta"]) < (tight["degree"], -tight["eta"])
