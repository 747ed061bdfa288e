"""A researcher's first day: a victim dataset of the rescue maze, a colour-histogram detector
trained on part of it, scored on the rest against the dataset's COCO annotations.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/victim_detector.py out/victims

Writes OUT/maze.json, the dataset OUT/victims/ (COCO annotations in OUT/victims/cam0/coco.json),
OUT/scores.json (precision and recall per class) and OUT/detections.png (a test frame with the
COCO boxes in white and the detections in the class colour).
"""

import json
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.patches as patches  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import omnicam  # noqa: E402

FRAMES, TRAIN = 60, 40  # the first 40 frames train, the last 20 test
BINS = 8                # colour histogram bins per channel
COLOURS = {"victim": "#e41a1c", "debris": "#ff7f00", "ramp": "#4daf4a"}


def make_dataset(out):
    (out / "maze.json").write_text(json.dumps(omnicam.mapping_arena(seed=3)))
    spec = out / "victims.json"
    spec.write_text(json.dumps({
        "format": "omnicam-dataset/1", "scene": "maze.json", "size": 128, "spp": 4, "shading": "lit",
        "poses": {"random": {"count": FRAMES, "seed": 1, "region": [0, 0, 8, 6.4], "clearance": 0.25}},
        "outputs": {"rgb": "png", "depth": False, "instance": True, "semantic": True, "normal": False,
                    "landmarks": False, "coco": True}}))
    omnicam.run_dataset(str(spec), str(out / "victims"),
                        progress=lambda done, total: print(f"\rrendering {done}/{total}", end="", flush=True))
    print()
    return omnicam.Dataset(out / "victims", outputs=["rgb", "semantic"])


def colour_bins(rgba):
    """Each pixel's colour histogram bin (display-encoded colour, BINS per channel)."""
    rgb = np.clip(rgba[..., :3] / np.maximum(rgba[..., 3:], 1e-6), 0, 1) ** (1 / 2.2)
    q = np.minimum((rgb * BINS).astype(int), BINS - 1)
    return (q[..., 0] * BINS + q[..., 1]) * BINS + q[..., 2]


def train(dataset, frames, class_count):
    """P(class | colour bin) from the semantic masks of the training frames (every class, and 0)."""
    counts = np.ones((class_count, BINS ** 3))  # add-one smoothing
    for k in frames:
        item = dataset[k]
        seen = item["rgb"][..., 3] > 0.999
        np.add.at(counts, (item["semantic"][seen], colour_bins(item["rgb"])[seen]), 1)
    return counts / counts.sum(axis=0, keepdims=True)


def components(mask):
    """4-connected components of a boolean mask, as lists of (row, col)."""
    label = np.zeros(mask.shape, dtype=int)
    found = []
    for start in zip(*np.nonzero(mask)):
        if label[start]:
            continue
        found.append([])
        label[start] = len(found)
        stack = [start]
        while stack:
            r, c = stack.pop()
            found[-1].append((r, c))
            for rr, cc in ((r + 1, c), (r - 1, c), (r, c + 1), (r, c - 1)):
                if 0 <= rr < mask.shape[0] and 0 <= cc < mask.shape[1] and mask[rr, cc] and not label[rr, cc]:
                    label[rr, cc] = len(found)
                    stack.append((rr, cc))
    return found


def detect(model, item, class_ids, min_pixels=4):
    """Boxes [x, y, w, h] per class id: components of pixels whose likeliest class it is."""
    seen = item["rgb"][..., 3] > 0.999
    likeliest = np.where(seen, model.argmax(axis=0)[colour_bins(item["rgb"])], 0)
    boxes = {}
    for class_id in class_ids:
        boxes[class_id] = []
        for pixels in components(likeliest == class_id):
            if len(pixels) >= min_pixels:
                rows, cols = np.array(pixels).T
                boxes[class_id].append([cols.min(), rows.min(), cols.max() - cols.min() + 1, rows.max() - rows.min() + 1])
    return boxes


def iou(a, b):
    ix = max(0, min(a[0] + a[2], b[0] + b[2]) - max(a[0], b[0]))
    iy = max(0, min(a[1] + a[3], b[1] + b[3]) - max(a[1], b[1]))
    inter = ix * iy
    return inter / (a[2] * a[3] + b[2] * b[3] - inter)


def score(dataset, coco, model, frames, categories):
    """Precision and recall per class: a detection matches an unmatched COCO box of its class with IoU ≥ 0.5."""
    by_image = {}
    for a in coco["annotations"]:
        by_image.setdefault(a["image_id"], []).append(a)
    image_of_frame = {image["frame"]: image["id"] for image in coco["images"]}
    tally = {name: {"tp": 0, "fp": 0, "fn": 0} for name in categories.values()}
    shown = None
    for k in frames:
        item = dataset[k]
        truth = by_image.get(image_of_frame[item["index"]], [])
        found = detect(model, item, categories)
        for class_id, name in categories.items():
            boxes = [a["bbox"] for a in truth if a["category_id"] == class_id]
            unmatched = list(range(len(boxes)))
            for box in found[class_id]:
                best = max(unmatched, key=lambda j: iou(box, boxes[j]), default=None)
                if best is not None and iou(box, boxes[best]) >= 0.5:
                    unmatched.remove(best)
                    tally[name]["tp"] += 1
                else:
                    tally[name]["fp"] += 1
            tally[name]["fn"] += len(unmatched)
        if shown is None and any(a["category_id"] in categories and categories[a["category_id"]] == "victim" for a in truth):
            shown = (item, truth, found)
    for t in tally.values():
        t["ground_truth"] = t["tp"] + t["fn"]
        # None (null, "n/a"): a class never detected, or never present, has no precision or recall.
        t["precision"] = t["tp"] / (t["tp"] + t["fp"]) if t["tp"] + t["fp"] else None
        t["recall"] = t["tp"] / t["ground_truth"] if t["ground_truth"] else None
    return tally, shown


def draw(shown, categories, path):
    item, truth, found = shown
    figure, ax = plt.subplots(figsize=(5, 5))
    ax.imshow(np.clip(item["rgb"][..., :3], 0, 1) ** (1 / 2.2))
    for a in truth:
        if a["category_id"] in categories:
            x, y, w, h = a["bbox"]
            ax.add_patch(patches.Rectangle((x - 0.5, y - 0.5), w, h, fill=False, edgecolor="white", linewidth=1.5))
    for class_id, boxes in found.items():
        for x, y, w, h in boxes:
            ax.add_patch(patches.Rectangle((x - 0.5, y - 0.5), w, h, fill=False, linestyle="--",
                                           edgecolor=COLOURS.get(categories[class_id], "cyan"), linewidth=1.5))
    ax.set_title(f"frame {item['index']}: COCO boxes (white), detections (dashed)", fontsize=9)
    ax.set_axis_off()
    figure.tight_layout()
    figure.savefig(path, dpi=100)


def main(out_dir):
    out = pathlib.Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    dataset = make_dataset(out)
    coco = json.loads((out / "victims" / dataset.camera / "coco.json").read_text())
    categories = {c["id"]: c["name"] for c in coco["categories"] if "keypoints" not in c}
    model = train(dataset, range(TRAIN), len(dataset.classes))
    tally, shown = score(dataset, coco, model, range(TRAIN, len(dataset)), categories)
    (out / "scores.json").write_text(json.dumps(tally, indent=1))
    print(f"{'class':8} {'truth':>5} {'TP':>4} {'FP':>4} {'precision':>9} {'recall':>6}")
    for name, t in tally.items():
        shown_ratio = {key: "n/a" if t[key] is None else f"{t[key]:.2f}" for key in ("precision", "recall")}
        print(f"{name:8} {t['ground_truth']:5d} {t['tp']:4d} {t['fp']:4d} {shown_ratio['precision']:>9} {shown_ratio['recall']:>6}")
    if shown:
        draw(shown, categories, out / "detections.png")
    print("wrote", out / "scores.json")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: victim_detector.py OUT_DIR")
    main(sys.argv[1])
