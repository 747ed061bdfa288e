"""The examples under examples/python run as a researcher runs them and write their figures."""

import os
import shutil
import subprocess
import sys

from conftest import SOURCE


def run_example(name, out):
    # A copy, run from elsewhere, as a user copies an example to start from: it finds omnicam's
    # files through omnicam.data_path, not beside itself.
    copy = out / "my_copy" / name
    copy.parent.mkdir(parents=True)
    shutil.copyfile(SOURCE / "examples" / "python" / name, copy)
    done = subprocess.run([sys.executable, str(copy), str(out)], cwd=str(copy.parent),
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


def test_the_victim_detector_scores_against_the_coco_file(tmp_path):
    import json

    out = run_example("victim_detector.py", tmp_path)
    assert "precision" in out
    scores = json.loads((tmp_path / "scores.json").read_text())
    coco = json.loads((tmp_path / "victims" / "cam0" / "coco.json").read_text())
    names = {c["id"]: c["name"] for c in coco["categories"]}
    test_images = {image["id"] for image in coco["images"] if image["frame"] >= 40}
    assert len(coco["images"]) == 60 and len(test_images) == 20
    for name, tally in scores.items():
        truth = sum(1 for a in coco["annotations"] if a["image_id"] in test_images and names[a["category_id"]] == name)
        assert tally["ground_truth"] == truth  # every COCO box of the test frames is counted once
        # n/a (null) exactly where nothing was detected, or nothing was there to find
        assert (tally["precision"] is None) == (tally["tp"] + tally["fp"] == 0)
        assert (tally["recall"] is None) == (tally["ground_truth"] == 0)
        assert all(0 <= tally[key] <= 1 for key in ("precision", "recall") if tally[key] is not None)
    # Victims' clothes and skin stand out of the maze's colours (measured: precision 0.92, recall 0.38).
    assert scores["victim"]["ground_truth"] > 20 and scores["victim"]["precision"] >= 0.5 and scores["victim"]["recall"] > 0.1
    assert (tmp_path / "detections.png").read_bytes()[:4] == b"\x89PNG"
