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
    itself early: with rho = 0.999 the Neumann iteration's error shrinks by 0.999 a step, so
    4000 steps leave it near 0.999^4000 = 0.02 of the first, far above the tolerance. The signal
    is sent a twentieth of an uninterrupted run's time after the start; ending before three
    quarters of that time shows that the signal stopped it (the margin absorbs the other jobs'
    load on a shared machine, which can delay the timer thread)."""
    import threading
    import time

    import numpy as np

    solver = panelrad.Solver(panelrad.paper_cube(), level=3, method="dense", solver="neumann",
                             tolerance=1e-12, max_iterations=4000)
    rho, E = np.full(solver.n, 0.999), np.ones(solver.n)
    t = time.perf_counter()
    full = solver.solve(rho, E)
    full_s = time.perf_counter() - t
    assert not full.converged and full.iterations >= 4000
    timer = threading.Timer(full_s / 20, os.kill, (os.getpid(), signal.SIGINT))
    t = time.perf_counter()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            solver.solve(rho, E)
    finally:
        timer.join()
    assert time.perf_counter() - t < 0.75 * full_s
