"""Rendering from Python: the CLI's pixels, AOVs against closed-form geometry, arrays that own
the rendered buffers, one renderer across threads, and datasets with progress."""

import concurrent.futures
import json
import pathlib

import numpy as np
import pytest

import omnicam
from conftest import SOURCE, run_cli

POSE = (2.5, 1.8, 35.0)


def test_the_pixels_are_the_clis_exactly(robocup, tmp_path):
    frame = omnicam.Renderer(robocup).render(POSE, spp=4, shading="lit")
    code, _, err = run_cli("render", SOURCE / "scenes" / "robocup2006.json", "--pose=%g,%g,%g" % POSE,
                           "--spp", 4, "--shading", "lit", "-o", tmp_path / "cli.exr")
    assert code == 0, err
    cli = omnicam.read_image(str(tmp_path / "cli.exr"))
    assert frame["rgb"].dtype == np.float32 and frame["rgb"].shape == (360, 360, 4)
    np.testing.assert_array_equal(frame["rgb"], cli)


@pytest.mark.parametrize("call, words", [
    (lambda s: omnicam.Renderer(s).render(POSE, shadng="lit"), "Renderer.render(): unknown keyword argument 'shadng' "
                                                                "(did you mean shading?)"),
    (lambda s: omnicam.Renderer(s, engin="povray"), "Renderer(): unknown keyword argument 'engin' (did you mean engine?)"),
    (lambda s: omnicam.render(s, None, sizee=32), "render(): unknown keyword argument 'sizee' (did you mean size?)"),
    (lambda s: omnicam.Camera(s.rig).project([[1.0, 1.0, 0.0]], poze=POSE),
     "Camera.project(): unknown keyword argument 'poze' (did you mean pose?)"),
    # A setting given where it does not go is sent where it does.
    (lambda s: omnicam.Renderer(s, spp=4), "Renderer(): unknown keyword argument 'spp' (spp is an argument of "
                                           "Renderer.render(), not of Renderer(); docs/render-settings.md)"),
    (lambda s: omnicam.Renderer(s).render(POSE, engine="povray"), "Renderer.render(): unknown keyword argument 'engine' "
     "(engine is an argument of Renderer(...), not of Renderer.render(); docs/render-settings.md)"),
], ids=["Renderer.render", "Renderer", "render", "Camera.project", "spp to Renderer", "engine to render"])
def test_a_mistyped_keyword_is_named_with_the_one_meant(robocup, call, words):
    """As the CLI names a mistyped flag, in one line, instead of pybind11's list of signatures."""
    with pytest.raises(TypeError) as raised:
        call(robocup)
    assert str(raised.value) == words


def test_an_argument_of_the_wrong_type_is_named_in_one_line(robocup):
    renderer = omnicam.Renderer(robocup)
    for keywords, words in [({"outputs": "depth"}, "outputs must be List[str] (got str 'depth')"),
                            ({"spp": True}, "spp must be Optional[int] (got bool True)"),
                            ({"size": 64.0}, "size must be int (got float 64.0)"),
                            ({"spp": "four"}, "spp must be Optional[int] (got str 'four')")]:
        with pytest.raises(TypeError) as raised:
            renderer.render(POSE, **keywords)
        assert str(raised.value) == "Renderer.render(): " + words
    with pytest.raises(omnicam.InputError, match="^outputs: name at least one of rgb, depth"):
        renderer.render(POSE, size=16, outputs=[])
    # numpy's scalars are what pybind11 takes: the argument at fault is the one named.
    with pytest.raises(TypeError) as raised:
        renderer.render(POSE, denoise=np.bool_(False), spp=np.int64(4), outputs="depth")
    assert str(raised.value) == "Renderer.render(): outputs must be List[str] (got str 'depth')"


def test_a_frame_without_a_recording_camera_is_refused(robocup):
    with pytest.raises(omnicam.InputError) as raised:
        omnicam.Renderer(robocup).render(POSE, size=16, frame=3)
    assert str(raised.value) == "frame: only with recording= (it picks the recording camera drawn for that frame)"
    with pytest.raises(omnicam.InputError, match="^frame: only with recording="):  # 0 given is given, too
        omnicam.render(robocup, POSE, size=16, frame=0)


def test_other_type_errors_keep_pybinds_message(robocup):
    with pytest.raises(TypeError) as raised:  # omnicam's own classes are judged by their names
        omnicam.Renderer(robocup).render(POSE, rig="front")
    assert str(raised.value) == "Renderer.render(): rig must be Optional[omnicam.Rig] (got str 'front')"
    with pytest.raises(TypeError) as raised:  # a type the wrapper does not judge: pybind11's words
        omnicam.srgb8(object())
    assert "incompatible function arguments" in str(raised.value)


def test_depth_of_the_floor_is_the_distance_along_the_ray(robocup):
    """Every floor pixel's depth is where its pixel-centre ray meets the plane z = 0."""
    frame = omnicam.Renderer(robocup).render(POSE, outputs=["depth", "semantic", "instance"])
    floor_id = next(c["id"] for c in robocup.ids["classes"] if c["name"] == "floor")
    rows, cols = np.nonzero(frame["semantic"] == floor_id)
    assert rows.size > 5000
    centres = np.column_stack([cols + 0.5, rows + 0.5])
    origins, directions = omnicam.Camera(robocup.rig).rays(centres, pose=POSE)
    along = -origins[:, 2] / directions[:, 2]
    np.testing.assert_allclose(frame["depth"][rows, cols], along, rtol=1e-5)


def test_class_ids_follow_the_scenes_instance_table(robocup):
    frame = omnicam.Renderer(robocup).render(POSE, outputs=["instance", "semantic", "normal", "depth"])
    class_of = np.array([i["class_id"] for i in robocup.ids["instances"]], dtype=np.uint16)
    np.testing.assert_array_equal(frame["semantic"], class_of[frame["instance"]])
    hit = frame["instance"] > 0
    # The field below the horizon (its radius is 73.7 px of 180) and the low walls: the rest of
    # the mirror sees the sky, which holds nothing.
    assert 0.05 < hit.mean() < 0.2
    np.testing.assert_array_equal(hit, frame["depth"] > 0)
    np.testing.assert_allclose(np.linalg.norm(frame["normal"][hit], axis=1), 1.0, atol=1e-5)
    assert (frame["normal"][~hit] == 0).all()


def test_arrays_own_the_rendered_buffers_and_are_named_and_shaped_as_datasets_store_them(robocup):
    frame = omnicam.Renderer(robocup).render(POSE, outputs=["rgb", "depth", "semantic", "normal"])
    assert frame["rgb"].flags.owndata is False and frame["rgb"].base is not None  # the C++ buffer itself
    assert frame["rgb"].shape == (360, 360, 4) and frame["rgb"].dtype == np.float32
    assert frame["depth"].shape == (360, 360) and frame["depth"].dtype == np.float32
    assert frame["semantic"].shape == (360, 360) and frame["semantic"].dtype == np.uint16
    assert frame["normal"].shape == (360, 360, 3)


def test_the_old_output_names_are_refused_with_the_new_ones(robocup):
    renderer = omnicam.Renderer(robocup)
    with pytest.raises(omnicam.InputError, match=r'outputs: "rgba" is now "rgb" \(H, W, 4\), as datasets name it'):
        renderer.render(outputs=["rgba"])
    with pytest.raises(omnicam.InputError, match='outputs: "class" is now "semantic"'):
        renderer.render(outputs=["class"])
    with pytest.raises(omnicam.InputError, match='is not one of rgb, depth, instance, semantic, normal'):
        renderer.render(outputs=["landmarks"])


def test_one_renderer_serves_threads_and_poses(robocup):
    renderer = omnicam.Renderer(robocup)
    assert renderer.concurrent
    poses = [(1.0 + 0.5 * k, 2.0, 20.0 * k) for k in range(6)]
    alone = [renderer.render(p, size=120)["rgb"] for p in poses]
    with concurrent.futures.ThreadPoolExecutor(3) as pool:
        together = list(pool.map(lambda p: renderer.render(p, size=120)["rgb"], poses))
    for a, b in zip(alone, together):
        np.testing.assert_array_equal(a, b)
    assert not np.array_equal(alone[0], alone[1])


def test_a_physical_rig_renders(robocup):
    rig = robocup.rig
    rig.camera_offset_mm = [2.0, 0.0, 0.0]
    moved = omnicam.render(robocup, POSE, rig=rig, size=120)["rgb"]
    ideal = omnicam.render(robocup, POSE, size=120)["rgb"]
    assert moved.shape == ideal.shape and not np.array_equal(moved, ideal)


def test_bad_render_arguments_raise_one_line(robocup):
    renderer = omnicam.Renderer(robocup)
    with pytest.raises(omnicam.InputError, match="outputs: \"colour\" is not one of"):
        renderer.render(outputs=["colour"])
    with pytest.raises(omnicam.InputError, match="spp"):
        renderer.render(spp=3)
    with pytest.raises(omnicam.InputError, match="shading"):
        renderer.render(shading="glossy")
    with pytest.raises(omnicam.InputError, match="engine"):
        omnicam.Renderer(robocup, engine="mitsuba")
    with pytest.raises(omnicam.InputError, match="^outputs: the povray engine renders colour only"):
        omnicam.Renderer(robocup, engine="povray").render(outputs=["depth"])


def test_path_shading_is_the_clis_and_its_settings_are_checked(robocup, tmp_path):
    """shading="path" with bounces, seed and denoise gives the CLI's pixels; a seed changes the
    noise; bounces without path shading and denoise of lit frames raise one line."""
    renderer = omnicam.Renderer(robocup)
    frame = renderer.render(POSE, size=96, spp=4, shading="path", bounces=1, seed=3, denoise=True)
    code, _, err = run_cli("render", SOURCE / "scenes" / "robocup2006.json", "--pose=%g,%g,%g" % POSE, "--size", 96,
                           "--spp", 4, "--shading", "path", "--bounces", 1, "--seed", 3, "--denoise",
                           "-o", tmp_path / "cli.exr")
    assert code == 0, err
    np.testing.assert_array_equal(frame["rgb"], omnicam.read_image(str(tmp_path / "cli.exr")))
    other = renderer.render(POSE, size=96, spp=4, shading="path", bounces=1, seed=4, denoise=True)
    assert not np.array_equal(frame["rgb"], other["rgb"])
    with pytest.raises(omnicam.InputError, match="bounces: only with shading path"):
        renderer.render(bounces=3)
    with pytest.raises(omnicam.InputError, match="denoise: only for path-traced frames"):
        renderer.render(shading="lit", denoise=True)


def test_adaptive_sampling_is_the_clis_and_its_settings_are_checked(robocup, tmp_path):
    """adaptive_spp and target_error give the CLI's pixels; a tighter target refines more pixels;
    adaptive sampling of denoised or unlit frames raises one line."""
    renderer = omnicam.Renderer(robocup)
    frame = renderer.render(POSE, size=64, spp=4, shading="path", adaptive_spp=64, target_error=0.05)
    code, _, err = run_cli("render", SOURCE / "scenes" / "robocup2006.json", "--pose=%g,%g,%g" % POSE, "--size", 64,
                           "--spp", 4, "--shading", "path", "--adaptive-spp", 64, "--target-error", 0.05,
                           "-o", tmp_path / "cli.exr")
    assert code == 0, err
    np.testing.assert_array_equal(frame["rgb"], omnicam.read_image(str(tmp_path / "cli.exr")))
    first = renderer.render(POSE, size=64, spp=4, shading="path")["rgb"]
    loose = renderer.render(POSE, size=64, spp=4, shading="path", adaptive_spp=64, target_error=0.2)["rgb"]
    refined = np.any(frame["rgb"] != first, axis=-1).sum()
    assert 0 < np.any(loose != first, axis=-1).sum() < refined
    with pytest.raises(omnicam.InputError, match="adaptive_spp: not with denoise"):
        renderer.render(shading="path", denoise=True, adaptive_spp=16)
    with pytest.raises(omnicam.InputError, match="adaptive_spp: only with the fast engine's exact mode and shading path"):
        renderer.render(adaptive_spp=16)
    with pytest.raises(omnicam.InputError, match="target_error: only with adaptive_spp"):
        renderer.render(shading="path", target_error=0.1)


def test_a_dataset_runs_with_progress_and_stops_on_an_exception(tmp_path):
    spec = tmp_path / "spec.json"
    spec.write_text(json.dumps({
        "format": "omnicam-dataset/1", "scene": str(SOURCE / "scenes" / "robocup2006.json"),
        "size": 32, "poses": {"path": "thesis-loop", "frames": 12},
        "outputs": {"rgb": "png", "depth": True}}))
    seen = []
    result = omnicam.run_dataset(str(spec), str(tmp_path / "ds"), progress=lambda done, total: seen.append((done, total)))
    assert result["frames"] == 12 and result["rendered"] == 12 and not result["stopped"]
    assert seen[0] == (0, 12) and seen[-1] == (12, 12) and len(seen) == 13
    assert (tmp_path / "ds" / "manifest.json").exists()

    class Enough(Exception):
        pass

    def stop_after_the_first(done, total):
        if done >= 1:
            raise Enough()

    with pytest.raises(Enough):
        omnicam.run_dataset(str(spec), str(tmp_path / "ds2"), progress=stop_after_the_first)
    # The fast engine renders windows of 8 frames: the run stopped after the first window (not
    # machine-dependent), and resuming keeps those 8 and renders the other 4.
    again = omnicam.run_dataset(str(spec), str(tmp_path / "ds2"))
    assert (again["kept"], again["rendered"]) == (8, 4)


def test_none_is_not_a_scene():
    with pytest.raises(TypeError):
        omnicam.Renderer(None)
    with pytest.raises(TypeError):
        omnicam.render(None)
    rig = omnicam.Rig()
    with pytest.raises(omnicam.InputError, match="height"):
        rig.height = float("nan")


def test_recording_is_the_datasets_camera_drawn_for_the_frame(robocup, tmp_path):
    """recording= with frame=k gives frame k of a one-camera dataset with the same `recording`:
    the same drawn camera, the same noise; the AOVs stay exact."""
    recording = {"preset": {"choice": ["webcam", "machine_vision", "phone"]}, "seed": 9}
    spec = tmp_path / "spec.json"
    spec.write_text(json.dumps({
        "format": "omnicam-dataset/1", "scene": str(SOURCE / "scenes" / "robocup2006.json"),
        "size": 96, "spp": 4, "shading": "lit", "poses": {"path": "thesis-loop", "frames": 4},
        "outputs": {"rgb": "png", "depth": False, "normal": False}, "recording": recording}))
    omnicam.run_dataset(str(spec), str(tmp_path / "ds"))
    manifest = json.loads((tmp_path / "ds" / "manifest.json").read_text())
    frame = manifest["frames"][3]
    pose = (frame["pose"]["x"], frame["pose"]["y"], frame["pose"]["yaw_deg"])
    renderer = omnicam.Renderer(robocup)
    out = renderer.render(pose, size=96, spp=4, shading="lit", recording=recording, frame=3, outputs=["rgb", "depth"])
    written = omnicam.read_image(str(tmp_path / "ds" / "cam0" / "rgb" / "000003.png"))
    inside = out["rgb"][..., 3] == 1.0
    np.testing.assert_allclose(out["rgb"][inside], written[inside], atol=1e-6)
    # Another frame draws another camera; the depth is the clean render's.
    assert not np.array_equal(renderer.render(pose, size=96, spp=4, shading="lit", recording=recording, frame=2)["rgb"], out["rgb"])
    clean = renderer.render(pose, size=96, spp=4, shading="lit", outputs=["rgb", "depth"])
    np.testing.assert_array_equal(clean["depth"], out["depth"])
    assert not np.array_equal(clean["rgb"], out["rgb"])
    # A preset by name; bad input is one line naming the field.
    assert renderer.render(pose, size=32, recording="phone")["rgb"].shape == (32, 32, 4)
    # The keyword is the field, named once (as every keyword's message starts).
    with pytest.raises(omnicam.InputError, match=r'^recording: unknown preset "webcm"'):
        renderer.render(pose, size=32, recording="webcm")
    with pytest.raises(omnicam.InputError, match=r"^recording\.bayer: must be one of none, rggb"):
        renderer.render(pose, size=32, recording={"bayer": "rgbg"})
    with pytest.raises(omnicam.InputError, match=r"recording\.exposure_ev\.uniform: lo > hi"):
        renderer.render(pose, size=32, recording={"exposure_ev": {"uniform": [1, 0]}})
    # numpy's numbers are numbers here too (as everywhere a number is taken): the same frame.
    by_numpy = {"preset": "webcam", "seed": np.int64(7), "exposure_ev": np.float32(0.5), "jpeg_quality": np.int64(90),
                "white_balance": np.array([1.1, 1.0, 0.9])}
    by_python = {"preset": "webcam", "seed": 7, "exposure_ev": 0.5, "jpeg_quality": 90, "white_balance": [1.1, 1.0, 0.9]}
    np.testing.assert_array_equal(renderer.render(pose, size=32, recording=by_numpy)["rgb"],
                                  renderer.render(pose, size=32, recording=by_python)["rgb"])
    with pytest.raises(omnicam.InputError, match=r'^recording: not JSON-like \(.*; got a "PosixPath"\)$'):
        renderer.render(pose, size=32, recording={"preset": tmp_path})
    # A file of one recording object, as --recording takes it: a path or its text.
    camera_file = tmp_path / "camera.json"
    camera_file.write_text(json.dumps(by_python))
    for given in (camera_file, str(camera_file)):
        np.testing.assert_array_equal(renderer.render(pose, size=32, recording=given)["rgb"],
                                      renderer.render(pose, size=32, recording=by_python)["rgb"])
    with pytest.raises(omnicam.InputError, match=r"^recording: .*nope\.json: no such file \(a preset's name or a JSON file\)$"):
        renderer.render(pose, size=32, recording=tmp_path / "nope.json")
    # A path is a file whatever its name: a missing one named like a preset is not the preset.
    with pytest.raises(omnicam.InputError, match=r"^recording: webcam: no such file"):
        renderer.render(pose, size=32, recording=pathlib.Path("webcam"))
    with pytest.raises(omnicam.InputError, match=r"^recording: exposure_ev: must be a finite number \(got nan\)"):
        renderer.render(pose, size=32, recording={"exposure_ev": np.float32("nan")})


def test_srgb8_gives_the_codes_of_the_clis_png(robocup, tmp_path):
    from PIL import Image

    frame = omnicam.Renderer(robocup).render(POSE, spp=4, shading="lit")
    code, _, err = run_cli("render", SOURCE / "scenes" / "robocup2006.json", "--pose=%g,%g,%g" % POSE,
                           "--spp", 4, "--shading", "lit", "-o", tmp_path / "cli.png")
    assert code == 0, err
    png = np.asarray(Image.open(tmp_path / "cli.png").convert("RGBA"))
    codes = omnicam.srgb8(frame["rgb"])
    assert codes.dtype == np.uint8 and codes.shape == (360, 360, 4)
    np.testing.assert_array_equal(codes, png)
    with pytest.raises(omnicam.InputError, match="srgb8: the image must be"):
        omnicam.srgb8(frame["rgb"][..., :3])
