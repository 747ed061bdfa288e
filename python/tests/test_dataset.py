"""omnicam.Dataset: a dataset folder read back as numpy, checked against the files read on their
own, against a fresh render of the same pose, and as untrusted input."""

import json
import multiprocessing
import os
import pickle

import numpy as np
import pytest

import omnicam
from conftest import SOURCE

SIZE = 64


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    root = tmp_path_factory.mktemp("dataset")
    spec = root / "spec.json"
    spec.write_text(json.dumps({
        "format": "omnicam-dataset/1", "scene": str(SOURCE / "scenes" / "robocup2006.json"),
        "size": SIZE, "poses": {"path": "thesis-loop", "frames": 3},
        "cameras": [{"name": "front", "mount": {"x": 0.1, "y": 0.0, "yaw_deg": 0}},
                    {"name": "rear", "mount": {"x": -0.1, "y": 0.0, "yaw_deg": 180}}],
        "outputs": {"rgb": "exr", "depth": True, "instance": True, "semantic": True, "normal": True,
                    "landmarks": True}}))
    omnicam.run_dataset(str(spec), str(root / "ds"))
    return root / "ds"


def test_items_hold_every_output_as_the_files_hold_them(folder):
    dataset = omnicam.Dataset(folder)
    assert len(dataset) == 3 and dataset.cameras == ["front", "rear"] and dataset.camera == "front"
    item = dataset[1]
    manifest = json.loads((folder / "manifest.json").read_text())
    record = manifest["frames"][1]
    assert item["index"] == record["index"] and item["timestamp"] == record["timestamp"]
    assert item["pose"] == pytest.approx(tuple(record["cameras"]["front"]["pose"][k] for k in ("x", "y", "yaw_deg")))
    files = {kind: str(folder / f["path"]) for kind, f in record["cameras"]["front"]["files"].items()}
    np.testing.assert_array_equal(item["rgb"], omnicam.read_image(files["rgb"]))
    np.testing.assert_array_equal(item["depth"], omnicam.read_exr_channels(files["depth"], ["Z"])[..., 0])
    np.testing.assert_array_equal(item["normal"], omnicam.read_exr_channels(files["normal"], ["X", "Y", "Z"]))
    np.testing.assert_array_equal(item["instance"], omnicam.read_uint16_png(files["instance"]))
    np.testing.assert_array_equal(item["semantic"], omnicam.read_uint16_png(files["semantic"]))
    assert item["landmarks"] == json.loads(open(files["landmarks"]).read())
    assert item["intrinsics"]["model"] == "mei_unified" and item["intrinsics"]["width"] == SIZE
    assert item["recording"] is None  # nothing drawn
    rear = dataset[1, "rear"]
    assert rear["camera"] == "rear" and not np.array_equal(rear["depth"], item["depth"])
    assert dataset[-1]["index"] == manifest["frames"][-1]["index"]
    with pytest.raises(IndexError):
        dataset[3]
    assert dataset[np.int64(1)]["index"] == dataset[1]["index"]  # numpy's integers index too
    with pytest.raises(TypeError, match="frame positions .* not str"):
        dataset["a"]


def test_a_frame_is_what_the_renderer_draws_at_its_pose(folder, robocup):
    item = omnicam.Dataset(folder, outputs=["depth", "instance"])[2]
    fresh = omnicam.Renderer(robocup).render(item["pose"], size=SIZE, outputs=["depth", "instance"])
    np.testing.assert_array_equal(item["depth"], fresh["depth"])
    np.testing.assert_array_equal(item["instance"], fresh["instance"])
    assert set(item) >= {"depth", "instance"} and "rgb" not in item
    with pytest.raises(KeyError, match=r"'rgb': not read: this Dataset reads outputs depth, instance .give outputs="):
        item["rgb"]


def _first_depth_sum(dataset):
    return float(dataset[0]["depth"].sum())


def _first_item(dataset):
    return dataset[0]


def test_it_pickles_into_worker_processes(folder):
    dataset = omnicam.Dataset(folder, outputs=["depth"])
    again = pickle.loads(pickle.dumps(dataset))
    np.testing.assert_array_equal(again[0]["depth"], dataset[0]["depth"])
    with multiprocessing.get_context("spawn").Pool(2) as pool:
        sums = pool.map(_first_depth_sum, [dataset, dataset])
        # Whole items come back from the workers, as a DataLoader's do: their rig included.
        returned = pool.map(_first_item, [dataset])[0]
    assert sums == [float(dataset[0]["depth"].sum())] * 2
    item = dataset[0]
    assert returned["rig"] == item["rig"] and returned["pose"] == item["pose"]
    np.testing.assert_array_equal(returned["depth"], item["depth"])
    with pytest.raises(KeyError, match="not read"):
        returned["rgb"]  # its missing keys still say why
    assert pickle.loads(pickle.dumps(omnicam.Rig({"height": 0.3}))) == omnicam.Rig({"height": 0.3})


def test_a_changed_file_fails_its_hash_check_and_a_link_is_never_followed(folder, tmp_path):
    import shutil

    copy = tmp_path / "copy"
    shutil.copytree(folder, copy, symlinks=True)
    depth = copy / "front" / "depth" / "000000.exr"
    data = bytearray(depth.read_bytes())
    data[-1] ^= 0x01
    depth.write_bytes(bytes(data))
    with pytest.raises(omnicam.InputError, match="changed since it was written"):
        omnicam.Dataset(copy, outputs=["depth"], check_hashes=True)[0]
    assert not omnicam.Dataset(copy).verify()["ok"]
    instance = copy / "front" / "instance" / "000000.png"
    instance.unlink()
    os.symlink(folder / "front" / "instance" / "000000.png", instance)
    with pytest.raises(omnicam.InputError, match="link"):
        omnicam.Dataset(copy, outputs=["instance"])[0]


def test_unknown_cameras_outputs_and_folders_are_refused(folder, tmp_path):
    # Bad arguments are bad input (InputError, a ValueError), as everywhere else in omnicam.
    with pytest.raises(omnicam.InputError, match="camera 'side'"):
        omnicam.Dataset(folder, camera="side")
    with pytest.raises(omnicam.InputError, match="output 'flow'"):
        omnicam.Dataset(folder, outputs=["flow"])
    with pytest.raises(omnicam.InputError, match="output 'dept' .*did you mean depth\\?"):
        omnicam.Dataset(folder, outputs=["dept"])
    with pytest.raises(TypeError, match=r"^outputs must be a list of output names, such as \['depth'\] \(got str 'depth'\)$"):
        omnicam.Dataset(folder, outputs="depth")
    with pytest.raises(omnicam.InputError):
        omnicam.Dataset(tmp_path / "nothing")
    with pytest.raises(KeyError, match=r"camera 'side' is not in frame 0 \(its cameras: front, rear\)"):
        omnicam.Dataset(folder)[0, "side"]
    assert omnicam.Dataset(folder).verify()["ok"]


@pytest.fixture(scope="module")
def layered(tmp_path_factory, folder):
    """The same frames as `folder`, one OpenEXR per frame and camera."""
    root = tmp_path_factory.mktemp("layered")
    spec = json.loads((folder / "manifest.json").read_text())["spec"]
    spec["layout"] = "multilayer"
    del spec["outputs"]["rgb"]
    spec["outputs"]["coco"] = True
    (root / "spec.json").write_text(json.dumps(spec))
    omnicam.run_dataset(str(root / "spec.json"), str(root / "ds"))
    return root / "ds"


def test_a_multilayer_dataset_reads_as_the_files_layout_reads(folder, layered):
    files, layers = omnicam.Dataset(folder, camera="rear"), omnicam.Dataset(layered, camera="rear", check_hashes=True)
    assert layers.header["outputs"]["layout"] == "multilayer" and "coco" in layers.outputs
    assert set(layers.outputs) <= set(omnicam.dataset.OUTPUTS) and "multilayer" not in omnicam.dataset.OUTPUTS
    for index in range(3):
        a, b = files[index], layers[index]
        for output in ("depth", "normal", "instance", "semantic"):
            assert b[output].dtype == a[output].dtype and b[output].shape == a[output].shape
            np.testing.assert_array_equal(b[output], a[output], err_msg=output)
        # Colour: float32 in the files layout's EXR, half in the frame's.
        np.testing.assert_allclose(b["rgb"], a["rgb"], rtol=2.0 ** -11, atol=1e-7)
        assert b["landmarks"] == a["landmarks"]
        assert b["coco"]["frame"] == a["index"] and b["coco"]["camera"] == "rear"
    # The camera's COCO file gathers every frame's part.
    coco = json.loads((layered / "rear" / "coco.json").read_text())
    assert [image["file_name"] for image in coco["images"]] == [f"multilayer/00000{i}.exr" for i in range(3)]
    assert len(coco["annotations"]) == sum(len(layers[i]["coco"]["annotations"]) + 1 for i in range(3))
    frame = layered / "rear" / "multilayer" / "000001.exr"
    assert omnicam.read_exr_channels(str(frame), ["depth.Z"])[..., 0].tolist() == files[1]["depth"].tolist()
    # Ids as the integers they are (read as floats they would be scaled by 2^-32).
    ids = omnicam.read_exr_channels(frame, ["instance.I", "semantic.I"])
    assert ids.dtype == np.uint32 and ids.shape == (*files[1]["instance"].shape, 2)
    np.testing.assert_array_equal(ids[..., 0], files[1]["instance"])
    np.testing.assert_array_equal(ids[..., 1], files[1]["semantic"])
    assert ids[..., 0].max() > 1
    with pytest.raises(omnicam.InputError, match="channels of two kinds"):
        omnicam.read_exr_channels(frame, ["depth.Z", "instance.I"])
    with pytest.raises(omnicam.InputError, match=r"no channel \"Y\" \(it has .*depth\.Z"):
        omnicam.read_exr_channels(frame, ["Y"])


def test_items_carry_the_recording_camera_drawn_for_them(tmp_path):
    """A drawn recording camera's values per frame and camera, as the manifest states them, and
    the frame is what render() records with them."""
    spec = tmp_path / "spec.json"
    spec.write_text(json.dumps({
        "format": "omnicam-dataset/1", "scene": str(SOURCE / "scenes" / "robocup2006.json"),
        "size": 32, "poses": {"path": "thesis-loop", "frames": 2},
        "cameras": [{"name": "front"}, {"name": "rear", "mount": {"x": -0.1, "y": 0.0, "yaw_deg": 180}}],
        "recording": {"preset": "webcam", "seed": 7},
        "outputs": {"rgb": "png", "depth": False, "instance": False, "semantic": False, "normal": False, "landmarks": False}}))
    omnicam.run_dataset(str(spec), str(tmp_path / "ds"))
    manifest = json.loads((tmp_path / "ds" / "manifest.json").read_text())
    dataset = omnicam.Dataset(tmp_path / "ds")
    drawn = []
    for position, record in enumerate(manifest["frames"]):
        for camera in ("front", "rear"):
            item = dataset[position, camera]
            assert item["recording"] == record["cameras"][camera]["recording"]
            drawn.append(json.dumps(item["recording"], sort_keys=True))
    assert len(set(drawn)) == 4  # a camera per frame and camera
    # A key the item lacks says why: an output the dataset never wrote, one not read, a typo.
    with pytest.raises(KeyError, match="the dataset holds no landmarks .its spec's outputs wrote: rgb"):
        dataset[0]["landmarks"]
    with pytest.raises(KeyError, match=r"did you mean 'recording'\?"):
        dataset[0]["recordng"]
    assert isinstance(dataset[0], dict) and "landmarks" not in dataset[0]



def test_a_fixed_recording_camera_is_each_items_recording_too(tmp_path, robocup):
    """A recording camera that draws nothing is no "None": each item carries its values (the
    spec's, every setting that acts), and render() records the frame with them."""
    recording = {"exposure_ev": 0.3, "jpeg_quality": 80, "white_balance": [1.12, 1.0, 0.84]}
    spec = tmp_path / "spec.json"
    spec.write_text(json.dumps({
        "format": "omnicam-dataset/1", "scene": str(SOURCE / "scenes" / "robocup2006.json"),
        "size": 32, "poses": {"path": "thesis-loop", "frames": 2}, "recording": recording,
        "outputs": {"rgb": "png", "depth": False, "instance": False, "semantic": False, "normal": False, "landmarks": False}}))
    omnicam.run_dataset(str(spec), str(tmp_path / "ds"))
    dataset = omnicam.Dataset(tmp_path / "ds")
    item = dataset[1]
    assert item["recording"] is not None
    for key, value in recording.items():
        assert item["recording"][key] == value, key
    assert dataset[0]["recording"] == item["recording"]
    again = omnicam.Renderer(robocup).render(item["robot_pose"], size=32, recording=item["recording"], frame=1)
    np.testing.assert_allclose(again["rgb"], item["rgb"], atol=1e-6)


def test_a_scene_reads_files_outside_its_folder_only_when_the_caller_allows_it(tmp_path):
    (tmp_path / "scene").mkdir()
    (tmp_path / "scene" / "scene.json").write_bytes((SOURCE / "tests" / "bad_inputs" / "scenes" / "texture_outside.json").read_bytes())
    (tmp_path / "outside.png").write_bytes((SOURCE / "tests" / "bad_inputs" / "outside.png").read_bytes())
    spec = tmp_path / "spec.json"
    spec.write_text(json.dumps({"format": "omnicam-dataset/1", "scene": "scene/scene.json", "size": 16,
                                "poses": {"list": [[0, 0, 0]]}, "outputs": {"rgb": "png"}}))
    with pytest.raises(omnicam.InputError) as raised:
        omnicam.run_dataset(spec, tmp_path / "ds")
    # This front's own keyword, which run_dataset takes, as load_scene does.
    assert str(raised.value).endswith("resolves outside the scene's folder (pass allow_outside_files=True to permit it)")
    assert not (tmp_path / "ds").exists()
    assert omnicam.run_dataset(spec, tmp_path / "ds", allow_outside_files=True)["rendered"] == 1
