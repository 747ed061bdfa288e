"""Render the RoboCup field along its thesis loop and show what each frame holds.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/render_path.py out/python-example

Writes OUT/path.png: for four poses along the path, the omnidirectional image, its depth and
its instance masks (each object its own colour), side by side.
"""

import pathlib
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no window
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import omnicam  # noqa: E402


def main(out_dir):
    out = pathlib.Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    scene = omnicam.load_scene(omnicam.data_path("scenes/robocup2006.json"))
    renderer = omnicam.Renderer(scene)  # built once, reused for every pose
    path = scene.paths["thesis-loop"]
    poses = [path[k] for k in np.linspace(0, len(path) - 1, 4).astype(int)]

    figure, axes = plt.subplots(len(poses), 3, figsize=(9, 3 * len(poses)))
    palette = np.random.default_rng(0).uniform(0.2, 1.0, (len(scene.objects) + 1, 3))
    palette[0] = 0.0  # instance 0: nothing (beyond the rim, or the sky)
    for row, pose in zip(axes, poses):
        frame = renderer.render(pose, spp=4, shading="lit", outputs=["rgb", "depth", "instance"])
        row[0].imshow(np.clip(frame["rgb"][..., :3], 0, 1) ** (1 / 2.2))  # linear RGB (alpha dropped) → display
        row[0].set_title("pose (%.1f, %.1f, %.0f°)" % pose, fontsize=9)
        depth = np.ma.masked_equal(frame["depth"], 0.0)
        shown = row[1].imshow(depth, cmap="viridis", vmax=np.percentile(depth.compressed(), 95))
        figure.colorbar(shown, ax=row[1], fraction=0.046, label="depth (m)")
        row[2].imshow(palette[frame["instance"]])
        row[2].set_title("%d objects seen" % (len(np.unique(frame["instance"])) - 1), fontsize=9)
        for ax in row:
            ax.set_axis_off()
    figure.tight_layout()
    figure.savefig(out / "path.png", dpi=80)
    print("wrote", out / "path.png")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: render_path.py OUT_DIR")
    main(sys.argv[1])
