#!/usr/bin/env python3
"""The cost of calling panelrad from Python: the same solve from the C++ command line and from the
Python module, timed end to end.

The scene is the paper's cube geometry (examples/meshes/cube.off: 6 squares, 12 triangles) with
rho 0.5 on y = 0, 1; 0.4 on z = 0, 1; 0.3 on x = 0, 1 (31) and E = 1, given by a JSON sidecar, at
level 6: n = 12 * 4^6 = 49,152 elements. Both sides do the same work through the same library
call (solve_scene, automatic operator and solver choice) and write the same CSV:
  C++:    panelrad solve cube.off --materials cube.json --levels 6 --formats csv --threads T --quiet
  Python: load_scene(cube.off, materials=cube.json); solve_scene(scene, level=6, threads=T);
          write_outputs(solution, prefix, formats=("csv",))
The C++ time is the process's wall time (start-up included, a few ms); the Python time is measured
inside one interpreter after `import panelrad` (the import is timed separately). Each side also
reports the library's own time for the solve (solve_scene's total: subdivision, operator,
iterations), from the command line's summary and from Solution.total_s: the wall time minus
that is what each spends outside the solve (reading the scene, writing the CSV, start-up or the
bindings), a figure that the machine's other load disturbs far less than the wall times. The runs
alternate, C++ first, and the medians are printed.

Usage: python_overhead.py [--cli build/cli/panelrad] [--level 6] [--repeats 3] [--threads 2]
with PYTHONPATH pointing at the module (build/python).
"""
import argparse
import re
import json
import os
import pathlib
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

SOURCE_DIR = pathlib.Path(__file__).resolve().parents[1]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--cli", default=str(SOURCE_DIR / "build" / "cli" / "panelrad"))
    parser.add_argument("--level", type=int, default=6)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--threads", type=int, default=2)
    args = parser.parse_args()

    t0 = time.perf_counter()
    import panelrad  # noqa: E402  (timed)
    import_s = time.perf_counter() - t0

    work = pathlib.Path(tempfile.mkdtemp(prefix="panelrad_overhead_"))
    try:
        mesh = work / "cube.off"
        shutil.copy(SOURCE_DIR / "examples" / "meshes" / "cube.off", mesh)
        # OFF faces 0, 1: x = 0, 1; 2, 3: y = 0, 1; 4, 5: z = 0, 1.
        materials = work / "cube.json"
        materials.write_text(json.dumps({"default": {"rho": 0.3, "E": 1},
                                         "facets": [{"ids": [2, 3], "rho": 0.5}, {"ids": [4, 5], "rho": 0.4}]}))
        cli_s, cli_inside_s, py_s, inside_s = [], [], [], []
        summary = ""
        for r in range(args.repeats):
            t = time.perf_counter()
            done = subprocess.run([args.cli, "solve", str(mesh), "--materials", str(materials), "--levels",
                                   str(args.level), "--formats", "csv", "--threads", str(args.threads), "--quiet",
                                   "--out", str(work / "cli")], check=True, capture_output=True, text=True)
            cli_s.append(time.perf_counter() - t)
            summary = done.stdout
            total = re.search(r"total ([0-9.]+) s", summary)
            cli_inside_s.append(float(total.group(1)) if total else float("nan"))

            t = time.perf_counter()
            scene = panelrad.load_scene(mesh, materials=materials)
            solution = panelrad.solve_scene(scene, level=args.level, threads=args.threads)
            solution.require_converged()
            panelrad.write_outputs(solution, work / "py", formats=("csv",))
            py_s.append(time.perf_counter() - t)
            inside_s.append(solution.total_s)
            print(f"run {r + 1}: C++ {cli_s[-1]:.3f} s (solve {cli_inside_s[-1]:.2f} s), "
                  f"Python {py_s[-1]:.3f} s (solve {solution.total_s:.3f} s)", flush=True)
        same = (work / "cli.csv").read_bytes() == (work / "py.csv").read_bytes()
    finally:
        shutil.rmtree(work)

    print(f"n = {solution.n} (level {solution.level}), {solution.method}, threads {args.threads}")
    print(summary.strip().splitlines()[3] if summary.count("\n") > 3 else summary.strip())
    print(f"import panelrad: {import_s:.3f} s")
    cli, py = statistics.median(cli_s), statistics.median(py_s)
    print(f"median of {args.repeats}: C++ command line {cli:.3f} s, Python {py:.3f} s, "
          f"difference {py - cli:+.3f} s ({100 * (py - cli) / cli:+.1f}%)")
    cli_out = statistics.median(w - i for w, i in zip(cli_s, cli_inside_s))
    py_out = statistics.median(w - i for w, i in zip(py_s, inside_s))
    print(f"median time outside the solve: C++ command line {cli_out:.3f} s, Python {py_out:.3f} s "
          f"(the command line's solve time is printed to 0.01 s)")
    print(f"median library solve time: C++ {statistics.median(cli_inside_s):.2f} s, "
          f"Python {statistics.median(inside_s):.3f} s")
    print(f"CSV files identical: {'yes' if same else 'NO'}")
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
