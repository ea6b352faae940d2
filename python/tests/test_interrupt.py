"""Ctrl-C during a setup or a solve: SIGINT is delivered while the library runs with the GIL
released; the next stage line or product raises KeyboardInterrupt, and the module keeps working."""
import os
import signal

import pytest

import panelrad


def interrupt_at(word):
    def progress(line):
        if word in line:
            os.kill(os.getpid(), signal.SIGINT)
    return progress


def test_interrupting_the_setup():
    with pytest.raises(KeyboardInterrupt):
        panelrad.Solver(panelrad.paper_cube(), level=3, method="fast", progress=interrupt_at("fast operator"))


def test_interrupting_a_solve():
    solver = panelrad.Solver(panelrad.paper_cube(), level=2, method="dense", solver="neumann",
                             progress=interrupt_at("product 3"))
    with pytest.raises(KeyboardInterrupt):
        solver.solve()
    # Still usable afterwards (the signal was consumed): a solve with new data runs to the end.
    quiet = panelrad.Solver(panelrad.paper_cube(), level=2, method="dense")
    (result,) = quiet.solve()
    assert result.converged


def test_progress_lines_reach_python():
    lines = []
    panelrad.Solver(panelrad.paper_cube(), level=1, method="dense", progress=lines.append).solve()
    assert any("dense matrix" in line for line in lines)
    assert any("product" in line for line in lines)


def test_sigint_from_another_thread_stops_a_running_solve():
    """The real Ctrl-C path: SIGINT arrives while the main thread is inside the library with the GIL
    released; the solver's next product runs the handler and stops. The solve cannot end by
    itself early: with rho = 0.999 the Neumann iteration's error shrinks by 0.999 a step, far
    above the tolerance after 40,000 steps. The signal is sent 0.2 s after the start. A library
    that ignored the signal would return only after all 40,000 products (and Python would then
    raise KeyboardInterrupt all the same), so the products are counted through the progress lines:
    the interrupted solve must have made fewer than half of them."""
    import threading

    import numpy as np

    products = []
    solver = panelrad.Solver(panelrad.paper_cube(), level=3, method="dense", solver="neumann", tolerance=1e-12,
                             max_iterations=40000, progress=lambda line: products.append(line) if "product" in line else None)
    rho, E = np.full(solver.n, 0.999), np.ones(solver.n)
    products.clear()
    timer = threading.Timer(0.2, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            solver.solve(rho, E)
    finally:
        timer.join()
    assert 0 < len(products) < 20000
