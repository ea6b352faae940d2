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
