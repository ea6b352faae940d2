"""examples/python/cornell_box.py runs to the end and writes its plot (when matplotlib is there)."""
import importlib.util
import os
import subprocess
import sys


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
