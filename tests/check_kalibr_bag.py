"""Reads a calibration sequence's Kalibr files as Kalibr would, independently of omnicam
(dataset_cli_test runs it):
python3 check_kalibr_bag.py DATASET TAG_ROWS TAG_COLUMNS TAG_SIZE TAG_SPACING MARGIN (the scene's AprilGrid)

- kalibr_camchain.yaml passes Kalibr's ConfigReader checks (kalibr_common/ConfigReader.py:
  CameraParameters.checkIntrinsics, checkDistortion, checkResolution, checkRosTopic; omni: five
  intrinsics, xi >= 0, focal lengths and principal point floats >= 0), and every camN > 0 has
  T_cn_cnm1, equal to the cameras' poses in poses.tum (ideal rigs only: a physical rig's best-fit
  frame differs from poses.tum's by opencv.yaml's camera_from_rig);
- kalibr.bag (Debian's rosbag) holds every camera's frames on /<camera>/image_raw, rgb8, stamped
  i x frame_interval_s, a mirror camera's image the PNG flipped top to bottom;
- aslam_cv's omni projection (OmniProjection + RadialTangentialDistortion, written out here) with
  the camchain's parameters puts every seen corner of corners.json where the flipped image shows it;
- every corner of every frame's board, its white margin included (docs/scene-format.md: the
  pattern reaches a gap beyond the outer tags, the margin beyond that), is at least 1 cm above the
  floor (z = 0), from the written poses: corners.json's viewpoint_from_target and poses.tum (viewpoint frame x forward, y left,
  z up; the camera frame X forward, Y right, Z down at F').
Prints "kalibr ok: ..." when all hold."""
import json
import math
import sys

import numpy as np
import rosbag
import yaml
from PIL import Image

root = sys.argv[1]
tag_rows, tag_cols = int(sys.argv[2]), int(sys.argv[3])
tag_size, tag_spacing, margin = float(sys.argv[4]), float(sys.argv[5]), float(sys.argv[6])
manifest = json.load(open(root + "/manifest.json"))
names = [c["name"] for c in manifest["cameras"]]
interval_ns = round(manifest["settings"]["frame_interval_s"] * 1e9)

# Kalibr's points(): row by row over the 2R x 2C grid of tag corners.
corners = np.array([[(c // 2) * (1 + tag_spacing) * tag_size + (c % 2) * tag_size,
                     (r // 2) * (1 + tag_spacing) * tag_size + (r % 2) * tag_size, 0.0]
                    for r in range(2 * tag_rows) for c in range(2 * tag_cols)])
gap = tag_spacing * tag_size
x_edges = (-gap - margin, tag_cols * (1 + tag_spacing) * tag_size + margin)
y_edges = (-gap - margin, tag_rows * (1 + tag_spacing) * tag_size + margin)
outline = np.array([[x, y, 0.0] for x in x_edges for y in y_edges])
CAMERA_FROM_VIEWPOINT = np.diag([1.0, -1.0, -1.0])


def check_like_kalibr(cam):
    model, k = cam["camera_model"], cam["intrinsics"]
    assert model == "omni" and len(k) == 5, (model, k)
    assert k[0] >= 0, "xi"
    assert all(isinstance(v, float) and v >= 0.0 for v in k[1:]), ("focalLength / principalPoint", k)
    assert cam["distortion_model"] == "radtan" and len(cam["distortion_coeffs"]) == 4
    res = cam["resolution"]
    assert len(res) == 2 and all(isinstance(v, int) for v in res)
    assert isinstance(cam["rostopic"], str)


def project_like_aslam(cam, p):
    xi, fu, fv, pu, pv = cam["intrinsics"]
    k1, k2, p1, p2 = cam["distortion_coeffs"]
    rz = 1.0 / (p[2] + xi * np.linalg.norm(p))
    mx, my = p[0] * rz, p[1] * rz
    mx2, my2, mxy = mx * mx, my * my, mx * my
    rho2 = mx2 + my2
    rad = k1 * rho2 + k2 * rho2 * rho2
    mx, my = mx + mx * rad + 2 * p1 * mxy + p2 * (rho2 + 2 * mx2), my + my * rad + 2 * p2 * mxy + p1 * (rho2 + 2 * my2)
    return fu * mx + pu, fv * my + pv


def world_from_camera(name):
    line = next(l for l in open("%s/%s/poses.tum" % (root, name)) if not l.startswith("#"))
    t, tx, ty, tz, qx, qy, qz, qw = map(float, line.split())
    r = np.array([
        [1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw)],
        [2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw)],
        [2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy)]])
    m = np.eye(4)
    m[:3, :3], m[:3, 3] = r, [tx, ty, tz]
    return m


chain = yaml.safe_load(open(root + "/kalibr_camchain.yaml"))
assert sorted(chain) == ["cam%d" % n for n in range(len(names))], sorted(chain)
for n, name in enumerate(names):
    cam = chain["cam%d" % n]
    check_like_kalibr(cam)
    assert cam["rostopic"] == "/%s/image_raw" % name
    if n > 0:
        t = np.array(cam["T_cn_cnm1"], dtype=float)
        expected = np.linalg.inv(world_from_camera(name)) @ world_from_camera(names[n - 1])
        assert t.shape == (4, 4) and np.abs(t - expected).max() < 1e-6, (t, expected)

# The bag: every camera's frames, flipped.
seen_topics = {}
with rosbag.Bag(root + "/kalibr.bag") as bag:
    for topic, m, t in bag.read_messages():
        name = topic.split("/")[1]
        assert topic == "/%s/image_raw" % name and name in names, topic
        assert m.encoding == "rgb8" and m.step == 3 * m.width and m.header.frame_id == name
        # The record time is the stamp, but at least ROS's TIME_MIN (1 ns): C++ rosbag skips 0.
        assert m.header.stamp.to_nsec() == m.header.seq * interval_ns, (m.header.seq, m.header.stamp)
        assert t.to_nsec() == max(m.header.stamp.to_nsec(), 1), (m.header.seq, t)
        png = np.asarray(Image.open("%s/%s/rgb/%06d.png" % (root, name, m.header.seq)).convert("RGB"))
        data = np.frombuffer(m.data, np.uint8).reshape(m.height, m.width, 3)
        assert (data == png[::-1]).all(), (name, m.header.seq)
        assert not (data == png).all(), "flipped"
        seen_topics[name] = seen_topics.get(name, 0) + 1
frames = manifest["frame_count"]
assert seen_topics == {name: frames for name in names}, seen_topics

# The corners through the camchain's model, against the flipped image's; the boards above the floor.
projected, lowest = {}, math.inf
for n, name in enumerate(names):
    projected[name] = 0
    cam = chain["cam%d" % n]
    height = cam["resolution"][1]
    world_from_cam = world_from_camera(name)
    for frame in json.load(open("%s/%s/calibration/corners.json" % (root, name)))["frames"]:
        vt = np.array(frame["viewpoint_from_target"])
        to_camera = lambda points: (points @ vt[:, :3].T + vt[:, 3]) @ CAMERA_FROM_VIEWPOINT.T
        in_camera = to_camera(corners)
        board = to_camera(outline) @ world_from_cam[:3, :3].T + world_from_cam[:3, 3]
        lowest = min(lowest, board[:, 2].min())
        for corner in frame["corners"]:
            if corner["sight"] != "seen":
                continue
            u, v = project_like_aslam(cam, in_camera[corner["index"]])
            x, y = corner["raster"][0] - 0.5, height - 1 - (corner["raster"][1] - 0.5)
            assert abs(u - x) < 1e-6 and abs(v - y) < 1e-6, (name, frame["frame"], corner["index"], u, v, x, y)
            projected[name] += 1
assert lowest >= 0.01 - 1e-9, "a board corner %.4f m above the floor" % lowest
assert all(projected.values()), ("a camera with no corner to project", projected)
print("kalibr ok: %d cameras, %d images, corners projected %s, lowest board corner (margin included) %.4f m above the floor"
      % (len(names), sum(seen_topics.values()), projected, lowest))
