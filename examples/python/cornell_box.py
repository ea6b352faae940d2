#!/usr/bin/env python3
"""The Cornell box from Python: load the OBJ scene (materials R, G, B from its MTL), solve the
radiosity equation on every channel with one operator, print the energy balance, and plot the
radiosity on the floor (the facets facing up at the lowest height) with matplotlib when it is
installed (headless, backend Agg; skipped with a note when it is not).

Usage: cornell_box.py [PNG] [--max-elements N] [--scene OBJ]
  PNG: where the floor plot goes (default cornell_floor.png). Run with PYTHONPATH=build/python
  from a build with -DPANELRAD_PYTHON=ON, or after cmake --install.
"""
import argparse
import pathlib
import sys

import numpy as np

import panelrad

HERE = pathlib.Path(__file__).resolve().parent


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("png", nargs="?", default="cornell_floor.png")
    parser.add_argument("--max-elements", type=int, default=20000)
    parser.add_argument("--scene", default=str(HERE.parent / "scenes" / "cornell_box.obj"))
    args = parser.parse_args()

    scene = panelrad.load_scene(args.scene)
    print(scene)
    solution = panelrad.solve_scene(scene, max_elements=args.max_elements)
    solution.require_converged()
    print(solution)
    for ch in solution.channels:
        print(f"  {ch.name}: {ch.iterations} products, residual {ch.residual:.2e}, "
              f"emitted {ch.emitted:.4g}, absorbed {ch.absorbed:.4g}, escaped {100 * ch.escaped:.1f}%")

    # The floor: elements whose inner normal (the lit side) points up, at the lowest height.
    normals, centroids = solution.normals, solution.centroids
    # Up is the axis along which the light's facets face down: the ceiling light emits most.
    emitting = solution.channels[0].E > 0
    axis = int(np.argmax(np.abs(normals[emitting].mean(axis=0))))
    up = -np.sign(normals[emitting].mean(axis=0)[axis])  # the light faces down: its normal is -up
    floor_height = np.min(centroids[:, axis] * up) * up
    floor = (normals[:, axis] * up > 0.999) & (np.abs(centroids[:, axis] - floor_height) < 1e-9 * solution.diameter)
    luminance = sum(w * ch.radiosity for w, ch in zip((0.2126, 0.7152, 0.0722), solution.channels))
    print(f"floor: {floor.sum()} elements, radiosity (luminance) {luminance[floor].min():.4g} .. "
          f"{luminance[floor].max():.4g}")

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from matplotlib.collections import PolyCollection
    except ImportError:
        print("matplotlib is not installed: no plot")
        return 0
    # Each floor element as a triangle in the floor's plane (the two other axes), in its colour.
    corners = solution.element_vertices[floor]
    plane = [a for a in range(3) if a != axis]
    fig, ax = plt.subplots(figsize=(6, 5.5))
    rgb = np.stack([ch.radiosity[floor] for ch in solution.channels], axis=1)
    rgb = np.clip(rgb / np.percentile(rgb, 99), 0, 1)
    ax.add_collection(PolyCollection(corners[:, :, plane], facecolors=rgb, edgecolors="none"))
    ax.autoscale()
    ax.set_aspect("equal")
    ax.set_title(f"Cornell box floor: radiosity, n = {solution.n}")
    ax.set_xlabel("xyz"[plane[0]])
    ax.set_ylabel("xyz"[plane[1]])
    fig.savefig(args.png, dpi=120, bbox_inches="tight")
    print(f"wrote {args.png}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
