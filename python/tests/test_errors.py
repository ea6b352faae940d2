"""Bad input raises the right exceptions, with the library's message; every exception the
module raises is a panelrad.Error."""
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
    # A misuse is a panelrad.Error too, and still the Python exception it is named after.
    assert issubclass(panelrad.ArgumentError, panelrad.Error) and issubclass(panelrad.ArgumentError, ValueError)
    assert issubclass(panelrad.ArgumentTypeError, panelrad.Error)
    assert issubclass(panelrad.ArgumentTypeError, TypeError)
    assert issubclass(panelrad.ChannelError, panelrad.Error)
    assert issubclass(panelrad.ChannelError, KeyError) and issubclass(panelrad.ChannelError, IndexError)
    for name in panelrad.__all__:
        obj = getattr(panelrad, name)
        if isinstance(obj, type) and issubclass(obj, BaseException):
            assert issubclass(obj, panelrad.Error), name


def test_every_failure_is_a_panelrad_error(cube_arrays, tmp_path):
    """Each kind of failure the module reports, caught as panelrad.Error."""
    v, t, f = cube_arrays
    scene = panelrad.Scene(v, t, rho=0.5, E=1.0, facets=f)
    solution = panelrad.solve_scene(scene, level=0, method="dense")
    failures = {
        "write_outputs into a missing folder": lambda: panelrad.write_outputs(
            solution, tmp_path / "missing" / "cube", formats=("csv",)),
        "rho = 1": lambda: scene.set_reflectivity(1.0),
        "a wrong shape": lambda: panelrad.Scene(np.zeros((8, 2)), t, facets=f),
        "a wrong dtype": lambda: panelrad.Scene(v.astype(np.complex128), t, facets=f),
        "an unknown channel name": lambda: scene.reflectivity("R"),
        "a channel index out of range": lambda: solution[3],
        "an unknown method": lambda: panelrad.Solver(scene, level=0, method="fastest"),
        "an unknown keyword": lambda: panelrad.Solver(scene, level=0, tol=1e-8),
        "a level beyond the element index": lambda: panelrad.Solver(panelrad.paper_cube(), level=14),
        "a missing file": lambda: panelrad.load_scene(tmp_path / "missing.obj"),
    }
    for what, fail in failures.items():
        with pytest.raises(panelrad.Error):
            fail()
        try:
            fail()
        except panelrad.Error as e:
            assert str(e), what


def test_write_outputs_into_a_missing_folder(cube_arrays, tmp_path):
    v, t, f = cube_arrays
    solution = panelrad.solve_scene(panelrad.Scene(v, t, rho=0.5, E=1.0, facets=f), level=0, method="dense")
    with pytest.raises(panelrad.Error, match="missing"):
        panelrad.write_outputs(solution, tmp_path / "missing" / "cube", formats=("csv",))
    assert not (tmp_path / "missing").exists()


def test_a_misspelled_keyword_is_named_with_the_accepted_ones(cube_arrays):
    v, t, f = cube_arrays
    scene = panelrad.Scene(v, t, rho=0.5, E=1.0, facets=f)
    for call in (lambda: panelrad.Solver(scene, level=0, tol=1e-8),
                 lambda: panelrad.solve_scene(scene, level=0, tol=1e-8)):
        with pytest.raises(TypeError) as info:
            call()
        message = str(info.value)
        assert "'tol'" in message, message
        assert "did you mean 'tolerance'" in message, message
        for accepted in ("level", "max_elements", "accuracy", "method", "eta", "degree", "near", "mu", "visibility",
                         "solver", "tolerance", "max_iterations", "threads", "progress"):
            assert accepted in message, (accepted, message)
    with pytest.raises(TypeError, match="'levels'.*did you mean 'level'"):
        panelrad.Solver(scene, levels=0)
    # A keyword of the right name but the wrong type names it too.
    with pytest.raises(TypeError, match="max_iterations"):
        panelrad.Solver(scene, level=0, max_iterations="many")
    with pytest.raises(TypeError, match="level"):
        panelrad.Solver(scene, level=0.5)


def test_the_emission_is_set_as_emission_and_zero_unless_given(cube_arrays):
    v, t, f = cube_arrays
    scene = panelrad.Scene(v, t, rho=0.5, facets=f)
    np.testing.assert_array_equal(scene.emission(), np.zeros(6))  # no surface emits by default
    assert not hasattr(scene, "set_emissivity") and not hasattr(scene, "emissivity")
    (dark,) = panelrad.Solver(scene, level=1, method="dense").solve()
    assert dark.converged and not dark.u.any()
    scene.set_emission(np.arange(6.0))
    np.testing.assert_array_equal(scene.emission(), np.arange(6.0))
    (lit,) = panelrad.Solver(scene, level=1, method="dense").solve()
    assert lit.u.min() > 0


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
        scene.set_emission(-1.0)
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
    # The library's own checks (SolveOptions::validate), naming the keyword and the value.
    for keywords, named in [({"tolerance": float("inf")}, "tolerance: .*got inf"),
                            ({"tolerance": 0.0}, "tolerance: .*got 0"),
                            ({"max_iterations": 0}, "max_iterations: .*got 0"),
                            ({"method": "fast", "degree": 13}, "degree: .*got 13"),
                            ({"method": "fast", "eta": 1.5}, "eta: .*got 1.5"),
                            ({"method": "dense", "near": "quadrature", "mu": -1}, "mu: .*got -1"),
                            ({"max_elements": 0, "level": None}, "max_elements: .*got 0")]:
        with pytest.raises(ValueError, match=named):
            panelrad.Solver(scene, **{"level": 0, **keywords})
    solver = panelrad.Solver(scene, level=1, method="dense")
    with pytest.raises(ValueError, match=r"E: expected shape \(48,\)"):
        solver.solve(np.ones(47))
    with pytest.raises(ValueError):
        solver.solve(np.full(48, 1.0), np.ones(48))  # rho = 1
    with pytest.raises(TypeError):
        solver.solve(np.ones(48, dtype=bool))


def test_not_converged_is_a_solver_error(cube_arrays):
    v, t, f = cube_arrays
    scene = panelrad.Scene(v, t, rho=0.9, E=1.0, facets=f)
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
