"""COCO annotations of a rendered frame, decoded by an independent implementation of COCO's
compressed RLE (pycocotools' rleFrString, written out here), back to the instance masks exactly."""

import re

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
    frame = omnicam.Renderer(robocup).render((4.0, 3.2, 0.0), outputs=["instance", "semantic"])
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
        assert frame["semantic"][rows[0], cols[0]] == a["category_id"]
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
    # By name, as a spec's outputs.coco.classes names them: the same annotations.
    assert omnicam.coco_annotations(frame["instance"], robocup, classes=["floor"]) == only_floor
    # What the scene does not have is refused, not annotated as nothing.
    for classes, words in (([99], "99 is not a class id of the scene"), (["flor"], '"flor" is not a class of the scene'),
                           ("floor", "a list of class names or ids, not one string"), ([1.5], "class name or id (got float)")):
        with pytest.raises(omnicam.InputError, match=re.escape(words)):
            omnicam.coco_annotations(frame["instance"], robocup, classes=classes)
    foreign = frame["instance"].copy()
    foreign[0, 0] = 999
    with pytest.raises(omnicam.InputError, match="id 999 is not an instance of the scene"):
        omnicam.coco_annotations(foreign, robocup)


# A dataset's COCO files.

import json  # noqa: E402

import pytest  # noqa: E402

from conftest import SOURCE, run_cli  # noqa: E402


def write_spec(path, coco, frames=3):
    path.write_text(json.dumps({
        "format": "omnicam-dataset/1", "scene": str(SOURCE / "scenes" / "robocup2006.json"),
        "size": 128, "poses": {"path": "thesis-loop", "frames": frames},
        "cameras": [{"name": "front", "mount": {"x": 0.1, "y": 0.0, "yaw_deg": 0}},
                    {"name": "rear", "mount": {"x": -0.1, "y": 0.0, "yaw_deg": 180}}],
        "outputs": {"rgb": "png", "instance": True, "landmarks": True, "coco": coco}}))
    return str(path)


@pytest.fixture(scope="module")
def coco_dataset(tmp_path_factory):
    root = tmp_path_factory.mktemp("coco")
    spec = write_spec(root / "spec.json", True)
    omnicam.run_dataset(spec, str(root / "ds"))
    return root


def test_a_datasets_coco_file_decodes_to_its_instance_masks(coco_dataset):
    folder = coco_dataset / "ds"
    for camera in ("front", "rear"):
        coco = json.loads((folder / camera / "coco.json").read_text())
        dataset = omnicam.Dataset(folder, camera=camera)
        names = {c["id"]: c["name"] for c in coco["categories"]}
        assert set(names.values()) == {"beacon", "goal", "landmark"}
        assert [image["frame"] for image in coco["images"]] == [dataset[k]["index"] for k in range(len(dataset))]
        class_of = {i["id"]: i["class_id"] for i in dataset.instances}
        for k, image in enumerate(coco["images"]):
            item = dataset[k]
            assert (folder / camera / image["file_name"]).exists() and image["width"] == 128
            mine = [a for a in coco["annotations"] if a["image_id"] == image["id"]]
            objects = [a for a in mine if names[a["category_id"]] != "landmark"]
            for a in objects:
                mask = item["instance"] == a["instance_id"]
                decoded = mask_from_runs(decode_counts(a["segmentation"]["counts"]), *a["segmentation"]["size"])
                np.testing.assert_array_equal(decoded, mask)
                assert a["area"] == mask.sum()
            visible = {int(i) for i in np.unique(item["instance"])
                       if i and names.get(class_of[int(i)]) in ("beacon", "goal")}
            assert sorted(a["instance_id"] for a in objects) == sorted(visible)
            # The landmarks as keypoints: visible 2, occluded 1, not imaged 0, as the landmark file says.
            (keypoints,) = [a for a in mine if names[a["category_id"]] == "landmark"]
            for j, landmark in enumerate(item["landmarks"]["landmarks"]):
                x, y, v = keypoints["keypoints"][3 * j:3 * j + 3]
                if v:
                    assert [x, y] == landmark["centre"] and (v == 1) == landmark["occluded"]
                else:
                    assert not landmark["in_view"] or landmark["visible_fraction"] == 0 or \
                        not (0 <= landmark["centre"][0] < 128 and 0 <= landmark["centre"][1] < 128)
        assert len({a["id"] for a in coco["annotations"]}) == len(coco["annotations"])
    assert omnicam.Dataset(folder).verify()["ok"]
    manifest = json.loads((folder / "manifest.json").read_text())
    assert manifest["cameras"][0]["files"]["coco"]["path"] == "front/coco.json"


def test_a_resumed_and_a_sharded_run_write_the_same_coco_files(coco_dataset, tmp_path):
    import shutil

    spec = str(coco_dataset / "spec.json")
    # Resumed: a frame's files and the COCO files gone; the run renders that frame again.
    shutil.copytree(coco_dataset / "ds", tmp_path / "resumed")
    for camera in ("front", "rear"):
        (tmp_path / "resumed" / camera / "coco.json").unlink()
    (tmp_path / "resumed" / "front" / "rgb" / "000001.png").unlink()
    result = omnicam.run_dataset(spec, str(tmp_path / "resumed"))
    assert result["rendered"] == 1 and result["kept"] == 2
    # Sharded: no COCO file until the merge has every frame.
    code, _, err = run_cli("dataset", spec, "-o", tmp_path / "sharded", "--shard", "0/2")
    assert code == 0, err
    assert not (tmp_path / "sharded" / "front" / "coco.json").exists()
    code, _, err = run_cli("dataset", spec, "-o", tmp_path / "sharded", "--shard", "1/2")
    assert code == 0, err
    code, _, err = run_cli("dataset", "--merge", tmp_path / "sharded")
    assert code == 0, err
    for camera in ("front", "rear"):
        one_go = (coco_dataset / "ds" / camera / "coco.json").read_bytes()
        assert (tmp_path / "resumed" / camera / "coco.json").read_bytes() == one_go
        assert (tmp_path / "sharded" / camera / "coco.json").read_bytes() == one_go


def test_coco_classes_are_chosen_by_name(tmp_path):
    spec = write_spec(tmp_path / "spec.json", {"classes": ["goal"]}, frames=1)
    omnicam.run_dataset(spec, str(tmp_path / "ds"))
    coco = json.loads((tmp_path / "ds" / "front" / "coco.json").read_text())
    assert [c["name"] for c in coco["categories"]] == ["goal", "landmark"]
    bad = write_spec(tmp_path / "bad.json", {"classes": ["victim"]}, frames=1)
    with pytest.raises(omnicam.InputError, match='outputs.coco.classes: "victim" is not a class of the scene'):
        omnicam.run_dataset(bad, str(tmp_path / "bad"))
