"""omnicam: catadioptric omnidirectional camera simulation with exact ground truth.

The library's own objects, not subprocess calls (docs/python.md)::

    import omnicam
    scene = omnicam.load_scene("scenes/robocup2006.json")
    renderer = omnicam.Renderer(scene)
    frame = renderer.render((1.0, 2.0, 90.0), outputs=["rgb", "depth", "instance"])
    camera = omnicam.Camera(scene.rig)
    pixels = camera.project(points_world, pose=(1.0, 2.0, 90.0))
"""

from ._omnicam import (  # noqa: F401  (the public interface)
    Camera,
    ExternalError,
    InputError,
    MemoryShortage,
    OutputError,
    Renderer,
    Rig,
    Scene,
    coco_annotations,
    load_scene,
    mapping_arena,
    read_exr_channels,
    read_image,
    read_uint16_png,
    render,
    run_dataset,
    verify_dataset,
)
from ._omnicam import __version__ as __version__  # the file VERSION
from .dataset import Dataset  # noqa: F401

# Name the compiled classes as users import them (omnicam.Rig, not omnicam._omnicam.Rig).
for _name in ("Camera", "ExternalError", "InputError", "MemoryShortage", "OutputError", "Renderer", "Rig", "Scene"):
    globals()[_name].__module__ = __name__
del _name

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
    "load_scene",
    "mapping_arena",
    "read_exr_channels",
    "read_image",
    "read_uint16_png",
    "render",
    "run_dataset",
    "verify_dataset",
]
