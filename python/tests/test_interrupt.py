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
    above the tolerance after 40,000 steps. An uninterrupted run is estimated from 1,000 steps (x40);
    the signal is sent 0.2 s after the start. A library that ignored the signal would return only
    after the whole run (and Python would then raise KeyboardInterrupt all the same), so the test
    also requires the interrupted run to take under a quarter of the estimate: the interrupted run
    takes about 0.2 s plus one product, the estimate tens of seconds."""
    import threading
    import time

    import numpy as np

    cube = panelrad.paper_cube()
    probe = panelrad.Solver(cube, level=3, method="dense", solver="neumann", tolerance=1e-12, max_iterations=1000)
    rho, E = np.full(probe.n, 0.999), np.ones(probe.n)
    t = time.perf_counter()
    short = probe.solve(rho, E)
    estimate_s = 40 * (time.perf_counter() - t)
    assert not short.converged
    solver = panelrad.Solver(cube, level=3, method="dense", solver="neumann", tolerance=1e-12, max_iterations=40000)
    timer = threading.Timer(0.2, os.kill, (os.getpid(), signal.SIGINT))
    t = time.perf_counter()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            solver.solve(rho, E)
    finally:
        timer.join()
    assert time.perf_counter() - t < 0.25 * estimate_s
