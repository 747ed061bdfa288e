#!/usr/bin/env python3
"""Frames/s against added triangles, from `scene_scaling --csv CSV`: plot_scaling.py CSV SVG."""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    with open(sys.argv[1], newline="") as f:
        rows = list(csv.DictReader(f))
    fig, ax = plt.subplots(figsize=(6.4, 3.6))
    for arena in dict.fromkeys(r["arena"] for r in rows):
        mine = [r for r in rows if r["arena"] == arena and int(r["triangles"]) > 0]
        alone = [float(r["frames_per_second"]) for r in rows if r["arena"] == arena and int(r["triangles"]) == 0][0]
        line, = ax.plot([int(r["triangles"]) for r in mine], [float(r["frames_per_second"]) for r in mine], "o-",
                        label=f"{arena} + debris")
        ax.axhline(alone, color=line.get_color(), linestyle=":", linewidth=1, label=f"{arena} alone")
        ax.axhline(alone / 2, color=line.get_color(), linestyle="--", linewidth=0.7, alpha=0.6,
                   label=f"goal: 50 % of {arena}")
    ax.set_xscale("log")
    ax.set_ylim(bottom=0)
    ax.set_xlabel("added triangles")
    ax.set_ylabel("frames/s (360x360, 1 spp, exact)")
    ax.legend(fontsize=7, loc="lower left")
    fig.tight_layout()
    fig.savefig(sys.argv[2])


if __name__ == "__main__":
    main()
