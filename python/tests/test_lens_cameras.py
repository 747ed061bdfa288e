"""Lens cameras (docs/lens-cameras.md) from Python: rigs, cameras, renders, a mixed dataset, and
its Kalibr files checked by Kalibr's own rules and projected with aslam_cv's formulas, written
here independently of omnicam."""

import json
import math

import numpy as np
import pytest
import yaml

import omnicam
from conftest import SOURCE, run_cli

LENSES = {
    "fisheye": {"model": "kannala_brandt", "width": 96, "height": 72, "fx": 30, "fy": 30.5, "cx": 48.2, "cy": 35.1,
                "k": [0.02, -0.005, 0.001, -0.0002], "max_theta_deg": 85, "rotation_deg": [0, 10, 0]},
    "ds": {"model": "double_sphere", "width": 96, "height": 72, "fx": 36, "fy": 36, "xi": -0.2, "alpha": 0.6,
           "rotation_deg": [0, -30, 40]},
    "eucm": {"model": "eucm", "width": 96, "height": 72, "fx": 45, "fy": 44, "alpha": 0.6, "beta": 1.1,
             "rotation_deg": [5, 0, -60]},
    "pano": {"model": "equirectangular", "width": 128, "height": 64},
}


def lens_rig(name, height=0.35):
    return omnicam.Rig({"height": height, "lens": LENSES[name]})


def test_a_lens_rig_is_a_camera_whose_rays_and_projections_invert(robocup):
    for name in LENSES:
        camera = omnicam.Camera(lens_rig(name))
        assert camera.model == LENSES[name]["model"] and camera.central
        assert (camera.width, camera.height) == (LENSES[name]["width"], LENSES[name]["height"])
        pixels = np.array([[x + 0.5, y + 0.5] for y in range(0, camera.height, 5) for x in range(0, camera.width, 5)])
        seen = camera.images(pixels)
        assert seen.sum() > len(pixels) // 3
        origins, directions = camera.rays(pixels[seen], pose=(1.0, -0.5, 30.0))
        back = camera.project(origins + 2.5 * directions, pose=(1.0, -0.5, 30.0))
        np.testing.assert_allclose(back, pixels[seen], atol=1e-7)
        assert camera.describe()["model"] == LENSES[name]["model"]


def test_a_lens_rig_reads_back_from_its_dict_and_renders_its_own_size(robocup):
    rig = lens_rig("fisheye")
    assert omnicam.Rig(rig.to_dict()) == rig and not rig.ideal and omnicam.Rig().lens is None
    assert rig.lens["model"] == "kannala_brandt" and rig.lens["k"] == LENSES["fisheye"]["k"]
    frame = omnicam.Renderer(robocup).render((0.0, 0.0, 0.0), rig=rig, outputs=["rgb", "depth"])
    assert frame["rgb"].shape == (72, 96, 4) and frame["depth"].shape == (72, 96)
    with pytest.raises(omnicam.InputError, match=r"rig\.lens\.xi: unknown field"):
        omnicam.Rig({"lens": dict(LENSES["fisheye"], xi=0.5)})
    # A scene's or sidecar's {"rig": ...} given whole is told apart from a typo.
    with pytest.raises(omnicam.InputError, match=r"rig\.rig: a rig inside the rig: give the rig's own fields"):
        omnicam.Rig({"rig": rig.to_dict()})


@pytest.fixture(scope="module")
def mixed(tmp_path_factory):
    root = tmp_path_factory.mktemp("mixed")
    cameras = [{"name": "omni", "mount": {"x": 0.0, "y": 0.0, "yaw_deg": 0}}]
    cameras += [{"name": name, "mount": {"x": 0.0, "y": 0.0, "yaw_deg": 0},
                 "rig": {"height": 0.35, "lens": LENSES[name]}} for name in LENSES]
    (root / "spec.json").write_text(json.dumps({
        "format": "omnicam-dataset/1", "scene": str(SOURCE / "scenes" / "robocup2006.json"),
        "poses": {"list": [[0.5, -0.3, 20.0], [1.5, 0.4, -70.0]]}, "cameras": cameras,
        "outputs": {"rgb": "png", "depth": True, "instance": True, "semantic": True, "normal": True, "landmarks": True,
                    "coco": True}}))
    omnicam.run_dataset(str(root / "spec.json"), str(root / "ds"))
    return root / "ds"


def test_a_mirror_and_lens_cameras_make_one_dataset_that_verifies(mixed):
    report = omnicam.verify_dataset(str(mixed))
    assert report["problems"] == [] and report["files"] > 50
    dataset = omnicam.Dataset(mixed)
    assert dataset.cameras == ["omni", "fisheye", "ds", "eucm", "pano"]
    fisheye = dataset[1, "fisheye"]
    assert fisheye["depth"].shape == (72, 96) and fisheye["intrinsics"]["model"] == "kannala_brandt"
    assert dataset[0, "pano"]["rgb"].shape == (64, 128, 4)
    assert fisheye["normal"].shape == (72, 96, 3) and fisheye["semantic"].shape == (72, 96)
    # Landmarks are where the lens camera projects them.
    camera = omnicam.Camera(lens_rig("fisheye"))
    seen = [lm for lm in fisheye["landmarks"]["landmarks"] if lm["in_view"]]
    assert len(seen) >= 2
    pose = tuple(fisheye["pose"])
    projected = camera.project(np.array([lm["position"] for lm in seen]), pose=pose)
    np.testing.assert_allclose(projected, [lm["centre"] for lm in seen], atol=1e-9)
    assert (mixed / "fisheye" / "coco.json").exists()
    files = {p.name for p in (mixed / "pano" / "intrinsics").iterdir()}
    assert files == {"rays.exr"}  # no third-party layout has the panorama
    assert {p.name for p in (mixed / "fisheye" / "intrinsics").iterdir()} == {
        "opencv.yaml", "kalibr.yaml", "camodocal.yaml", "rays.exr"}


# Kalibr's ConfigReader (kalibr_common/ConfigReader.py, CameraParameters.checkIntrinsics and
# checkDistortion): focal lengths and principal points are floats >= 0; ds alpha in [0, 1); eucm
# alpha in [0, 1), beta >= 0; ds and eucm take no distortion; pinhole takes equidistant or radtan.
def check_like_kalibr(cam):
    model, intrinsics = cam["camera_model"], cam["intrinsics"]
    assert all(isinstance(v, float) for v in intrinsics), intrinsics
    assert all(isinstance(v, float) for v in cam["distortion_coeffs"])
    focal_and_centre = {"pinhole": intrinsics, "ds": intrinsics[2:], "eucm": intrinsics[2:]}[model]
    assert all(v >= 0.0 for v in focal_and_centre)
    if model == "ds":
        assert 0.0 <= intrinsics[1] < 1.0 and cam["distortion_model"] == "none" and cam["distortion_coeffs"] == []
    if model == "eucm":
        assert 0.0 <= intrinsics[0] < 1.0 and intrinsics[1] >= 0.0 and cam["distortion_model"] == "none"
    if model == "pinhole":
        assert cam["distortion_model"] in ("equidistant", "radtan")
    assert all(isinstance(v, int) for v in cam["resolution"]) and cam["rostopic"].startswith("/")


# aslam_cv's projections (PinholeProjection + EquidistantDistortion, DoubleSphereProjection,
# ExtendedUnifiedProjection), camera frame X right, Y down, Z forward; pixel centres at integers.
def project_like_kalibr(cam, p):
    x, y, z = p
    model, k = cam["camera_model"], cam["intrinsics"]
    if model == "pinhole":
        fu, fv, pu, pv = k
        k1, k2, k3, k4 = cam["distortion_coeffs"]
        mx, my = x / z, y / z
        r = math.hypot(mx, my)
        theta = math.atan(r)
        theta_d = theta * (1 + k1 * theta**2 + k2 * theta**4 + k3 * theta**6 + k4 * theta**8)
        scale = theta_d / r if r > 1e-8 else 1.0
        return fu * mx * scale + pu, fv * my * scale + pv
    if model == "ds":
        xi, alpha, fu, fv, pu, pv = k
        d1 = math.sqrt(x * x + y * y + z * z)
        zz = xi * d1 + z
        d2 = math.sqrt(x * x + y * y + zz * zz)
        denominator = alpha * d2 + (1 - alpha) * zz
        return fu * x / denominator + pu, fv * y / denominator + pv
    alpha, beta, fu, fv, pu, pv = k
    d = math.sqrt(beta * (x * x + y * y) + z * z)
    denominator = alpha * d + (1 - alpha) * z
    return fu * x / denominator + pu, fv * y / denominator + pv


def world_from_camera(tum_line):
    t, tx, ty, tz, qx, qy, qz, qw = map(float, tum_line.split())
    rotation = np.array([
        [1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw)],
        [2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw)],
        [2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy)]])
    return rotation, np.array([tx, ty, tz])


@pytest.mark.parametrize("name", ["fisheye", "ds", "eucm"])
def test_kalibr_files_pass_kalibrs_checks_and_project_like_the_camera(mixed, name):
    cam = yaml.safe_load((mixed / name / "intrinsics" / "kalibr.yaml").read_text())["cam0"]
    check_like_kalibr(cam)
    assert cam["resolution"] == [LENSES[name]["width"], LENSES[name]["height"]]
    assert cam["rostopic"] == "/%s/image_raw" % name
    camera = omnicam.Camera(lens_rig(name))
    tum = [line for line in (mixed / name / "poses.tum").read_text().splitlines() if not line.startswith("#")]
    manifest = json.loads((mixed / "manifest.json").read_text())
    checked = 0
    for frame, line in enumerate(tum):
        rotation, origin = world_from_camera(line)
        pose = manifest["frames"][frame]["cameras"][name]["pose"]
        pixels = np.array([[x + 0.5, y + 0.5] for y in range(2, 72, 7) for x in range(2, 96, 7)])
        pixels = pixels[camera.images(pixels)]
        origins, directions = camera.rays(pixels, pose=(pose["x"], pose["y"], pose["yaw_deg"]))
        for pixel, start, direction in zip(pixels, origins, directions):
            in_camera = rotation.T @ (start + 1.7 * direction - origin)
            if name == "fisheye" and in_camera[2] <= 0.05:
                continue  # Kalibr's pinhole-equi images z > 0 only
            u, v = project_like_kalibr(cam, in_camera)
            assert abs(u + 0.5 - pixel[0]) < 1e-6 and abs(v + 0.5 - pixel[1]) < 1e-6, (name, pixel, u, v)
            checked += 1
    assert checked > 100


def test_a_lens_rigs_own_fields_can_be_set_and_the_mirrors_cannot():
    rig = lens_rig("fisheye")
    rig.height = 0.5
    rig.tilt_deg = [1.0, -2.0]
    rig.shutter = {"exposure_s": 0.01, "rolling": {"line_time_us": 30}}
    assert rig.to_dict()["height"] == 0.5 and rig.tilt_deg == [1.0, -2.0] and rig.lens["model"] == "kannala_brandt"
    assert rig.shape is None and omnicam.Rig().shape == "hyperboloid"
    with pytest.raises(omnicam.InputError, match=r"rig\.camera: a lens camera \(rig\.lens\) has no mirror"):
        rig.camera_offset_mm = [1.0, 0.0, 0.0]
    assert rig.camera_offset_mm is None  # left unchanged
    assert rig.resized(192).lens["width"] == 192 and rig.resized(192).lens["height"] == 144
    with pytest.raises(omnicam.InputError, match="keeps its aspect only at widths that are multiples of 4"):
        rig.resized(97)


def test_vibration_turns_a_lens_camera_and_a_resumed_run_keeps_every_frame(tmp_path):
    spec = tmp_path / "spec.json"
    spec.write_text(json.dumps({
        "format": "omnicam-dataset/1", "scene": str(SOURCE / "scenes" / "robocup2006.json"),
        "poses": {"list": [[0.5, -0.3, 20.0], [1.5, 0.4, -70.0]]},
        "cameras": [{"name": "omni"}, {"name": "pano", "rig": {"height": 0.35, "lens": dict(LENSES["pano"], width=64, height=32)}},
                    {"name": "fisheye", "rig": {"height": 0.35, "lens": dict(LENSES["fisheye"], max_theta_deg=75)}}],
        "vibration": {"seed": 4, "camera_rotation_deg": [1.0, 2.0, 3.0], "rig_tilt_deg": [1.0, 1.0]},
        "outputs": {"rgb": "png", "depth": True}}))
    code, out, err = run_cli("dataset", spec, "-o", tmp_path / "ds")
    assert code == 0, err
    manifest = json.loads((tmp_path / "ds" / "manifest.json").read_text())
    turned = [frame["cameras"]["fisheye"]["rig"]["lens"]["rotation_deg"] for frame in manifest["frames"]]
    assert all(abs(t[2]) > 0.0 and t != [0, 10, 0] for t in turned) and turned[0] != turned[1]
    code, out, err = run_cli("dataset", spec, "-o", tmp_path / "ds")
    assert code == 0 and "(0 rendered, 2 kept from an earlier run)" in out, out + err
    # Frames rendered from the manifest's rig are the frames: the recorded rig is the rendered one.
    frame = manifest["frames"][1]["cameras"]["fisheye"]
    rig = omnicam.Rig(frame["rig"])
    assert rig.lens["rotation_deg"] == turned[1]
