#!/usr/bin/env python3
"""Figures of the texture-realism experiment, drawn from the data files omnicam writes.

Usage: plot_texture_realism.py DIR   (DIR from `omnicam experiment texture-realism -o DIR`)

Reads DIR/data/detections.csv, DIR/data/ekf_<condition>.csv, DIR/data/histograms.json and
writes into DIR/figures/:
  detections_per_frame.png  true positives and false positives per frame (thesis Figs. 4.3/4.6)
  histograms.png            the trained colour histograms in RGB space (Figs. 4.4/4.5)
  ekf_path.png              truth, odometry and EKF estimate along thesis-loop (Fig. 4.7a)
  ekf_covariance.png        the EKF's position uncertainty along the path (Fig. 4.7b)
"""
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
from plot_files import save_figure  # noqa: E402


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def detections_per_frame(data, figures):
    rows = read_csv(os.path.join(data, "detections.csv"))
    conditions = list(dict.fromkeys(r["condition"] for r in rows))
    fig, axes = plt.subplots(len(conditions), 1, figsize=(9, 2.2 * len(conditions)), sharex=True, squeeze=False)
    for ax, condition in zip(axes[:, 0], conditions):
        mine = [r for r in rows if r["condition"] == condition]
        x = [int(r["pose_index"]) for r in mine]
        tp = [int(r["true_positives"]) for r in mine]
        fp = [int(r["false_positive_blobs"]) + int(r["false_identifications"]) for r in mine]
        visible = [int(r["visible_beacons"]) for r in mine]
        width = max(1.0, (x[1] - x[0]) * 0.4) if len(x) > 1 else 0.8
        ax.bar([v - width / 2 for v in x], tp, width=width, color="tab:green", label="true positives")
        ax.bar([v + width / 2 for v in x], fp, width=width, color="tab:red", label="false positives")
        ax.step(x, visible, where="mid", color="black", linewidth=0.8, label="visible beacons")
        ax.set_title(f"{condition}: {sum(tp)} true, {sum(fp)} false positives", fontsize=9)
        ax.set_ylabel("count")
        if max(fp + tp + [0]) > 40:  # hundreds of false positives next to a few true ones
            ax.set_yscale("symlog", linthresh=5)
            ax.yaxis.set_major_formatter(matplotlib.ticker.ScalarFormatter())
    axes[-1, 0].set_xlabel("thesis-loop frame")
    axes[0, 0].legend(fontsize=7, loc="upper right")
    fig.tight_layout()
    save_figure(fig, figures, "detections_per_frame.png", dpi=110)
    plt.close(fig)


def histograms(data, figures):
    with open(os.path.join(data, "histograms.json")) as f:
        sets = json.load(f)
    names = list(sets)
    colours = ["cyan", "magenta", "yellow"]
    fig = plt.figure(figsize=(4 * len(colours), 3.6 * len(names)))
    for row, name in enumerate(names):
        for col, colour in enumerate(colours):
            h = sets[name].get(colour)
            if h is None:
                continue
            ax = fig.add_subplot(len(names), len(colours), row * len(colours) + col + 1, projection="3d")
            for kind, marker in (("negative", "."), ("positive", "o")):
                bins = h[kind]
                if not bins:
                    continue
                if kind == "negative" and len(bins) > 3000:  # the most frequent negatives suffice to show the cloud
                    bins = sorted(bins, key=lambda b: -b[3])[:3000]
                biggest = max(b[3] for b in bins)
                sizes = [4 + 60 * math.sqrt(b[3] / biggest) for b in bins]
                rgb = [(b[0] / 255, b[1] / 255, b[2] / 255) for b in bins]
                ax.scatter([b[0] for b in bins], [b[1] for b in bins], [b[2] for b in bins], s=sizes, c=rgb,
                           marker=marker, alpha=0.9 if kind == "positive" else 0.35,
                           edgecolors="black" if kind == "positive" else "none", linewidths=0.3)
            ax.set_xlim(0, 255), ax.set_ylim(0, 255), ax.set_zlim(0, 255)
            ax.set_xlabel("R", fontsize=7), ax.set_ylabel("G", fontsize=7), ax.set_zlabel("B", fontsize=7)
            ax.tick_params(labelsize=6)
            ax.set_title(f"{name}: {colour} (rings positive, dots negative)", fontsize=8)
    fig.tight_layout()
    save_figure(fig, figures, "histograms.png", dpi=100)
    plt.close(fig)


def ekf(data, figures):
    files = sorted(f for f in os.listdir(data) if f.startswith("ekf_") and f.endswith(".csv"))
    conditions = [f[len("ekf_"):-len(".csv")] for f in files]
    columns = 2 if len(files) > 2 else len(files)
    rows = (len(files) + columns - 1) // columns
    fig, grid = plt.subplots(rows, columns, figsize=(5.5 * columns, 4.0 * rows), squeeze=False)
    axes = [list(grid.flatten())]
    fig2, axes2 = plt.subplots(1, 1, figsize=(8, 3.2))
    for ax, name, f in zip(axes[0], conditions, files):
        rows = read_csv(os.path.join(data, f))
        get = lambda key: [float(r[key]) for r in rows]  # noqa: E731
        ax.plot(get("true_x"), get("true_y"), "k-", linewidth=1.2, label="truth")
        ax.plot(get("odometry_x"), get("odometry_y"), "r--", linewidth=1, label="odometry")
        ax.plot(get("ekf_x"), get("ekf_y"), "b-", linewidth=1, label="EKF")
        ax.set_aspect("equal")
        ax.set_title(name, fontsize=9)
        ax.set_xlabel("x (m)")
        sigma = [100 * math.sqrt(max(0.0, (a + b) / 2)) for a, b in zip(get("p_xx"), get("p_yy"))]
        axes2.plot(range(len(sigma)), sigma, label=name)
    for ax in axes[0]:
        ax.set_ylabel("y (m)")
    axes[0][0].legend(fontsize=7)
    fig.tight_layout()
    save_figure(fig, figures, "ekf_path.png", dpi=110)
    axes2.set_xlabel("frame")
    axes2.set_ylabel("position σ (cm), sqrt of mean(P_xx, P_yy)")
    axes2.legend(fontsize=7)
    fig2.tight_layout()
    save_figure(fig2, figures, "ekf_covariance.png", dpi=110)
    plt.close(fig)
    plt.close(fig2)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    root = sys.argv[1]
    data, figures = os.path.join(root, "data"), os.path.join(root, "figures")
    os.makedirs(figures, exist_ok=True)
    detections_per_frame(data, figures)
    histograms(data, figures)
    ekf(data, figures)


if __name__ == "__main__":
    main()
