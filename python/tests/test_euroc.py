"""The EuRoC/ASL layout (docs/dataset-format.md, "EuRoC/ASL layout") read as a visual-inertial
odometry loader reads it: data.csv with csv, sensor.yaml with PyYAML, the images with Pillow, and
the omni (Mei) model projected by hand from T_BS and the intrinsics, against omnicam's own
projection."""

import csv
import json

import numpy as np
import pytest
import yaml
from PIL import Image

import omnicam

INTERVAL = 0.05


def euroc_dataset(source, tmp_path):
    scene = json.loads((source / "scenes" / "robocup2006.json").read_text())
    scene["rig"]["shutter"] = {"exposure_s": 0.01, "rolling": {"line_time_us": 25, "readout": "bottom-to-top"}}
    scene_file = tmp_path / "rolling.json"
    scene_file.write_text(json.dumps(scene))
    spec = tmp_path / "spec.json"
    spec.write_text(json.dumps({
        "format": "omnicam-dataset/1", "scene": str(scene_file), "size": 64, "euroc": True,
        "frame_interval_s": INTERVAL, "poses": {"list": [[0, 0, 0], [0.5, 0.2, 30], [1.0, -0.4, 75]]},
        "motion": {"velocity": [0.8, 0.0, 20.0]},
        "cameras": [{"name": "cam0"}, {"name": "cam1", "mount": {"x": 0.12, "y": -0.05, "yaw_deg": 90}}]}))
    omnicam.run_dataset(str(spec), str(tmp_path / "ds"))
    return tmp_path / "ds"


def read_sensor(folder):
    with open(folder / "sensor.yaml") as f:
        sensor = yaml.safe_load(f)
    t_bs = np.array(sensor["T_BS"]["data"], dtype=float).reshape(sensor["T_BS"]["rows"], sensor["T_BS"]["cols"])
    return sensor, t_bs


def mei_project(points_sensor, intrinsics):
    xi, fu, fv, pu, pv = intrinsics
    unit = points_sensor / np.linalg.norm(points_sensor, axis=1, keepdims=True)
    mx = unit[:, 0] / (unit[:, 2] + xi)
    my = unit[:, 1] / (unit[:, 2] + xi)
    return np.stack([fu * mx + pu, fv * my + pv], axis=1)


def test_a_loader_reads_every_camera_s_frames_timestamps_and_calibration(source, tmp_path):
    ds = euroc_dataset(source, tmp_path)
    manifest = json.loads((ds / "manifest.json").read_text())
    for camera in ("cam0", "cam1"):
        folder = ds / camera
        with open(folder / "data.csv", newline="") as f:
            rows = list(csv.reader(f))
        assert rows[0][0].startswith("#timestamp")
        stamps = [int(r[0]) for r in rows[1:]]
        assert stamps == [0, 50_000_000, 100_000_000]
        for stamp, (_, name) in zip(stamps, rows[1:]):
            assert name == f"{stamp}.png"
            image = np.asarray(Image.open(folder / "data" / name))
            assert image.shape[:2] == (64, 64) and image.dtype == np.uint8

        sensor, t_bs = read_sensor(folder)
        assert sensor["sensor_type"] == "camera" and sensor["camera_model"] == "omni"
        assert sensor["resolution"] == [64, 64]
        assert sensor["rate_hz"] == 1 / INTERVAL
        assert sensor["exposure_s"] == 0.01 and sensor["shutter"] == "rolling"
        # The spec's 25 µs, written in the shortest form that reads back exactly.
        assert sensor["line_time_s"] == 25e-6 and sensor["readout"] == "bottom-to-top"
        assert "line_time_s: 2.5e-05\n" in (folder / "sensor.yaml").read_text()
        assert np.allclose(t_bs[3], [0, 0, 0, 1]) and np.allclose(t_bs[:3, :3] @ t_bs[:3, :3].T, np.eye(3), atol=1e-15)
        assert sensor["distortion_coefficients"] == [0, 0, 0, 0]
        # Floats read as floats, whole ones included (rate_hz 20, T_BS's zeros), as typed readers expect.
        floats = [sensor["rate_hz"], sensor["exposure_s"], sensor["line_time_s"], *sensor["T_BS"]["data"],
                  *sensor["intrinsics"], *sensor["distortion_coefficients"]]
        assert all(type(v) is float for v in floats), [v for v in floats if type(v) is not float]

        # World points seen by the camera at frame 1, projected the way a VIO front end does:
        # world → body (the robot pose in the manifest) → sensor (T_BS inverted) → omni model.
        frame = manifest["frames"][1]
        x, y, yaw = (frame["pose"][k] for k in ("x", "y", "yaw_deg"))
        c, s = np.cos(np.radians(yaw)), np.sin(np.radians(yaw))
        t_wb = np.array([[c, -s, 0, x], [s, c, 0, y], [0, 0, 1, 0], [0, 0, 0, 1]])
        rng = np.random.default_rng(4)
        cam_pose = frame["cameras"][camera]["pose"]
        viewpoint = np.array([cam_pose["x"], cam_pose["y"], 0.4])
        # Points around the camera, below its viewpoint (the mirror images the floor and walls).
        angles = rng.uniform(-np.pi, np.pi, 200)
        ranges = rng.uniform(0.6, 3.0, 200)
        world = np.stack([viewpoint[0] + ranges * np.cos(angles), viewpoint[1] + ranges * np.sin(angles),
                          rng.uniform(0.0, 0.3, 200)], axis=1)
        homogeneous = np.hstack([world, np.ones((len(world), 1))])
        sensor_points = (np.linalg.inv(t_bs) @ np.linalg.inv(t_wb) @ homogeneous.T).T[:, :3]
        by_hand = mei_project(sensor_points, sensor["intrinsics"])
        rig = omnicam.Rig(manifest["cameras"][0]["rig"])
        ours = omnicam.Camera(rig).project(world, pose=(cam_pose["x"], cam_pose["y"], cam_pose["yaw_deg"]))
        seen = ~np.isnan(ours[:, 0])
        assert seen.sum() > 100
        # EuRoC's intrinsics put pixel centres at integers (OpenCV); omnicam's rasters at +0.5.
        assert np.max(np.abs(by_hand[seen] + 0.5 - ours[seen])) < 1e-6


def test_the_images_are_the_manifest_s_colour_frames(source, tmp_path):
    ds = euroc_dataset(source, tmp_path)
    dataset = omnicam.Dataset(ds, camera="cam1")
    assert len(dataset) == 3
    item = dataset[2]
    assert dataset.reader.frame(item["index"])["cameras"]["cam1"]["files"]["rgb"] == "cam1/data/100000000.png"
    assert omnicam.verify_dataset(str(ds))["ok"]
    assert item["velocity"] == (0.8, 0.0, 20.0)


def test_every_camera_s_sensor_file_says_its_stamps_are_the_exposure_start(source, tmp_path):
    # data.csv's stamps are each frame's exposure start, whatever the camera: the mirror's and a
    # lens camera's sensor.yaml both say so, where a reader looks for it.
    spec = tmp_path / "spec.json"
    spec.write_text(json.dumps({
        "format": "omnicam-dataset/1", "scene": str(source / "scenes" / "robocup2006.json"), "size": 32, "euroc": True,
        "poses": {"list": [[0, 0, 0]]},
        "cameras": [{"name": "mirror"},
                    {"name": "fisheye", "rig": {"height": 0.4, "lens": {"model": "fisheye_equidistant", "width": 32, "height": 24,
                                                                       "f_px": 8, "cx": 15.5, "cy": 11.5, "fov_deg": 180}}}]}))
    omnicam.run_dataset(str(spec), str(tmp_path / "ds"))
    for camera in ("mirror", "fisheye"):
        text = (tmp_path / "ds" / camera / "sensor.yaml").read_text()
        assert "Timestamps: exposure start." in text, (camera, text)
