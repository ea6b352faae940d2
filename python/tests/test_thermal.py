"""panelrad.thermal_solve: a plate under the sky against q = eps sigma (T^4 - T_env^4), a gray
body in a black room, the example script's energy balance, and refusals."""
import math
import os
import re
import subprocess
import sys

import numpy as np
import pytest

import panelrad

SIGMA = 5.670374419e-8


def plate():
    vertices = np.array([[0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0]], dtype=float)
    return panelrad.Scene(vertices, [[0, 1, 2], [0, 2, 3]], facets=[0, 0])


def test_plate_under_the_sky():
    s = panelrad.thermal_solve(plate(), {"facet 0": {"T": 320, "emissivity": 0.7}}, "facet",
                               environment=250, level=2)
    q = 0.7 * SIGMA * (320**4 - 250**4)
    np.testing.assert_allclose(s.q, q, rtol=1e-12)
    np.testing.assert_allclose(s.group_Q, [2 * q], rtol=1e-12)
    assert math.isclose(s.environment_Q, 2 * q, rel_tol=1e-12)
    assert s.converged and s.T.shape == (s.n,)


def test_adiabatic_plate_takes_the_sky_temperature():
    """An adiabatic plate alone under a sky at 250 K: J = H = sigma 250^4, so T = 250 K."""
    s = panelrad.thermal_solve(plate(), {"facet 0": {"q": 0, "emissivity": 0.4}}, "facet", environment=250, level=1)
    np.testing.assert_allclose(s.T, 250, rtol=1e-12)
    np.testing.assert_allclose(s.q, 0, atol=1e-9)


def band_fraction(lo_um, hi_um, T):
    """The share of sigma T^4 a blackbody at T emits between lo_um and hi_um: Planck's law
    integrated by scipy (independent of panelrad's series)."""
    from scipy.integrate import quad
    c2 = 1.438776877e-2
    x = lambda lam_um: c2 / (lam_um * 1e-6 * T)
    f = lambda t: t**3 / math.expm1(t)
    lo = x(hi_um) if math.isfinite(hi_um) else 0.0
    hi = x(lo_um) if lo_um > 0 else 700.0
    return 15 / math.pi**4 * quad(f, lo, hi, epsabs=1e-14, epsrel=1e-13, limit=200)[0]


def test_plate_under_the_sky_with_bands():
    """Band emissivities (0.9, 0.2, 0.6) in [0, 3], [3, 8], [8, inf) um: q = sum_k eps_k sigma
    (F_k(T) T^4 - F_k(T_env) T_env^4)."""
    eps = [0.9, 0.2, 0.6]
    bands = [(0, 3), (3, 8), (8, math.inf)]
    s = panelrad.thermal_solve(plate(), {"facet 0": {"T": 900, "emissivity": np.array(eps)}}, "facet",
                               environment=250, band_edges_um=[3, 8], level=1)
    q = sum(e * SIGMA * (band_fraction(a, b, 900) * 900**4 - band_fraction(a, b, 250) * 250**4)
            for e, (a, b) in zip(eps, bands))
    np.testing.assert_allclose(s.q, q, rtol=1e-10)
    assert s.band_edges_um == [3, 8]
    with pytest.raises(panelrad.ArgumentError, match="2 band emissivities for 3 bands"):
        panelrad.thermal_solve(plate(), {"facet 0": {"T": 900, "emissivity": [0.5, 0.5]}}, "facet",
                               environment=250, band_edges_um=[3, 8])


def test_example_script_balances(source_dir):
    done = subprocess.run([sys.executable, str(source_dir / "examples" / "python" / "thermal_room.py"), "--level", "2"],
                          capture_output=True, text=True, env=dict(os.environ), cwd=source_dir, timeout=300)
    assert done.returncode == 0, done.stderr
    found = re.search(r"energy balance: sum of the rates (\S+) W, defect (\S+)", done.stdout)
    assert found, done.stdout
    assert float(found[2]) < 1e-2
    assert "room_z0" in done.stdout


def test_refusals():
    scene = plate()
    with pytest.raises(panelrad.ArgumentError, match="has no condition"):
        panelrad.thermal_solve(scene, {}, "facet", environment=250)
    with pytest.raises(panelrad.ArgumentError, match="not a group"):
        panelrad.thermal_solve(scene, {"facet 0": {"T": 300, "emissivity": 1}, "roof": {"q": 0}}, "facet",
                               environment=250)
    with pytest.raises(panelrad.ArgumentError, match="the scene is open"):
        panelrad.thermal_solve(scene, {"facet 0": {"T": 300, "emissivity": 1}}, "facet")
    with pytest.raises(panelrad.ArgumentError, match=r"emissivity 2 is not in \(0, 1\]"):
        panelrad.thermal_solve(scene, {"facet 0": {"T": 300, "emissivity": 2}}, "facet", environment=250)
    with pytest.raises(TypeError):
        panelrad.thermal_solve(scene, {"facet 0": {"T": "hot", "emissivity": 1}}, "facet", environment=250)
