"""Figures of `omnicam experiment calibration` (experiments/calibration_study.h).

Run by omnicam with the results folder as its only argument: reads results.json and
data/residual_*.f32, writes figures/calibration_study_error.svg and
figures/calibration_study_residuals.png.
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
matplotlib.rcParams["svg.fonttype"] = "none"  # text as text: a smaller SVG
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from plot_files import save_figure  # noqa: E402

HEADLINE_DISTANCE_M = 0.5
SOURCES = [("exact", "exact corners"), ("detected_noisy", "recorded detections")]


def median_over_runs(rig, source, value):
    """The median over the seeds that converged, as the report's tables."""
    values = [value(run) for run in rig["runs"] if run["source"] == source and run["converged"]]
    return float(np.median(values)) if values else float("nan")


def held_out_px(run_or_rig_list, distance):
    for h in run_or_rig_list:
        if h["distance_m"] == distance:
            return h["rms_px"]
    return float("nan")


def error_figure(results, out):
    kinds = [k for k in ("lateral", "axial", "tilt") if any(r["kind"] == k for r in results["rigs"])]
    fig, axes = plt.subplots(1, len(kinds), figsize=(4.2 * len(kinds), 4.6), squeeze=False)
    for ax, kind in zip(axes[0], kinds):
        for lens, style in ((False, "-"), (True, "--")):
            rigs = [r for r in results["rigs"] if r["lens"] == lens and r["kind"] in ("ideal", kind)]
            if len(rigs) < 2:
                continue
            rigs.sort(key=lambda r: r["amount"])
            x = [r["amount"] for r in rigs]
            suffix = ", lens" if lens else ""
            for (source, title), colour in zip(SOURCES, ("tab:blue", "tab:orange")):
                ax.plot(x, [median_over_runs(r, source, lambda run: run["rms_px"]) for r in rigs], style, color=colour,
                        marker="o", markersize=3, alpha=0.5, label=f"training RMS, {title}{suffix}")
                ax.plot(x, [median_over_runs(r, source, lambda run: held_out_px(run["held_out"], HEADLINE_DISTANCE_M))
                            for r in rigs], style, color=colour, marker="s", markersize=4,
                        label=f"held-out at 0.5 m, {title}{suffix}")
            ax.plot(x, [held_out_px(r["best_fit_held_out"], HEADLINE_DISTANCE_M) for r in rigs], style, color="grey",
                    label=f"best central model at 0.5 m{suffix}")
        ax.axhline(0.3, color="green", linewidth=0.8, linestyle=":")
        ax.axhline(1.0, color="red", linewidth=0.8, linestyle=":")
        ax.set_yscale("log")
        ax.set_ylim(bottom=1e-3)  # exact corners on exact rigs reach 1e-13: below the plot's interest
        ax.set_xlabel("tilt (deg)" if kind == "tilt" else f"{kind} offset (mm)")
        ax.set_ylabel("RMS error (px)")
        ax.set_title(kind)
        ax.grid(True, which="both", alpha=0.3)
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, fontsize=7, loc="lower center", ncol=3)
    fig.tight_layout(rect=(0, 0.2, 1, 1))
    save_figure(fig, os.path.join(out, "figures"), "calibration_study_error.svg")


def residual_figure(results, out):
    size = results["image_size"]
    panels = []
    for rig in results["rigs"]:
        for source, title in SOURCES:
            path = os.path.join(out, "data", f"residual_{rig['slug']}_{source}.f32")
            if os.path.exists(path):
                panels.append((f"{rig['label']}\n{title}", np.fromfile(path, dtype="<f4").reshape(size, size)))
    if not panels:
        return
    columns = len(SOURCES)
    rows = (len(panels) + columns - 1) // columns
    fig, axes = plt.subplots(rows, columns, figsize=(3.0 * columns, 2.9 * rows), squeeze=False)
    image = None
    for ax in axes.flat:
        ax.axis("off")
    for ax, (title, data) in zip(axes.flat, panels):
        image = ax.imshow(np.ma.masked_invalid(data), cmap="magma", vmin=0.0, vmax=3.0)
        ax.set_title(title, fontsize=8)
    fig.colorbar(image, ax=axes.ravel().tolist(), shrink=0.8, label="px at 0.5 m")
    save_figure(fig, os.path.join(out, "figures"), "calibration_study_residuals.png", dpi=72)


def main():
    out = sys.argv[1]
    with open(os.path.join(out, "results.json")) as f:
        results = json.load(f)
    os.makedirs(os.path.join(out, "figures"), exist_ok=True)
    error_figure(results, out)
    residual_figure(results, out)


if __name__ == "__main__":
    main()
