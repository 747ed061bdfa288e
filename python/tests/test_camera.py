"""The camera interface, vectorised: closed-form cases, round trips and the CLI's `project`."""

import collections.abc
import numpy as np
import pytest

import omnicam
from conftest import SOURCE, run_cli


def test_the_point_below_the_viewpoint_is_the_image_centre_and_the_sky_is_nan(robocup):
    camera = omnicam.Camera(robocup.rig)
    assert camera.model == "mei_unified" and camera.central
    # The CLI's own closed-form case (tests/cli_test.cpp): straight below is pixel (180, 180).
    pixels = camera.project(np.array([[1.0, 1.0, 0.0], [1.0, 1.1, 5.0]]), pose=(1.0, 1.0, 30.0))
    np.testing.assert_allclose(pixels[0], [180.0, 180.0], atol=1e-9)
    assert np.isnan(pixels[1]).all()


def test_world_points_project_as_the_cli_projects_them(robocup):
    rng = np.random.default_rng(3)
    points = np.column_stack([rng.uniform(0, 8, 20), rng.uniform(0, 6, 20), rng.uniform(0, 0.5, 20)])
    pose = (3.5, 2.0, 40.0)
    ours = omnicam.Camera(robocup.rig).project(points, pose=pose)
    args = ["project", SOURCE / "scenes" / "robocup2006.json", "--pose=%g,%g,%g" % pose]
    args += ["--point=%.17g,%.17g,%.17g" % tuple(p) for p in points]
    code, out, err = run_cli(*args)
    assert code == 0, err
    cli = np.array([[float(v) for v in line.split()] for line in out.splitlines()])
    np.testing.assert_allclose(ours, cli, atol=1e-5, equal_nan=True)  # the CLI prints 6 decimals
    assert np.isfinite(ours).sum() > 5


@pytest.mark.parametrize("offset", [None, [2.0, -1.4, 1.0]])
def test_rays_and_project_round_trip(robocup, offset):
    rig = robocup.rig
    if offset:
        rig.camera_offset_mm = offset
        rig.camera_rotation_deg = [1.0, -0.6, 0.8]
    camera = omnicam.Camera(rig)
    assert camera.model == ("physical" if offset else "mei_unified")
    rng = np.random.default_rng(7)
    pixels = rng.uniform(0, 360, (20000, 2))
    origins, directions = camera.rays(pixels)
    seen = camera.images(pixels)
    np.testing.assert_array_equal(np.isfinite(origins[:, 0]), seen)
    np.testing.assert_allclose(np.linalg.norm(directions[seen], axis=1), 1.0, atol=1e-12)
    depths = np.exp(rng.uniform(np.log(0.1), np.log(100.0), seen.sum()))
    back = camera.project(origins[seen] + depths[:, None] * directions[seen])
    assert np.isfinite(back).all()
    assert np.abs(back - pixels[seen]).max() <= 1e-6


def test_world_frame_rays_pass_through_the_points_they_image(robocup):
    camera = omnicam.Camera(robocup.rig)
    pose = (2.0, 3.0, -60.0)
    pixels = np.array([[100.5, 200.5], [180.5, 40.5], [300.25, 170.75]])
    origins, directions = camera.rays(pixels, pose=pose)
    points = origins + 1.7 * directions
    np.testing.assert_allclose(camera.project(points, pose=pose), pixels, atol=1e-8)


def test_rays_at_a_time_are_the_rays_from_where_the_motion_model_puts_the_robot(robocup):
    # The motion model in closed form (docs/motion.md): driving at v along its heading without
    # turning, the robot is v·t further along it; turning on the spot at ω, it has turned ω·t.
    camera = omnicam.Camera(robocup.rig)
    pixels = np.array([[100.5, 200.5], [180.5, 40.5], [300.25, 170.75]])
    start = (2.0, 3.0, 30.0)
    for velocity, t, then in [
        ((1.5, 0.0, 0.0), 0.2, (2.0 + 0.3 * np.cos(np.radians(30.0)), 3.0 + 0.3 * np.sin(np.radians(30.0)), 30.0)),
        ((0.0, 0.0, 90.0), 0.5, (2.0, 3.0, 75.0)),
    ]:
        moving = camera.rays(pixels, pose=start, velocity=velocity, time=t)
        placed = camera.rays(pixels, pose=then)
        for got, want in zip(moving, placed):
            np.testing.assert_allclose(got, want, atol=1e-12)
    # A time without a velocity would do nothing: refused. At time 0 a moving robot's rays are its start's.
    with pytest.raises(omnicam.InputError, match="time: does nothing without a pose and a velocity"):
        camera.rays(pixels, pose=start, time=0.7)
    np.testing.assert_array_equal(camera.rays(pixels, pose=start, velocity=(1.0, 0.5, 40.0))[0],
                                  camera.rays(pixels, pose=start)[0])
    # One time per pixel: each pixel's ray as if asked alone at its time.
    times = np.array([0.0, 0.2, 0.5])
    each = [camera.rays(pixels[k:k + 1], pose=start, velocity=(1.5, 0.0, 90.0), time=float(times[k])) for k in range(3)]
    together = camera.rays(pixels, pose=start, velocity=(1.5, 0.0, 90.0), time=times)
    for part in range(2):
        np.testing.assert_array_equal(together[part], np.concatenate([e[part] for e in each]))
    with pytest.raises(omnicam.InputError, match=r"time: must be a number or an array of one time per pixel, shape \(3,\)"):
        camera.rays(pixels, pose=start, velocity=(1.5, 0.0, 90.0), time=np.zeros(2))
    for wrong in [np.array([True, False, True]), [True, False, True], np.zeros(3, dtype=complex), 10**400, "0.1"]:
        with pytest.raises(omnicam.InputError, match="time: must be"):
            camera.rays(pixels, pose=start, velocity=(1.5, 0.0, 90.0), time=wrong)
    # numpy's scalars are numbers; a NaN in an array is a pixel without a time: its ray is NaN.
    np.testing.assert_array_equal(camera.rays(pixels, pose=start, velocity=(1.5, 0.0, 90.0), time=np.float32(0.25))[1],
                                  camera.rays(pixels, pose=start, velocity=(1.5, 0.0, 90.0), time=0.25)[1])
    partial = camera.rays(pixels, pose=start, velocity=(1.5, 0.0, 90.0), time=np.array([0.0, np.nan, 0.5]))
    assert np.isnan(partial[0][1]).all() and np.isnan(partial[1][1]).all()
    np.testing.assert_array_equal(partial[1][[0, 2]], together[1][[0, 2]])
    with pytest.raises(omnicam.InputError, match="velocity: needs a pose"):
        camera.rays(pixels, velocity=(1.0, 0.0, 0.0), time=0.1)
    with pytest.raises(omnicam.InputError, match="time: must be within"):
        camera.rays(pixels, pose=start, velocity=(1.0, 0.0, 0.0), time=float("nan"))


def test_bad_arrays_are_input_errors(robocup):
    camera = omnicam.Camera(robocup.rig)
    with pytest.raises(omnicam.InputError, match=r"points: must be an array of shape \(N, 3\)"):
        camera.project(np.zeros((4, 2)))
    with pytest.raises(omnicam.InputError, match="pose"):
        camera.project(np.zeros((1, 3)), pose=(1.0, 2.0))
    with pytest.raises(omnicam.InputError):
        camera.rays(np.zeros(5))
    with pytest.raises(omnicam.InputError, match=r"points: must be an array of shape \(N, 3\) of real numbers"):
        camera.project([["a", "b", "c"]])
    # numpy would drop an imaginary part with only a warning; bools are no coordinates.
    with pytest.raises(omnicam.InputError, match=r"points: must be an array of shape \(N, 3\) of real numbers .*complex128"):
        camera.project(np.zeros((2, 3), dtype=complex))
    with pytest.raises(omnicam.InputError, match=r"pixels: must be an array of shape \(N, 2\) of real numbers .*bool"):
        camera.rays(np.zeros((2, 2), dtype=bool))
    for pose in [(True, 0.0, 0.0), (np.bool_(True), 0, 0), (1.0, 2.0, 3.0 + 1j), (1.0, 2.0, np.complex128(3.0)), "1,2,3",
                 np.array(1.0), np.zeros((1, 3)), (1.0, 2.0, 10**400)]:
        with pytest.raises(omnicam.InputError, match=r"pose: must be \(x, y, yaw_deg\)"):
            camera.project(np.zeros((1, 3)), pose=pose)
    with pytest.raises(omnicam.InputError, match=r"velocity: must be \(vx, vy, yaw_rate_deg_per_s\)"):
        camera.rays(np.zeros((1, 2)), pose=(0, 0, 0), velocity=(False, 0, 0), time=0.1)
    # A pose of too many numbers is refused at the fourth: the rest is never read.
    class Counted(collections.abc.Sequence):
        def __init__(self):
            self.read = 0

        def __len__(self):
            return 10**6

        def __getitem__(self, k):
            if k >= len(self):
                raise IndexError(k)
            self.read += 1
            return 0.0
    long_pose = Counted()
    with pytest.raises(omnicam.InputError, match=r"pose: must be \(x, y, yaw_deg\), 3 numbers"):
        camera.project(np.zeros((1, 3)), pose=long_pose)
    assert long_pose.read == 4
    # numpy's own number types are numbers.
    np.testing.assert_array_equal(camera.project(np.zeros((1, 3)), pose=(np.float32(1.0), np.int64(0), 0)),
                                  camera.project(np.zeros((1, 3)), pose=(1.0, 0.0, 0.0)))


def test_plain_lists_are_arrays_too(robocup):
    camera = omnicam.Camera(robocup.rig)
    points = [[1, 1, 0], [1.5, 0.5, 0.3]]
    np.testing.assert_array_equal(camera.project(points, pose=(1.0, 1.0, 30.0)),
                                  camera.project(np.array(points, dtype=np.float64), pose=(1.0, 1.0, 30.0)))
    pixels = [[180.5, 100.5]]
    origins, directions = camera.rays(pixels)
    np.testing.assert_array_equal(directions, camera.rays(np.array(pixels))[1])
    assert camera.images(pixels).tolist() == [True]


def test_describe_states_the_model(robocup):
    description = omnicam.Camera(robocup.rig).describe()
    assert description["model"] == "mei_unified"
