"""Shared fixtures: the source tree (for the paper's tables and the example scenes) and meshes
built from numpy arrays."""
import os
import pathlib

import numpy as np
import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("PANELRAD_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))


@pytest.fixture(scope="session")
def source_dir() -> pathlib.Path:
    return SOURCE_DIR


def box(lo, hi, inward):
    """The 8 corners and 12 triangles (6 square facets) of the box [lo, hi]^3, counter-clockwise
    seen from outside (inward=False) or from inside (inward=True)."""
    lo = np.asarray(lo, dtype=float)
    hi = np.asarray(hi, dtype=float)
    corners = np.array([[hi[0] if i & 1 else lo[0], hi[1] if i & 2 else lo[1], hi[2] if i & 4 else lo[2]]
                        for i in range(8)])
    # Each face's corners counter-clockwise seen from outside.
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    triangles = []
    for a, b, c, d in quads:
        t = [(a, b, c), (a, c, d)]
        if inward:
            t = [(x, z, y) for x, y, z in t]
        triangles.extend(t)
    facets = np.repeat(np.arange(6), 2)
    return corners, np.array(triangles, dtype=np.int64), facets


def room_with_box():
    """A closed room [0, 4]^3 (front sides inward) with a box [1, 2.5] x [1, 2] x [0.5, 1.5]
    floating inside it (front sides outward): 12 facets, 24 triangles."""
    rv, rt, rf = box((0, 0, 0), (4, 4, 4), inward=True)
    bv, bt, bf = box((1, 1, 0.5), (2.5, 2, 1.5), inward=False)
    vertices = np.vstack([rv, bv])
    triangles = np.vstack([rt, bt + len(rv)])
    facets = np.concatenate([rf, bf + 6])
    return vertices, triangles, facets
