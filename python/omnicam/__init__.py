"""omnicam: catadioptric omnidirectional camera simulation with exact ground truth.

The library's own objects, not subprocess calls (docs/python.md)::

    import omnicam
    scene = omnicam.load_scene("scenes/robocup2006.json")
    renderer = omnicam.Renderer(scene)
    frame = renderer.render((1.0, 2.0, 90.0), outputs=["rgb", "depth", "instance"])
    camera = omnicam.Camera(scene.rig)
    pixels = camera.project(points_world, pose=(1.0, 2.0, 90.0))
"""

# The compiled part loads on first use (PEP 562): `omnicam ...` and `python -m omnicam`, which
# only start the CLI, would otherwise load its ~280 shared libraries first, doubling what a short
# command costs. Type checkers and editors read __init__.pyi.
import importlib as _importlib
import typing as _typing

__all__ = [
    "Camera",
    "Dataset",
    "ExternalError",
    "InputError",
    "MemoryShortage",
    "OutputError",
    "Renderer",
    "Rig",
    "Scene",
    "coco_annotations",
    "data_path",
    "load_scene",
    "mapping_arena",
    "read_exr_channels",
    "read_image",
    "read_uint16_png",
    "render",
    "run_dataset",
    "srgb8",
    "verify_dataset",
]
_COMPILED = frozenset(__all__) - {"Dataset"} | {"__version__"}
_SUBMODULES = frozenset({"_omnicam", "dataset"})


def __getattr__(name: str) -> _typing.Any:
    if name == "Dataset":
        from .dataset import Dataset as value
    elif name in _COMPILED:
        from . import _omnicam

        value = getattr(_omnicam, name)
    elif name in _SUBMODULES:
        value = _importlib.import_module(f".{name}", __name__)
    else:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__() -> _typing.List[str]:
    return sorted(set(globals()) | _COMPILED | _SUBMODULES | {"Dataset"})
