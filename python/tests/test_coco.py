"""COCO annotations of a rendered frame, decoded by an independent implementation of COCO's
compressed RLE (pycocotools' rleFrString, written out here), back to the instance masks exactly."""

import numpy as np

import omnicam


def decode_counts(counts):
    """pycocotools' maskApi.c rleFrString, in Python."""
    runs, p = [], 0
    while p < len(counts):
        x, k, more = 0, 0, True
        while more:
            c = ord(counts[p]) - 48
            x |= (c & 0x1F) << (5 * k)
            more = bool(c & 0x20)
            p += 1
            k += 1
            if not more and (c & 0x10):
                x |= -1 << (5 * k)
        if len(runs) > 2:
            x += runs[-2]
        runs.append(x)
    return runs


def mask_from_runs(runs, height, width):
    flat = np.zeros(height * width, dtype=bool)
    at, value = 0, False
    for run in runs:
        flat[at:at + run] = value
        at += run
        value = not value
    assert at == height * width
    return flat.reshape(width, height).T  # column-major


def test_every_annotation_decodes_to_its_instance_mask(robocup):
    frame = omnicam.Renderer(robocup).render((4.0, 3.2, 0.0), outputs=["instance", "class"])
    instance = frame["instance"]
    annotations = omnicam.coco_annotations(instance, robocup)
    names = {c["id"]: c["name"] for c in robocup.ids["classes"]}
    assert annotations and {names[a["category_id"]] for a in annotations} <= {"beacon", "goal"}
    for a in annotations:
        mask = instance == a["instance_id"]
        decoded = mask_from_runs(decode_counts(a["segmentation"]["counts"]), *a["segmentation"]["size"])
        np.testing.assert_array_equal(decoded, mask)
        rows, cols = np.nonzero(mask)
        assert a["bbox"] == [cols.min(), rows.min(), cols.max() - cols.min() + 1, rows.max() - rows.min() + 1]
        assert a["area"] == mask.sum() and a["iscrowd"] == 0
        assert frame["class"][rows[0], cols[0]] == a["category_id"]
    # Every visible instance of those classes is annotated, once.
    chosen = {c["id"] for c in robocup.ids["classes"] if c["name"] in ("beacon", "goal")}
    class_of = {i["id"]: i["class_id"] for i in robocup.ids["instances"]}
    visible = {int(i) for i in np.unique(instance) if i and class_of[int(i)] in chosen}
    assert sorted(a["instance_id"] for a in annotations) == sorted(visible)


def test_classes_can_be_chosen(robocup):
    frame = omnicam.Renderer(robocup).render((4.0, 3.2, 0.0), outputs=["instance"])
    floor = next(c["id"] for c in robocup.ids["classes"] if c["name"] == "floor")
    only_floor = omnicam.coco_annotations(frame["instance"], robocup, classes=[floor])
    assert only_floor and all(a["category_id"] == floor for a in only_floor)
