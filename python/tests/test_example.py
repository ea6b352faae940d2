"""The examples run to the end: examples/python/cornell_box.py writes its plot (when matplotlib is
there), and examples/python/quickstart.py, the README's Python example, prints its summary."""
import importlib.util
import os
import re
import subprocess
import sys

import panelrad


def test_cornell_box_example(source_dir, tmp_path):
    png = tmp_path / "floor.png"
    done = subprocess.run([sys.executable, str(source_dir / "examples" / "python" / "cornell_box.py"), str(png),
                           "--max-elements", "800"], capture_output=True, text=True, env=dict(os.environ), timeout=300)
    assert done.returncode == 0, done.stderr
    assert "floor:" in done.stdout
    if importlib.util.find_spec("matplotlib") is not None:
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    else:
        assert "matplotlib is not installed" in done.stdout


def test_readme_quickstart(source_dir):
    """Run as the README shows it, from the repository's root (it writes no file)."""
    done = subprocess.run([sys.executable, str(source_dir / "examples" / "python" / "quickstart.py")],
                          capture_output=True, text=True, env=dict(os.environ), cwd=source_dir, timeout=300)
    assert done.returncode == 0, done.stderr
    found = re.fullmatch(r"n = (\d+), u from (\S+) to (\S+)\n", done.stdout)
    assert found, done.stdout
    n, low, high = int(found[1]), float(found[2]), float(found[3])
    n0 = panelrad.load_scene(source_dir / "examples" / "scenes" / "cornell_box.obj").num_triangles
    assert n == 4**3 * n0  # level 3
    assert 0 <= low < high
