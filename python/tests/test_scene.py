"""Scenes and rigs from Python: the same strict checks and one-line messages as the CLI."""

import json

import pytest

import omnicam
from conftest import SOURCE, run_cli


def test_a_scene_loads_with_its_rig_objects_ids_and_paths(robocup):
    assert robocup.name == "robocup2006"
    assert robocup.rig.ideal and robocup.rig.shape == "hyperboloid"
    assert robocup.rig.image_size == 360
    assert len(robocup.objects) > 10
    ids = robocup.ids
    assert ids["instances"][0]["id"] == 0 and ids["classes"][0]["id"] == 0
    assert [i["name"] for i in ids["instances"][1:]] == robocup.objects
    assert "thesis-loop" in robocup.paths and len(robocup.paths["thesis-loop"][0]) == 3


def test_a_bad_scene_raises_the_clis_one_line_message(tmp_path):
    scene = json.loads((SOURCE / "scenes" / "robocup2006.json").read_text())
    scene["rig"]["mirror"]["k"] = -3
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(scene))
    with pytest.raises(omnicam.InputError) as raised:
        omnicam.load_scene(str(bad))
    code, _, stderr = run_cli("render", bad, "-o", tmp_path / "x.png")
    assert code == 2
    message = str(raised.value)
    assert "\n" not in message and message.startswith(str(bad))
    assert message in stderr  # the CLI prints the same line (after its "omnicam: " prefix)
    assert isinstance(raised.value, ValueError)


def test_a_file_outside_the_scenes_folder_is_allowed_by_pythons_keyword_not_the_clis_flag(tmp_path):
    folder = tmp_path / "scene"
    folder.mkdir()
    (tmp_path / "sky.hdr").write_bytes(b"not read")
    scene = json.loads((SOURCE / "scenes" / "robocup2006.json").read_text())
    scene["environment"] = {"file": "../sky.hdr"}
    (folder / "s.json").write_text(json.dumps(scene))
    with pytest.raises(omnicam.InputError) as raised:
        omnicam.load_scene(folder / "s.json")
    message = str(raised.value)
    assert message.endswith('"../sky.hdr" resolves outside the scene\'s folder (pass allow_outside_files=True to permit it)'), message
    _, _, stderr = run_cli("render", folder / "s.json", "-o", tmp_path / "x.png")
    assert stderr.strip().endswith("resolves outside the scene's folder (pass --allow-outside-files to permit it)"), stderr


def test_a_scene_names_and_hashes_the_files_it_reads(tmp_path):
    import hashlib

    (tmp_path / "textures").mkdir()
    png = (SOURCE / "tests" / "bad_inputs" / "outside.png").read_bytes()
    (tmp_path / "textures" / "tiles.png").write_bytes(png)
    scene = {"format": "omnicam-scene/1",
             "materials": {"tiles": {"texture": {"file": "textures/tiles.png"}}, "again": {"texture": {"file": "textures/tiles.png"}}},
             "objects": [{"type": "quad", "name": "floor", "material": "tiles",
                          "origin": [-5, -5, 0], "edge_u": [10, 0, 0], "edge_v": [0, 10, 0]}]}
    (tmp_path / "s.json").write_text(json.dumps(scene))
    loaded = omnicam.load_scene(tmp_path / "s.json")
    # Once, however many materials read it; the scene's own text is its sha256.
    assert loaded.inputs == [("textures/tiles.png", hashlib.sha256(png).hexdigest())]
    assert loaded.sha256 == hashlib.sha256((tmp_path / "s.json").read_bytes()).hexdigest()
    # Named as the scene writes it (the same on every machine), not by where a link leads.
    (tmp_path / "textures" / "current.png").symlink_to("tiles.png")
    scene["materials"] = {"tiles": {"texture": {"file": "./textures/../textures/current.png"}}}
    (tmp_path / "s.json").write_text(json.dumps(scene))
    assert omnicam.load_scene(tmp_path / "s.json").inputs == [("textures/current.png", hashlib.sha256(png).hexdigest())]


def test_files_are_named_by_str_or_pathlib_path(tmp_path):
    from_path = omnicam.load_scene(SOURCE / "scenes" / "robocup2006.json")
    assert from_path.sha256 == omnicam.load_scene(str(SOURCE / "scenes" / "robocup2006.json")).sha256
    frame = omnicam.render(from_path, None, size=32)["rgb"]
    code, _, err = run_cli("render", SOURCE / "scenes" / "robocup2006.json", "--size", "32", "-o", tmp_path / "x.exr")
    assert code == 0, err
    assert (omnicam.read_image(tmp_path / "x.exr") == frame).all()


def test_data_path_names_the_files_omnicam_comes_with():
    assert omnicam.load_scene(omnicam.data_path("scenes/robocup2006.json")).name == "robocup2006"
    assert (omnicam.data_path() / "scenes" / "incidence-rings.json").is_file()
    for wrong in ("scenes/nothing.json", "../VERSION", "/etc/passwd"):
        with pytest.raises(omnicam.InputError) as raised:
            omnicam.data_path(wrong)
        assert str(raised.value).startswith("data_path: "), raised.value


def test_a_missing_scene_file_is_an_input_error(tmp_path):
    with pytest.raises(omnicam.InputError):
        omnicam.load_scene(str(tmp_path / "nothing.json"))


def test_rig_properties_go_through_the_scene_formats_checks(robocup):
    rig = robocup.rig
    rig.camera_offset_mm = [2.0, -1.0, 0.5]
    rig.camera_rotation_deg = [1.0, 0.0, 0.0]
    assert rig.camera_offset_mm == [2.0, -1.0, 0.5]
    assert not rig.ideal
    before = rig.to_dict()
    with pytest.raises(omnicam.InputError) as raised:
        rig.camera_offset_mm = [1e6, 0.0, 0.0]
    assert "rig.camera.offset_mm" in str(raised.value)
    assert rig.to_dict() == before  # unchanged
    with pytest.raises(omnicam.InputError):
        rig.image_size = 3  # below the smallest image
    # The scene keeps its own rig until one is assigned back.
    assert robocup.rig.ideal
    robocup.rig = rig
    assert robocup.rig == rig


def test_a_rig_round_trips_through_its_dict():
    rig = omnicam.Rig()
    rig.mirror = {"shape": "sphere", "radius": 0.03, "cap_angle_deg": 60, "camera_distance_m": 0.12}
    again = omnicam.Rig(rig.to_dict())
    assert again == rig and again.shape == "sphere"
    with pytest.raises(omnicam.InputError) as raised:
        omnicam.Rig({"mirror": {"shape": "sphere", "radius": 0.03, "k": 11}})
    assert "belongs to the hyperboloid shape" in str(raised.value)
    # A NaN or infinity (which JSON has not) is named by its field, as the setters name theirs.
    for given, field, shown in [({"height": float("nan")}, "height", "nan"), ({"mirror": {"k": float("inf")}}, "mirror.k", "inf"),
                                ({"camera": {"offset_mm": [0, float("-inf"), 0]}}, "camera.offset_mm[1]", "-inf")]:
        with pytest.raises(omnicam.InputError) as raised:
            omnicam.Rig(given)
        assert str(raised.value) == f"omnicam.Rig: {field}: must be a finite number (got {shown})"
    assert omnicam.Rig().resized(180).image_size == 180
    assert omnicam.Rig(None) == omnicam.Rig() and omnicam.Rig().ideal  # as the stub's default says
    # A lens camera has no mirror and no square image size: None, as the stub types them.
    lens = omnicam.Rig({"height": 0.4, "lens": {"model": "pinhole", "width": 64, "height": 48, "fx": 50, "fy": 50}})
    assert lens.image_size is None and lens.mirror is None and lens.lens["width"] == 64
