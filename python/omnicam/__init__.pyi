"""What `import omnicam` offers (__init__.py loads it on first use). Each name is re-exported
(`X as X`), which is what __init__.py's __all__ lists."""

from ._omnicam import (
    Camera as Camera,
    ExternalError as ExternalError,
    InputError as InputError,
    MemoryShortage as MemoryShortage,
    OutputError as OutputError,
    Renderer as Renderer,
    Rig as Rig,
    Scene as Scene,
    __version__ as __version__,
    coco_annotations as coco_annotations,
    data_path as data_path,
    load_scene as load_scene,
    mapping_arena as mapping_arena,
    read_exr_channels as read_exr_channels,
    read_image as read_image,
    read_uint16_png as read_uint16_png,
    render as render,
    run_dataset as run_dataset,
    srgb8 as srgb8,
    verify_dataset as verify_dataset,
)
from .dataset import Dataset as Dataset
