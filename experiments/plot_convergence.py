#!/usr/bin/env python3
"""The figure of the realistic-convergence study, drawn from the data omnicam writes.

Usage: plot_convergence.py DIR   (DIR from `omnicam experiment realistic-convergence -o DIR`)

Reads DIR/data/convergence.csv and writes DIR/figures/convergence.svg: PSNR against the
converged reference and the share of outlier pixels per spp, one line per rendering setup (the
mean over the poses; dots: each pose), with the 35 dB target.
"""
import csv
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from plot_files import save_figure  # noqa: E402


def main():
    root = sys.argv[1]
    rows = defaultdict(lambda: defaultdict(list))
    order = []
    with open(os.path.join(root, "data", "convergence.csv"), encoding="utf-8") as f:
        for row in csv.DictReader(f):
            if row["setup"] not in order:
                order.append(row["setup"])
            rows[row["setup"]][int(row["spp"])].append((float(row["psnr_db"]), 100.0 * float(row["outlier_share"])))
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    for setup in order:
        spps = sorted(rows[setup])
        psnr = [sum(p for p, _ in rows[setup][s]) / len(rows[setup][s]) for s in spps]
        outliers = [sum(o for _, o in rows[setup][s]) / len(rows[setup][s]) for s in spps]
        line, = left.plot(spps, psnr, marker="o", label=setup)
        right.plot(spps, outliers, marker="o", label=setup, color=line.get_color())
        for s in spps:
            left.scatter([s] * len(rows[setup][s]), [p for p, _ in rows[setup][s]], s=8, color=line.get_color(), alpha=0.5)
    left.axhline(35.0, color="grey", linestyle="--", linewidth=1, label="target 35 dB")
    for axis in (left, right):
        axis.set_xscale("log", base=2)
        axis.set_xlabel("samples per pixel")
        axis.grid(True, which="both", alpha=0.3)
    left.set_ylabel("PSNR vs converged (dB, 8-bit sRGB)")
    right.set_ylabel("outlier pixels (%)")
    right.set_yscale("symlog", linthresh=0.01)
    left.legend()
    fig.suptitle("Realistic frames: Blender renders of the textured hall against their converged reference")
    fig.tight_layout()
    save_figure(fig, os.path.join(root, "figures"), "convergence.svg")


if __name__ == "__main__":
    main()
