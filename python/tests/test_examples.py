"""The examples under examples/python run as a researcher runs them and write their figures."""

import os
import subprocess
import sys

from conftest import SOURCE


def run_example(name, out):
    done = subprocess.run([sys.executable, str(SOURCE / "examples" / "python" / name), str(out)],
                          capture_output=True, text=True, env=dict(os.environ))
    assert done.returncode == 0, done.stdout + done.stderr
    return done.stdout


def test_render_path_writes_its_figure(tmp_path):
    out = run_example("render_path.py", tmp_path)
    figure = tmp_path / "path.png"
    assert "wrote" in out and figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    import omnicam

    image = omnicam.read_image(str(figure))
    assert image.shape[0] > 500 and image[..., :3].std() > 0.05  # a figure, not a blank page
