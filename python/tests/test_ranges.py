"""Every Python entry point checks its arguments by the CLI's and the scene reader's rules: what
`omnicam` refuses with exit 2, Python refuses with omnicam.InputError (a ValueError), before
any work (docs/python.md, "Errors")."""

import json

import pytest

import omnicam
from conftest import SOURCE


@pytest.mark.parametrize("threads", [-1, 4097, 10**6])
def test_renderer_threads_are_in_the_clis_range(robocup, threads):
    with pytest.raises(omnicam.InputError, match=r"threads: must be an integer in \[0, 4096\]"):
        omnicam.Renderer(robocup, threads=threads)


@pytest.mark.parametrize("timeout", [0.0, -1.0, float("nan"), float("inf"), 1e300])
def test_renderer_timeouts_are_in_the_clis_range(robocup, timeout):
    with pytest.raises(omnicam.InputError, match=r"timeout: must be in \(0, 604800\] s"):
        omnicam.Renderer(robocup, engine="povray", timeout=timeout)


@pytest.mark.parametrize("size", [-5, 0, 7, 16385, 10**6, 2**31 - 1, 2**32 + 64, 2**64, -2**70])
def test_a_rig_resizes_only_within_the_image_size_limits(size):
    with pytest.raises(omnicam.InputError, match=r"image size: must be an integer in \[8, 16384\]"):
        omnicam.Rig().resized(size)


def test_a_physical_rig_resized_past_the_limit_is_refused_not_described_for_minutes():
    rig = omnicam.Rig({"camera": {"offset_mm": [1, 0, 0]}})
    with pytest.raises(omnicam.InputError, match="image size"):
        omnicam.Camera(rig.resized(2**31 - 1)).describe()
    assert omnicam.Rig().resized(16384).to_dict()["image"]["size"] == 16384


@pytest.mark.parametrize("size", [-5, 7, 16385, 2**40])
def test_render_sizes_are_in_range(robocup, size):
    with pytest.raises(omnicam.InputError, match=r"size: must be an integer in \[8, 16384\]"):
        omnicam.render(robocup, size=size)


@pytest.mark.parametrize("threads", [2**64, -2**64])
def test_integers_beyond_64_bits_are_refused_in_the_libraries_words(robocup, threads):
    """Not pybind's TypeError: the same InputError as for any number out of range."""
    with pytest.raises(omnicam.InputError, match=r"threads: must be an integer in \[0, 4096\]"):
        omnicam.Renderer(robocup, threads=threads)
    with pytest.raises(omnicam.InputError, match=r"spp: must be a perfect square n\*n from 1 to 1024 \(got 4294967297\)"):
        omnicam.render(robocup, spp=2**32 + 1)


def test_mapping_arena_counts_and_seed_are_bounded():
    with pytest.raises(omnicam.InputError, match=r"debris: must be an integer in \[0, 16000\]"):
        omnicam.mapping_arena(debris=10**9)
    with pytest.raises(omnicam.InputError, match="at most cells - 2 victims and 10 debris a cell"):
        omnicam.mapping_arena(debris=15000)
    with pytest.raises(omnicam.InputError, match=r"seed: must be an integer in \[0, 18446744073709551615\]"):
        omnicam.mapping_arena(seed=-1)
    assert omnicam.mapping_arena(seed=2**64 - 1)["objects"]


def test_an_integer_out_of_range_is_shown_as_python_wrote_it(robocup):
    with pytest.raises(omnicam.InputError) as raised:
        omnicam.render(robocup, size=7)
    assert str(raised.value) == "size: must be an integer in [8, 16384] (got 7)"
    with pytest.raises(omnicam.InputError) as raised:
        omnicam.Renderer(robocup, mode="cubemap", face_size=2**64)
    assert str(raised.value) == "face_size: must be an integer in 8–8192 (got 18446744073709551616)"
    with pytest.raises(omnicam.InputError) as raised:
        omnicam.Renderer(robocup, threads=-10**50)
    assert str(raised.value) == "threads: must be an integer in [0, 4096] (got -1000000000000000000… (51 digits))"


@pytest.mark.parametrize("options", [{"faces": 7}, {"face_size": -1}, {"polygons": 17}])
def test_cube_map_options_are_checked_when_the_renderer_is_made(robocup, options):
    with pytest.raises(omnicam.InputError):
        omnicam.Renderer(robocup, mode="thesis-mesh", **options)


@pytest.mark.parametrize("threads", [-1, 4097])
def test_dataset_threads_are_in_range(tmp_path, threads):
    (tmp_path / "box.json").write_bytes((SOURCE / "tests" / "bad_inputs" / "datasets" / "box.json").read_bytes())
    spec = tmp_path / "spec.json"
    spec.write_text(json.dumps({"format": "omnicam-dataset/1", "scene": "box.json", "poses": {"path": "p"}, "size": 16}))
    with pytest.raises(omnicam.InputError, match=r"threads: must be an integer in \[0, 4096\]"):
        omnicam.run_dataset(str(spec), str(tmp_path / "ds"), threads=threads)
    assert not (tmp_path / "ds").exists()
