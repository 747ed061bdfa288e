"""The installed package (pyproject.toml, setup.py; docs/python.md, "Installing"), as a user gets it.

From a fresh copy of the source tree: `python3 -m build --no-isolation` makes a wheel and an sdist.
With the copy renamed away, the wheel is installed into a new venv. From an empty folder, a user
script renders a frame and makes and reads a dataset, the `omnicam` entry point and
`python3 -m omnicam` render, and mypy --strict and stubtest check the installed types. Every
image is compared bit for bit with the CMake build's CLI (OMNICAM_BINARY) and module
(PYTHONPATH, this process's `omnicam`).

Run by CTest (python.package); the environment gives OMNICAM_SOURCE_DIR, OMNICAM_BINARY and
OMNICAM_BUILD_DIR.
"""

import json
import os
import re
import shutil
import subprocess
import sys
import tarfile
import tempfile
import time
import zipfile
from pathlib import Path

import numpy as np
import pytest

import omnicam  # the CMake build's module: the reference


def _required(name):
    value = os.environ.get(name)
    if not value:
        raise RuntimeError(f"{name} is not set: run this test through ctest (make test)")
    return Path(value)


SOURCE = _required("OMNICAM_SOURCE_DIR")
CLI = _required("OMNICAM_BINARY")
BUILD = _required("OMNICAM_BUILD_DIR")
SCENE = SOURCE / "scenes" / "robocup2006.json"
POSE = (1.0, -0.5, 30.0)
# The CLI's math (docs/conventions.md, "Reproducible pixels"), for the Python renders too.
PLAIN_MATH = "glibc.cpu.hwcaps=-FMA,-FMA4"

# Top-level folders of a working tree that are not the source: build and output folders.
NOT_SOURCE = {".git", "build", "build-package", "dist", "out"}

USER_SCRIPT = '''
import json, sys
import numpy as np
import omnicam

scene_file, spec, reference_dataset, out = sys.argv[1:]
scene = omnicam.load_scene(scene_file)
frame = omnicam.Renderer(scene).render((1.0, -0.5, 30.0), spp=4, shading="lit", outputs=["rgb", "depth", "instance"])
for name, image in frame.items():
    np.save(f"{out}/frame_{name}.npy", image)
# Blender through the extension: its driver script comes from the package's data.
np.save(f"{out}/blender_rgb.npy", omnicam.render(scene, (1.0, -0.5, 30.0), engine="blender", size=64)["rgb"])
omnicam.run_dataset(spec, f"{out}/dataset")
for label, folder in (("own", f"{out}/dataset"), ("cli", reference_dataset)):
    items = omnicam.Dataset(folder, outputs=["rgb", "depth"], check_hashes=True)
    for k in range(len(items)):
        np.save(f"{out}/{label}_{k}_rgb.npy", items[k]["rgb"])
        np.save(f"{out}/{label}_{k}_depth.npy", items[k]["depth"])
json.dump({"module": omnicam.__file__, "version": omnicam.__version__, "frames": len(items)},
          open(f"{out}/facts.json", "w"))
'''

TYPED_SCRIPT = '''
import numpy as np
import omnicam


def mean_depth(scene_file: str) -> float:
    renderer: omnicam.Renderer = omnicam.Renderer(omnicam.load_scene(scene_file))
    frame = renderer.render((0.0, 0.0, 0.0), outputs=["depth"], size=32)
    return float(np.mean(frame["depth"]))


version: str = omnicam.__version__
'''


def run(command, cwd, env=None, timeout=3000):
    """A command without a shell; its output shown if it fails."""
    done = subprocess.run([str(c) for c in command], cwd=cwd, env=env, capture_output=True, text=True,
                          timeout=timeout)
    assert done.returncode == 0, f"{command} failed ({done.returncode}):\n{done.stdout[-4000:]}\n{done.stderr[-4000:]}"
    return done


def user_environment(venv=None):
    """What a user's shell has: no build-tree PYTHONPATH, no omnicam overrides."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH" and not k.startswith("OMNICAM_")}
    if venv is not None:
        env["PATH"] = f"{venv / 'bin'}:{env.get('PATH', '/usr/bin:/bin')}"
        env["VIRTUAL_ENV"] = str(venv)
    return env


def not_source(folder, names):
    """Of `names` in `folder`, those that are not source: build and output folders, caches."""
    skipped = {n for n in names if n in ("__pycache__", "node_modules") or n.endswith(".pyc")}
    if Path(folder) == SOURCE:
        skipped |= {n for n in names if n in NOT_SOURCE or n.startswith("build")}
    return skipped | {n for n in names if (Path(folder) / n) == BUILD}


def copy_source_tree(target):
    shutil.copytree(SOURCE, target, ignore=not_source, symlinks=True)


def source_files(suffix):
    for folder, subfolders, files in os.walk(SOURCE):
        subfolders[:] = [d for d in subfolders if d not in not_source(folder, subfolders)]
        yield from (Path(folder) / f for f in files if f.endswith(suffix))


def decoded(path):
    return omnicam.read_image(str(path))


@pytest.fixture(scope="module")
def package(tmp_path_factory):
    """The wheel and sdist built from a fresh copy of the tree, the copy then renamed away; a venv
    with the wheel installed; an empty folder to work in."""
    root = Path(tempfile.mkdtemp(prefix="package-test-", dir=BUILD))
    try:
        tree, dist = root / "omnicam", root / "dist"
        copy_source_tree(tree)
        env = user_environment()
        env["CMAKE_BUILD_PARALLEL_LEVEL"] = str(os.cpu_count() or 1)
        started = time.monotonic()
        # As documented: the sdist first, then the wheel from the unpacked sdist (in a temporary
        # folder of python-build's, gone afterwards). ccache, with paths relative to each tree,
        # takes the objects `make build` compiled.
        run([sys.executable, "-m", "build", "--no-isolation", "--outdir", dist], cwd=tree, env=env)
        print(f"sdist and wheel built in {time.monotonic() - started:.1f} s")
        wheels, sdists = sorted(dist.glob("omnicam-*.whl")), sorted(dist.glob("omnicam-*.tar.gz"))
        assert len(wheels) == 1 and len(sdists) == 1, sorted(dist.iterdir())
        moved = tree.with_name("omnicam-moved-away")
        tree.rename(moved)  # nothing installed may need the tree it was built from
        venv = root / "venv"
        run([sys.executable, "-m", "venv", "--system-site-packages", venv], cwd=root, env=env)
        run([venv / "bin" / "pip", "install", "--no-build-isolation", "--no-index", wheels[0]], cwd=root, env=env)
        empty = root / "empty"
        empty.mkdir()
        yield {"root": root, "wheel": wheels[0], "sdist": sdists[0], "venv": venv, "empty": empty,
               "python": venv / "bin" / "python", "trees": [moved, tree, SOURCE, BUILD]}
    finally:
        shutil.rmtree(root)


def site_package(package):
    (folder,) = (package["venv"] / "lib").glob("python3*/site-packages/omnicam")
    return folder


def test_the_wheel_holds_the_extension_the_cli_the_stubs_and_the_data(package):
    names = set(zipfile.ZipFile(package["wheel"]).namelist())
    for name in ("omnicam/__init__.py", "omnicam/__main__.py", "omnicam/_omnicam.pyi", "omnicam/dataset.pyi",
                 "omnicam/py.typed", "omnicam/bin/omnicam", "omnicam/bin/omnicam-cli", "omnicam/bin/omnicam-ros",
                 "omnicam/data/refrender/blender_driver.py", "omnicam/data/calibration/write_rosbag.py",
                 "omnicam/data/scenes/robocup2006.json", "omnicam/data/experiments/plot_convergence.py",
                 "omnicam/data/docs/examples/dataset.json", "omnicam/data/docs/examples/calibration_room.json",
                 "omnicam/data/examples/recording/cool_noisy.json"):
        assert name in names, f"{name} is not in the wheel"
    assert any(n.startswith("omnicam/_omnicam.") and n.endswith(".so") for n in names)
    entry_points = next(n for n in names if n.endswith(".dist-info/entry_points.txt"))
    assert "omnicam = omnicam.__main__:main" in zipfile.ZipFile(package["wheel"]).read(entry_points).decode()
    print(f"wheel: {package['wheel'].stat().st_size / 1e6:.1f} MB")


def test_the_sdist_is_the_source_without_build_folders(package):
    with tarfile.open(package["sdist"]) as sdist:
        names = {n.split("/", 1)[1] for n in sdist.getnames() if "/" in n}
    for name in ("pyproject.toml", "setup.py", "CMakeLists.txt", "VERSION", "base/data_files.cpp",
                 "python/src/module.cpp", "scenes/robocup2006.json", "refrender/blender_driver.py"):
        assert name in names, f"{name} is not in the sdist"
    assert not any(n.startswith(("build/", "build-package/", "out/", ".git/")) for n in names)


def test_every_data_file_the_code_reads_is_installed(package):
    """Each dataFile("...") of the C++ sources names a file or folder of the package's data/."""
    names = set()
    for source in source_files(".cpp"):
        if not source.name.endswith("_test.cpp"):
            text = source.read_text(errors="replace")
            names |= set(re.findall(r'dataFile\("([^"]+)"\)', text))
            # The CLI's folders of them: scenesDir() + "/robocup2006.json" (app/cli_util.h).
            names |= {f"{folder}/{name}" for folder, name in
                      re.findall(r'(scenes|experiments)Dir\(\) \+ "/([^"]+)"', text)}
    assert {"refrender/blender_driver.py", "scenes/robocup2006.json", "experiments/plot_convergence.py"} <= names, \
        names  # the scan sees the calls
    data = site_package(package) / "data"
    for name in sorted(names):
        installed = data / name
        assert installed.is_file() or (installed.is_dir() and any(installed.iterdir())), f"{name} is not installed"


def test_no_installed_binary_names_a_source_or_build_tree(package):
    installed = site_package(package)
    binaries = [*installed.glob("_omnicam*.so"), *(installed / "bin" / name for name in ("omnicam", "omnicam-cli", "omnicam-ros"))]
    for binary in binaries:
        content = binary.read_bytes()
        for tree in package["trees"]:
            assert str(tree).encode() not in content, f"{binary.name} names {tree}"
        libraries = run(["ldd", binary], cwd=package["empty"]).stdout
        assert "not found" not in libraries, libraries
        assert not any(str(tree) in libraries for tree in package["trees"]), libraries


def test_a_user_script_renders_and_reads_datasets_as_the_cmake_build_does(package, tmp_path):
    spec = tmp_path / "spec.json"
    spec.write_text(json.dumps({
        "format": "omnicam-dataset/1", "scene": str(SCENE), "size": 64, "spp": 4, "shading": "lit",
        "poses": {"path": "thesis-loop", "frames": 3}, "outputs": {"rgb": "exr", "depth": True}}))
    reference = tmp_path / "cli-dataset"
    run([CLI, "dataset", spec, "-o", reference], cwd=tmp_path)
    run([CLI, "render", SCENE, "--pose=%g,%g,%g" % POSE, "--spp", 4, "--shading", "lit", "-o", tmp_path / "cli.exr"],
        cwd=tmp_path)
    run([CLI, "render", SCENE, "--pose=%g,%g,%g" % POSE, "--engine", "blender", "--size", 64,
         "-o", tmp_path / "cli-blender.exr"], cwd=tmp_path)
    script, out = package["empty"] / "user_script.py", tmp_path / "venv-out"
    out.mkdir()
    script.write_text(USER_SCRIPT)
    env = user_environment(package["venv"])
    env["GLIBC_TUNABLES"] = PLAIN_MATH
    run([package["python"], script, SCENE, spec, reference, out], cwd=package["empty"], env=env)
    facts = json.loads((out / "facts.json").read_text())
    assert Path(facts["module"]).is_relative_to(package["venv"]), facts["module"]
    assert facts["version"] == omnicam.__version__ == (SOURCE / "VERSION").read_text().strip()
    assert facts["frames"] == 3

    np.testing.assert_array_equal(np.load(out / "frame_rgb.npy"), decoded(tmp_path / "cli.exr"))
    np.testing.assert_array_equal(np.load(out / "blender_rgb.npy"), decoded(tmp_path / "cli-blender.exr"))
    own = omnicam.Renderer(omnicam.load_scene(str(SCENE))).render(POSE, spp=4, shading="lit",
                                                                     outputs=["depth", "instance"])
    for name in ("depth", "instance"):
        np.testing.assert_array_equal(np.load(out / f"frame_{name}.npy"), own[name])
    cli_frames = omnicam.Dataset(str(reference), outputs=["rgb", "depth"])
    for k in range(3):
        for label in ("own", "cli"):
            np.testing.assert_array_equal(np.load(out / f"{label}_{k}_rgb.npy"), cli_frames[k]["rgb"])
            np.testing.assert_array_equal(np.load(out / f"{label}_{k}_depth.npy"), cli_frames[k]["depth"])


@pytest.mark.parametrize("how", ["entry point", "python -m"])
def test_the_installed_cli_renders_the_cmake_clis_pixels(package, tmp_path, how):
    arguments = ["render", SCENE, "--pose=%g,%g,%g" % POSE, "--spp", 4, "--shading", "path", "--size", 96]
    run([CLI, *arguments, "-o", tmp_path / "cli.exr"], cwd=tmp_path)
    command = [package["venv"] / "bin" / "omnicam"] if how == "entry point" else [package["python"], "-m", "omnicam"]
    run([*command, *arguments, "-o", tmp_path / "installed.exr"], cwd=package["empty"],
        env=user_environment(package["venv"]))
    np.testing.assert_array_equal(decoded(tmp_path / "installed.exr"), decoded(tmp_path / "cli.exr"))
    version = run([*command, "--version"], cwd=package["empty"], env=user_environment(package["venv"])).stdout
    assert version.startswith(f"omnicam {omnicam.__version__} "), version


def test_the_cli_starts_without_loading_the_extension_which_loads_on_first_use(package):
    """The entry point and `python -m omnicam` exec the CLI; the compiled part (~280 shared
    libraries) would only double a short command's cost (omnicam/__init__.py)."""
    probe = ("import sys, omnicam.__main__; before = 'omnicam._omnicam' in sys.modules; "
             "rig = omnicam.Rig; print(before, 'omnicam._omnicam' in sys.modules, rig.__module__, "
             "[n for n in omnicam.__all__ + ['__version__', 'dataset'] if not hasattr(omnicam, n)])")
    out = run([package["python"], "-c", probe], cwd=package["empty"], env=user_environment(package["venv"])).stdout
    assert out.split() == ["False", "True", "omnicam", "[]"], out


@pytest.mark.parametrize("arguments", [["rings"], ["render", SCENE, "--engine", "blender", "--size", 64]],
                         ids=["rings", "blender"])
def test_the_installed_cli_finds_its_own_data_files(package, tmp_path, arguments):
    """`rings` reads its default scene, the Blender engine its driver script, from the package's
    data, not from any tree; the images equal the CMake CLI's."""
    run([package["venv"] / "bin" / "omnicam", *arguments, "-o", tmp_path / "installed.png"], cwd=package["empty"],
        env=user_environment(package["venv"]))
    run([CLI, *arguments, "-o", tmp_path / "cli.png"], cwd=tmp_path)
    np.testing.assert_array_equal(decoded(tmp_path / "installed.png"), decoded(tmp_path / "cli.png"))


def test_a_script_anywhere_finds_the_scenes_the_package_comes_with(package):
    """omnicam.data_path() is the installed package's data, from any working directory."""
    probe = ("import omnicam; path = omnicam.data_path('scenes/robocup2006.json'); "
             "print(omnicam.load_scene(path).name, path.is_relative_to(omnicam.data_path()), omnicam.data_path())")
    out = run([package["python"], "-c", probe], cwd=package["empty"], env=user_environment(package["venv"])).stdout.split()
    assert out[:2] == ["robocup2006", "True"], out
    assert Path(out[2]) == site_package(package) / "data", out


def test_a_typed_user_script_passes_mypy_strict_and_the_stubs_match_the_module(package):
    script = package["empty"] / "typed_user.py"
    script.write_text(TYPED_SCRIPT)
    env = user_environment(package["venv"])
    run([package["python"], "-m", "mypy", "--strict", "--no-incremental", script], cwd=package["empty"], env=env)
    # data/ holds scripts for other interpreters (Blender's, rosbag's), not modules of the package.
    config = package["empty"] / "stubtest.ini"
    config.write_text("[mypy]\nexclude = /omnicam/data/\n")
    run([package["python"], "-m", "mypy.stubtest", "--mypy-config-file", config, "--allowlist",
         SOURCE / "python" / "stubtest_allowlist.txt", "omnicam"], cwd=package["empty"], env=env)
