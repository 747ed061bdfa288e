"""omnicam.Dataset: a dataset folder (docs/dataset-format.md) as a map-style dataset.

It needs nothing but omnicam, so a torch.utils.data.DataLoader takes it as it is. The folder is
read as untrusted input: the manifest strictly, files only inside the folder, links never
followed, hashes checked on request.
"""

import difflib
import operator
import os

from ._omnicam import OUTPUTS, InputError, Rig, _DatasetReader, verify_dataset  # OUTPUTS: the outputs a frame may hold


class _Item(dict):
    """A dataset item: a dict whose missing key says why it is missing."""

    _written = ()  # the outputs the dataset holds, and those the Dataset reads
    _read = ()

    def __missing__(self, key):
        if key in OUTPUTS and key not in self._written:
            raise KeyError(f"{key!r}: the dataset holds no {key} (its spec's outputs wrote: {', '.join(self._written)})")
        if key in OUTPUTS:
            raise KeyError(f"{key!r}: not read: this Dataset reads outputs {', '.join(self._read)} "
                           f"(give outputs=[..., {key!r}] to read it too)")
        close = difflib.get_close_matches(str(key), list(self), n=1)
        hint = f"did you mean {close[0]!r}? " if close else ""
        raise KeyError(f"{key!r}: no such key ({hint}keys: {', '.join(self)})")


class Dataset:
    """The frames of one camera of a dataset folder.

    ``len(dataset)`` is the number of finished frames. ``dataset[i]`` is the i-th of them (in
    frame order; negative indices count from the end). ``dataset[i, "rear"]`` gives another
    camera's view of the same frame. Each item is a dict:

    - ``index``, ``timestamp`` (seconds, the exposure start), ``robot_pose`` and ``pose`` (the
      camera's), each pose as (x, y, yaw_deg) at the timestamp;
    - ``velocity``: the robot's (vx, vy, yaw_rate_deg_per_s) over the exposure (docs/motion.md);
    - ``robot_tilt_deg``: the robot's (roll, pitch), (0, 0) for a level robot;
    - ``rig``: the omnicam.Rig the frame was rendered with (a vibrating robot's frame rig, else
      the camera's rig);
    - ``recording``: the recording camera of this frame and camera (a dict in the spec's
      ``recording`` format, every value fixed): the values drawn for it, or the spec's own when it
      draws nothing; None without a recording camera. ``render(..., recording=item["recording"],
      frame=index * cameras + camera_position)`` records the frame again;
    - ``camera`` and ``intrinsics`` (the manifest's entry for the camera: the model and its
      parameters);
    - one entry per output the dataset holds, or per output asked for in ``outputs``:
      - ``rgb``: (H, W, 4) float32, linear, premultiplied alpha;
      - ``depth``: (H, W) float32 metres;
      - ``normal``: (H, W, 3) float32;
      - ``instance`` and ``semantic``: (H, W) uint16;
      - ``landmarks``: a dict;
      - ``coco``: the frame's COCO annotations (a dict; the camera's whole COCO file is
        ``<camera>/coco.json``).

    Both layouts read the same: one file per output, or one OpenEXR per frame (``"layout":
    "multilayer"``), decoded once per item. Files are opened when an item is read, not before. Pickling keeps only the folder and the
    options, so each DataLoader worker process opens the folder again itself.
    ``check_hashes=True`` re-hashes every file read against the manifest. ``verify()`` re-hashes
    them all.
    """

    def __init__(self, path, camera=None, outputs=None, check_hashes=False):
        """Opens the folder and reads its manifest (errors here): ``camera`` default the first,
        ``outputs`` a list of output names (default every output written)."""
        self.path = os.fspath(path)
        self.check_hashes = bool(check_hashes)
        self._reader = _DatasetReader(self.path)  # reads and checks the manifest now: errors here
        cameras = self._reader.cameras
        self.camera = cameras[0] if camera is None else camera
        if self.camera not in cameras:
            raise InputError(f"camera {self.camera!r} is not in {self.path} (cameras: {', '.join(cameras)})")
        written = self._reader.header["outputs"]["written"]
        if isinstance(outputs, (str, bytes)):  # would be walked letter by letter
            raise TypeError(f"outputs must be a list of output names, such as [{outputs!r}] (got {type(outputs).__name__} {outputs!r})")
        self.outputs = tuple(written if outputs is None else outputs)
        for output in self.outputs:
            if output not in written:
                close = difflib.get_close_matches(str(output), written, n=1)
                hint = f"did you mean {close[0]}? " if close else ""
                raise InputError(f"output {output!r} is not in {self.path} ({hint}written: {', '.join(written)})")

    # The reader holds the whole manifest and open state: workers open their own.
    def __getstate__(self):
        state = dict(self.__dict__)
        state["_reader"] = None
        return state

    def __setstate__(self, state):
        self.__dict__.update(state)

    @property
    def reader(self):
        """The C++ reader of the folder (opened again after unpickling)."""
        if self._reader is None:
            self._reader = _DatasetReader(self.path)
        return self._reader

    @property
    def cameras(self):
        """The dataset's camera names."""
        return self.reader.cameras

    @property
    def header(self):
        """The manifest without its frames: spec, engine, scene, settings, cameras, ids."""
        return self.reader.header

    @property
    def classes(self):
        """[{"id", "name"}]: the semantic ids (0: none)."""
        return self.header["classes"]

    @property
    def instances(self):
        """[{"id", "name", "class", "class_id"}]: the instance ids (0: none)."""
        return self.header["instances"]

    def _camera_entry(self, camera):
        """The manifest's entry of a camera (default this dataset's camera); InputError naming the
        cameras if there is none of that name (a bare StopIteration would end a caller's generator)."""
        camera = self.camera if camera is None else camera
        for entry in self.header["cameras"]:
            if entry["name"] == camera:
                return entry
        cameras = [entry["name"] for entry in self.header["cameras"]]
        raise InputError(f"camera {camera!r} is not in {self.path} (cameras: {', '.join(cameras)})")

    def intrinsics(self, camera=None):
        """The manifest's intrinsics of a camera (default this dataset's camera)."""
        return self._camera_entry(camera)["intrinsics"]

    def rig(self, camera=None):
        """The camera's rig as the manifest states it (default this dataset's camera): an omnicam.Rig."""
        return Rig(self._camera_entry(camera)["rig"])

    def __len__(self):
        """The number of finished frames (a dataset still being rendered has fewer than its spec asks)."""
        return len(self.reader.frames)

    def __getitem__(self, key):
        """``dataset[i]``: the i-th finished frame of this dataset's camera, as the class describes;
        ``dataset[i, "rear"]``: another camera's of the same frame."""
        position, camera = key if isinstance(key, tuple) else (key, self.camera)
        try:
            position = operator.index(position)
        except TypeError:
            raise TypeError("Dataset indices are frame positions (int) or (position, camera) tuples, "
                            f"not {type(position).__name__}") from None
        frames = self.reader.frames
        if not -len(frames) <= position < len(frames):
            raise IndexError(f"frame {position} of {len(frames)}")
        index = frames[position]
        frame = self.reader.frame(index)
        if camera not in frame["cameras"]:
            raise KeyError(f"camera {camera!r} is not in frame {index} (its cameras: {', '.join(sorted(frame['cameras']))})")
        item = _Item({
            "index": index,
            "timestamp": frame["timestamp"],
            "robot_pose": frame["robot_pose"],
            "pose": frame["cameras"][camera]["pose"],
            "velocity": frame["velocity"],
            "robot_tilt_deg": frame["robot_tilt_deg"],
            "rig": frame["cameras"][camera].get("rig") or self.rig(camera),
            "recording": frame["cameras"][camera].get("recording"),
            "camera": camera,
            "intrinsics": self.intrinsics(camera),
        })
        item._written, item._read = tuple(self.header["outputs"]["written"]), self.outputs
        item.update(self.reader.read(index, camera, list(self.outputs), self.check_hashes))
        return item

    def verify(self):
        """Re-hashes every file the manifest lists: {"files", "problems", "ok"}."""
        return verify_dataset(self.path)

    def __repr__(self):
        return f"<omnicam.Dataset {self.path!r} camera {self.camera!r}, {len(self)} frames>"
