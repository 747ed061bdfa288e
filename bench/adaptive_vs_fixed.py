"""Adaptive sampling against fixed sampling (docs/path-tracing.md, "Adaptive sampling"): each row's
frame rendered twice with one omnicam.Renderer (the second timed, its sample tables built by the
first), then its 8-bit sRGB PSNR inside the mirror disc against a converged frame, as
experiments/render_noise.h measures it.

    PYTHONPATH=build/python /usr/bin/python3 bench/adaptive_vs_fixed.py SCENE CONVERGED.exr X,Y,YAW
"""
import sys
import time

import numpy as np

import omnicam

ROWS = [(16, 0, 0.0), (64, 0, 0.0), (256, 0, 0.0), (1024, 0, 0.0),
        (16, 256, 0.02), (16, 256, 0.01), (64, 1024, 0.01), (64, 1024, 0.005)]


def srgb_levels(linear):
    x = np.clip(linear, 0.0, 1.0)
    return np.round(255.0 * np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055))


def psnr(frame, reference):
    inside = reference[..., 3] >= 0.999
    error = ((srgb_levels(frame[..., :3]) - srgb_levels(reference[..., :3])) ** 2).mean(-1)[inside]
    return 10.0 * np.log10(255.0 ** 2 / error.mean())


def main(scene_file, converged_file, pose_text):
    reference = np.asarray(omnicam.read_image(converged_file))
    pose = tuple(float(v) for v in pose_text.split(","))
    renderer = omnicam.Renderer(omnicam.load_scene(scene_file))
    for spp, most, target in ROWS:
        settings = dict(size=360, spp=spp, shading="path", seed=5)
        if most:
            settings.update(adaptive_spp=most, target_error=target)
        renderer.render(pose, **settings)
        start = time.perf_counter()
        frame = renderer.render(pose, **settings)["rgb"]
        seconds = time.perf_counter() - start
        label = "fixed %d spp" % spp if not most else "adaptive %d -> %d, target %g" % (spp, most, target)
        print("%-34s %7.2f s  %6.2f dB" % (label, seconds, psnr(frame, reference)), flush=True)


if __name__ == "__main__":
    main(*sys.argv[1:4])
