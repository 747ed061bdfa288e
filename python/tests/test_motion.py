"""Time in the camera from Python (docs/motion.md): a shutter on the rig, a velocity per render,
each frame's velocity and vibrating rig read back from a dataset."""

import json

import numpy as np
import pytest

import omnicam
from conftest import run_cli

ROLLING = {"exposure_s": 0.02, "rolling": {"line_time_us": 150, "readout": "left-to-right"}}


def test_the_shutter_and_tilt_are_rig_properties_read_strictly(robocup):
    rig = robocup.rig
    assert rig.shutter is None and rig.tilt_deg is None
    rig.shutter = ROLLING
    rig.tilt_deg = [1.5, -0.5]
    assert rig.shutter["rolling"] == ROLLING["rolling"]
    assert rig.tilt_deg == [1.5, -0.5]
    with pytest.raises(omnicam.InputError, match="readout"):
        rig.shutter = {"exposure_s": 0.01, "rolling": {"line_time_us": 10, "readout": "sideways"}}
    with pytest.raises(omnicam.InputError, match="tilt_deg"):
        rig.tilt_deg = [45, 0]


def test_a_moving_render_is_the_cli_s_bit_for_bit(robocup, tmp_path):
    rig = robocup.rig.resized(48)
    rig.shutter = ROLLING
    scene_file = tmp_path / "rolling.json"
    scene = json.loads(open(robocup.path).read())
    scene["rig"] = rig.to_dict()
    scene_file.write_text(json.dumps(scene))
    pose, velocity = (0.3, -0.2, 40.0), (1.0, 0.2, 90.0)
    ours = omnicam.render(robocup, pose, rig=rig, spp=4, velocity=velocity)["rgb"]
    code, out, err = run_cli("render", scene_file, "--spp", "4", "--pose=0.3,-0.2,40", "--velocity", "1,0.2,90",
                             "-o", tmp_path / "cli.exr")
    assert code == 0, out + err
    assert np.array_equal(ours, omnicam.read_image(str(tmp_path / "cli.exr")))
    still = omnicam.render(robocup, pose, rig=rig, spp=4)["rgb"]
    assert not np.array_equal(ours, still)
    # With the shutter an instant, a velocity would change nothing: refused, as the CLI refuses it.
    rig.shutter = None
    with pytest.raises(omnicam.InputError, match="velocity: the rig's shutter is an instant"):
        omnicam.render(robocup, pose, rig=rig, spp=4, velocity=velocity)
    code, _, err = run_cli("render", robocup.path, "--size", "48", "--velocity", "1,0.2,90", "-o", tmp_path / "x.png")
    assert code == 2 and "--velocity: the rig's shutter is an instant" in err


def test_a_bad_velocity_or_a_shutter_the_engine_cannot_render_is_an_input_error(robocup):
    rig = robocup.rig.resized(32)
    rig.shutter = {"exposure_s": 0.01}
    with pytest.raises(omnicam.InputError, match="velocity"):
        omnicam.render(robocup, rig=rig, velocity=(500.0, 0.0, 0.0))
    rig.shutter = ROLLING
    with pytest.raises(omnicam.InputError, match="global shutter only"):
        omnicam.render(robocup, rig=rig, velocity=(1.0, 0.0, 0.0), engine="blender")


def test_a_dataset_item_carries_its_velocity_and_its_vibrating_rig(source, tmp_path, robocup):
    # The scene with a global shutter: a dataset's motion needs one to be seen.
    scene = json.loads((source / "scenes" / "robocup2006.json").read_text())
    scene["rig"]["shutter"] = {"exposure_s": 0.01}
    (tmp_path / "moving.json").write_text(json.dumps(scene))
    moving = omnicam.load_scene(tmp_path / "moving.json")
    spec = tmp_path / "spec.json"
    spec.write_text(json.dumps({
        "format": "omnicam-dataset/1", "scene": "moving.json", "size": 40,
        "outputs": {"rgb": "exr"}, "poses": {"list": [[0, 0, 0], [0.4, 0.1, 15]]},
        "motion": {"velocity": [0.5, 0.0, 30.0]},
        "vibration": {"seed": 3, "rig_tilt_deg": [1.0, 1.0], "camera_offset_mm": [0.5, 0.5, 0.5]}}))
    omnicam.run_dataset(str(spec), str(tmp_path / "ds"))
    dataset = omnicam.Dataset(tmp_path / "ds")
    assert dataset.rig() == moving.rig.resized(40)
    first, second = dataset[0], dataset[1]
    assert first["velocity"] == (0.5, 0.0, 30.0)
    assert first["rig"] != second["rig"] and first["rig"] != dataset.rig()
    assert all(abs(t) <= 1.0 for t in second["rig"].tilt_deg)
    # The item's rig, pose and velocity render the item's image again, moving through its shutter.
    again = omnicam.render(moving, second["pose"], rig=second["rig"], velocity=second["velocity"])["rgb"]
    assert np.array_equal(again, second["rgb"])
    assert not np.array_equal(again, omnicam.render(moving, second["pose"], rig=second["rig"])["rgb"])


def test_a_dataset_item_carries_its_robot_tilt(source, tmp_path):
    spec = tmp_path / "spec.json"
    spec.write_text(json.dumps({
        "format": "omnicam-dataset/1", "scene": str(source / "scenes" / "robocup2006.json"), "size": 24,
        "outputs": {"rgb": "exr"}, "poses": {"list": [[0, 0, 0], [0.4, 0.1, 15]]},
        "robot": {"tilt_deg": [1.0, -2.0]}, "vibration": {"seed": 3, "robot_tilt_deg": [0.5, 0.5]}}))
    omnicam.run_dataset(str(spec), str(tmp_path / "ds"))
    dataset = omnicam.Dataset(tmp_path / "ds")
    tilts = [dataset[i]["robot_tilt_deg"] for i in range(2)]
    assert tilts[0] != tilts[1]
    for roll, pitch in tilts:
        assert abs(roll - 1.0) <= 0.5 and abs(pitch + 2.0) <= 0.5
    assert dataset[0]["rig"] == dataset.rig()  # the robot rocks; the rig itself is not shaken


def test_a_moving_frame_s_depth_lies_along_the_rays_at_its_pixels_times(robocup):
    """A rolling shutter's depth is taken at each pixel's line time (docs/motion.md, "AOVs"):
    pixel_times gives those instants; rays at them put every floor pixel's depth on z = 0, at
    points that project (with the velocity) back onto their pixels. Rays at the frame's start put
    them centimetres away."""
    rig = robocup.rig.resized(96)
    rig.shutter = ROLLING
    camera = omnicam.Camera(rig)
    pose, velocity = (0.3, -0.2, 40.0), (2.0, 0.5, 120.0)
    frame = omnicam.Renderer(robocup).render(pose, rig=rig, velocity=velocity, outputs=["depth", "semantic"])
    floor_id = next(c["id"] for c in robocup.ids["classes"] if c["name"] == "floor")
    rows, cols = np.nonzero(frame["semantic"] == floor_id)
    assert rows.size > 400
    centres = np.column_stack([cols + 0.5, rows + 0.5])
    times = camera.pixel_times(centres)
    # Closed form (shutter.h): left-to-right, each column a line of 150 µs, mid-exposure of 0.02 s.
    np.testing.assert_allclose(times, cols * 150e-6 + 0.01, rtol=0, atol=1e-15)
    origins, directions = camera.rays(centres, pose=pose, velocity=velocity, time=times)
    floor = origins + frame["depth"][rows, cols, None] * directions
    assert np.abs(floor[:, 2]).max() < 1e-5
    # The other way round: project with the velocity puts each floor point back on its pixel.
    np.testing.assert_allclose(camera.project(floor, pose=pose, velocity=velocity), centres, atol=1e-4)
    # Rays at the frame's start place the same depths elsewhere on the floor, off their pixels.
    origins, directions = camera.rays(centres, pose=pose, velocity=velocity)
    early = origins + frame["depth"][rows, cols, None] * directions
    assert np.linalg.norm(early - floor, axis=1).max() > 0.01
    assert np.abs(camera.project(early, pose=pose, velocity=velocity) - centres).max() > 0.5
    assert np.isnan(camera.pixel_times(np.array([[-0.5, 3.0], [96.0, 3.0], [np.nan, 1.0]]))).all()
