"""The operator H through Python: its products are the library's own, bit for bit, and it works
as a scipy LinearOperator for a Krylov solver of one's own."""
import inspect

import numpy as np
import pytest
import scipy.sparse.linalg as sla

import panelrad


@pytest.fixture(scope="module", params=["dense", "fast"])
def solver(request):
    # n = 768: the fast method at eta 0.5, M 2 uses the far field here.
    kwargs = {"eta": 0.5, "degree": 2} if request.param == "fast" else {}
    return panelrad.Solver(panelrad.paper_cube(), level=3, method=request.param, **kwargs)


def test_matvec_is_the_solvers_product_bit_for_bit(solver):
    (result,) = solver.solve()  # solve_channels: irradiance = H u from the solver's own product
    op = solver.operator
    assert op.shape == (solver.n, solver.n)
    assert op.dtype == np.float64
    np.testing.assert_array_equal(op.matvec(result.u), result.irradiance)
    np.testing.assert_array_equal(solver.irradiance(result.u), result.irradiance)
    # (n, 1) in, (n, 1) out; @ and matmat column by column are the same bits.
    col = op.matvec(result.u.reshape(-1, 1))
    assert col.shape == (solver.n, 1)
    np.testing.assert_array_equal(col[:, 0], result.irradiance)
    V = np.stack([result.u, np.ones(solver.n), solver.areas], axis=1)
    Y = op @ V
    for j in range(3):
        np.testing.assert_array_equal(Y[:, j], op.matvec(V[:, j].copy()))


def test_matvec_of_non_contiguous_input(solver):
    x = np.ones((solver.n, 2))[:, 0]  # a strided view
    assert not x.flags.c_contiguous
    np.testing.assert_array_equal(solver.operator.matvec(x), solver.operator.matvec(np.ascontiguousarray(x)))


def test_scipy_gmres_agrees_with_the_solver(solver):
    rho, E = solver.channel_values(0)
    H = sla.aslinearoperator(solver.operator)
    A = sla.LinearOperator(H.shape, matvec=lambda v: v - rho * H.matvec(v), dtype=np.float64)
    # scipy >= 1.12 names the relative tolerance rtol (tol before).
    rtol = {"rtol" if "rtol" in inspect.signature(sla.gmres).parameters else "tol": 1e-12}
    u, info = sla.gmres(A, E, atol=0, restart=50, maxiter=200, **rtol)
    assert info == 0
    (result,) = solver.solve()
    # Both solve the same system: the difference of the two answers is at most the sum of their
    # errors. scipy's: ||e||_inf <= ||(I-K)^-1||_inf ||r||_inf <= 2 ||r||_2 <= 2e-12 ||E||_2, as
    # ||(I-K)^-1||_inf <= 1/(1 - max rho) = 2 (11). The solver's: it stopped when its error bound
    # reached solver.tolerance relative to max |u|.
    bound = 2 * 1e-12 * np.linalg.norm(E) + solver.tolerance * np.max(np.abs(result.u))
    assert np.max(np.abs(u - result.u)) <= bound


def test_element_views_are_read_only_and_consistent(solver):
    c = solver.centroids
    assert c.shape == (solver.n, 3) and not c.flags.writeable
    with pytest.raises(ValueError):
        c[0, 0] = 1.0
    corners = solver.element_vertices
    np.testing.assert_allclose(corners.mean(axis=1), c, rtol=0, atol=1e-15)
    assert np.all(np.abs(np.linalg.norm(solver.normals, axis=1) - 1) < 1e-15)
    # The cube's surface area is 6.
    assert np.sum(solver.areas) == pytest.approx(6.0, rel=1e-14)
    assert set(np.unique(solver.facets)) == set(range(6))


def test_views_and_operator_outlive_their_objects():
    import gc

    solver = panelrad.Solver(panelrad.paper_cube(), level=1, method="dense")
    centroids, normals, result = solver.centroids, solver.normals, solver.solve()[0]
    u, op = result.u, solver.operator
    expected = (centroids.copy(), u.copy(), op.matvec(u))
    del solver, result
    gc.collect()
    np.testing.assert_array_equal(centroids, expected[0])  # the views keep the solver alive
    np.testing.assert_array_equal(u, expected[1])
    np.testing.assert_array_equal(op.matvec(u), expected[2])  # so does the operator
    assert normals.shape == (48, 3)


def test_progress_must_be_callable():
    with pytest.raises(TypeError, match="progress"):
        panelrad.Solver(panelrad.paper_cube(), level=0, progress="stderr")
