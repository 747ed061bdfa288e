"""Arguments as research code passes them: numpy's integer scalars where ints are taken, arrays
of any integer dtype for ids, and a short message naming the argument (keyword or positional)
that has the wrong type, never pybind11's list of overloads (docs/python.md, "Errors")."""

import os
import threading

import numpy as np
import pytest

import omnicam


def test_numpy_integers_are_ints(robocup):
    renderer = omnicam.Renderer(robocup, threads=np.int64(2))
    pose = (0.5, 0.2, 30.0)
    as_ints = renderer.render(pose, size=64, spp=4, shading="path", bounces=1, seed=3)["rgb"]
    as_numpy = renderer.render(pose, size=np.int64(64), spp=np.int32(4), shading="path", bounces=np.uint8(1),
                               seed=np.uint64(3))["rgb"]
    assert np.array_equal(as_ints, as_numpy)
    drawn = renderer.render(pose, size=64, recording="webcam", frame=np.int64(5))["rgb"]
    assert np.array_equal(drawn, renderer.render(pose, size=64, recording="webcam", frame=5)["rgb"])
    assert omnicam.Rig().resized(np.int16(64)) == omnicam.Rig().resized(64)


@pytest.mark.parametrize("value", [np.float64(64.0), np.True_, True, 64.0, "64"])
def test_what_is_no_integer_is_refused_with_the_type_it_takes(robocup, value):
    with pytest.raises(TypeError, match=r"^Renderer\.render\(\): size must be int \(got "):
        omnicam.Renderer(robocup).render(size=value)


def test_a_positional_argument_of_the_wrong_type_is_named(robocup):
    with pytest.raises(TypeError, match=r"^read_exr_channels\(\): channels must be List\[str\] \(got str 'Z'\)$"):
        omnicam.read_exr_channels("frame.exr", "Z")
    with pytest.raises(TypeError, match=r"^load_scene\(\): path must be os\.PathLike \(got int 3\)$"):
        omnicam.load_scene(3)
    with pytest.raises(TypeError, match=r"^Camera\(\): rig must be omnicam\.Rig \(got dict \{'height': 0\.4\}\)$"):
        omnicam.Camera({"height": 0.4})
    with pytest.raises(TypeError, match=r"^run_dataset\(\): progress must be Optional\[function\] \(got int 3\)$"):
        omnicam.run_dataset("spec.json", "out", progress=3)
    # Keyword-only parameters take no positional argument: said so, not blamed on one of them.
    with pytest.raises(TypeError, match=r"^Renderer\.render\(\): takes 1 positional argument \(pose\), got 2; the others by keyword$"):
        omnicam.Renderer(robocup).render((0, 0, 0), 64)
    with pytest.raises(TypeError, match=r"^Camera\(\): takes 2 positional arguments \(rig, traced\), got 3; "):
        omnicam.Camera(omnicam.Rig(), False, 3)
    # A method's self and a positional pose that fits are not blamed.
    with pytest.raises(TypeError, match=r"^Renderer\.render\(\): size must be int \(got str 'a'\)$"):
        omnicam.Renderer(robocup).render((0, 0, 0), size="a")


def test_instance_ids_of_any_integer_dtype_are_taken_as_they_are(robocup):
    ids = np.zeros((8, 8), np.uint16)
    ids[2:5, 3:7] = 26
    expected = omnicam.coco_annotations(ids, robocup)
    assert len(expected) == 1 and expected[0]["instance_id"] == 26 and expected[0]["bbox"] == [3, 2, 4, 3]
    for dtype in (np.uint32, np.int64, np.int32, np.uint8):
        assert omnicam.coco_annotations(ids.astype(dtype), robocup) == expected
    assert omnicam.coco_annotations(ids.tolist(), robocup) == expected  # an array-like: lists of ints
    with pytest.raises(omnicam.InputError, match=r"^instance: must be an array of shape \(H, W\)$"):
        omnicam.coco_annotations([1, 2, 3], robocup)
    # Never wrapped, rounded or taken from another kind of number.
    last = len(robocup.objects)
    for wrong, shown in ((65536 + 26, 65562), (-1, -1), (2**63 + 5, 2**63 + 5)):
        plane = ids.astype(np.int64 if wrong < 2**63 else np.uint64)
        plane[0, 0] = wrong
        with pytest.raises(omnicam.InputError, match=rf"^instance: id {shown} is not an instance of the scene \(its ids: 0 to {last}\)$"):
            omnicam.coco_annotations(plane, robocup)
    for dtype in (np.float32, np.float64, np.bool_):
        with pytest.raises(omnicam.InputError, match=r"^instance: must hold integer ids, as the instance plane does \(got an array of dtype "):
            omnicam.coco_annotations(ids.astype(dtype), robocup)


def _cpu_ticks_by_thread():
    """Each thread of this process: its user + system CPU time, in clock ticks (/proc)."""
    ticks = {}
    for tid in os.listdir("/proc/self/task"):
        try:
            with open(f"/proc/self/task/{tid}/stat") as stat:
                fields = stat.read().rsplit(")", 1)[1].split()
        except FileNotFoundError:  # a thread that ended meanwhile
            continue
        ticks[int(tid)] = int(fields[11]) + int(fields[12])
    return ticks


def test_threads_caps_the_fast_engine_too(robocup):
    # The CPU time each thread spent on one render: with threads=1 the calling thread renders it
    # all, and no TBB worker of the process (there are some: the first render woke them) takes
    # any of it. The work is counted, not timed.
    omnicam.Renderer(robocup).render((0.5, 0.2, 30.0), size=64, spp=4, shading="path")
    renderer = omnicam.Renderer(robocup, threads=1)
    before = _cpu_ticks_by_thread()
    frame = renderer.render((0.5, 0.2, 30.0), size=360, spp=64, shading="path")["rgb"]
    after = _cpu_ticks_by_thread()
    caller = threading.get_native_id()
    own = after[caller] - before.get(caller, 0)
    others = sum(t - before.get(tid, 0) for tid, t in after.items() if tid != caller)
    assert own >= 20, f"the render took {own} ticks on the caller's thread: too short to tell"
    assert others <= 0.1 * own + 5, f"other threads took {others} ticks of the render's CPU, the caller {own}"
    # The same frame on every core: threads changes how long it takes, not what it renders.
    assert np.array_equal(frame, omnicam.Renderer(robocup).render((0.5, 0.2, 30.0), size=360, spp=64, shading="path")["rgb"])


def _documented(owner, name, value):
    doc = getattr(value, "__doc__", None)
    return f"{owner}.{name}" if not doc or not doc.strip() else None


def test_every_public_function_class_method_property_and_error_has_a_docstring():
    missing = []
    for name in omnicam.__all__:
        value = getattr(omnicam, name)
        missing.append(_documented("omnicam", name, value))
        if isinstance(value, type) and not issubclass(value, BaseException):
            for attribute, member in vars(value).items():
                if attribute.startswith("_") and attribute != "__init__":
                    continue
                if isinstance(member, property):
                    missing.append(_documented(name, attribute, member))
                elif callable(member):
                    missing.append(_documented(name, attribute, member))
    assert [m for m in missing if m] == []


@pytest.mark.parametrize("kind", [str, os.fsencode, lambda name: __import__("pathlib").Path(name)])
def test_a_file_name_holding_a_nul_is_refused_not_cut_short(tmp_path, kind):
    # The C library would read "…/a" for "…/a\0b"; Python's own open() refuses such a name, and so
    # does every function of omnicam that takes a file or folder (docs/python.md, "Errors").
    (tmp_path / "a").mkdir()
    name = kind(str(tmp_path / "a") + "\0b")
    nul = r"a\\x00b\": a file name cannot hold a NUL character$"
    calls = [omnicam.load_scene, omnicam.read_image, omnicam.read_uint16_png, omnicam.verify_dataset,
             omnicam.Dataset, lambda p: omnicam.read_exr_channels(p, ["R"]),
             lambda p: omnicam.run_dataset(p, tmp_path / "out"), lambda p: omnicam.run_dataset(tmp_path / "spec", p)]
    for call in calls:
        with pytest.raises(omnicam.InputError, match=nul):
            call(name)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a"]  # nothing written
    with pytest.raises(omnicam.InputError, match=r"^data_path: \"scenes\\x00/robocup2006\.json\": a file name cannot hold a NUL"):
        omnicam.data_path("scenes\0/robocup2006.json")
