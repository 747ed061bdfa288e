"""omnicam: catadioptric omnidirectional camera simulation with exact ground truth.

The library's own objects, not subprocess calls (docs/python.md)::

    import omnicam
    scene = omnicam.load_scene(omnicam.data_path("scenes/robocup2006.json"))
    renderer = omnicam.Renderer(scene)
    frame = renderer.render((1.0, 2.0, 90.0), outputs=["rgb", "depth", "instance"])
    camera = omnicam.Camera(scene.rig)
    pixels = camera.project(points_world, pose=(1.0, 2.0, 90.0))
"""

# The compiled part loads on first use (PEP 562): `omnicam ...` and `python -m omnicam`, which
# only start the CLI, would otherwise load its ~280 shared libraries first, doubling what a short
# command costs. Type checkers and editors read __init__.pyi.
import difflib as _difflib
import functools as _functools
import importlib as _importlib
import numbers as _numbers
import os as _os
import re as _re
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


# A mistyped keyword ("shadng=") gets pybind11's TypeError: every overload's signature and the
# call, hundreds of characters. _omnicam's functions and methods are wrapped so that it names the
# keyword and the one meant instead, as the CLI names a mistyped flag, and an argument (keyword or
# positional) of a type it cannot be with the type it takes. Other TypeErrors pass as they are.
# _omnicam calls this when it loads (python/src/module.cpp).
_INCOMPATIBLE = ("incompatible function arguments", "incompatible constructor arguments")
_OVERLOAD = _re.compile(r"^\s+\d+\. [\w.]*\((.*)\)(?: -> .*)?$", _re.M)
_PARAMETER = _re.compile(r"(?:^|, )\*?(\w+):")
_TYPED = _re.compile(r"(?:^|, )\*?(\w+): ([^=,\[]+(?:\[[^=]*?\])?)")


def _is_bool(value: _typing.Any) -> bool:
    # numpy's bool (numpy.bool_; numpy 2's numpy.bool) by its dtype's kind, not its type's name.
    return isinstance(value, bool) or getattr(getattr(value, "dtype", None), "kind", None) == "b"


def _fits(value: _typing.Any, annotation: str) -> bool:
    """Whether `value` can be what pybind11 names `annotation` (the simple cases; else True)."""
    annotation = annotation.strip()
    optional = _re.fullmatch(r"Optional\[(.*)\]", annotation)
    if optional:
        return value is None or _fits(value, optional.group(1))
    # numpy's scalars are numbers too (numbers.Integral, numbers.Real), and pybind11 takes them.
    if annotation == "int":
        return isinstance(value, _numbers.Integral) and not _is_bool(value)
    if annotation == "float":
        return isinstance(value, _numbers.Real) and not _is_bool(value)
    if annotation == "bool":
        return _is_bool(value)
    if annotation == "str":
        return isinstance(value, str)
    if annotation == "List[str]":
        return isinstance(value, (list, tuple)) and all(isinstance(item, str) for item in value)
    if annotation == "function" or annotation.startswith("Callable["):
        return callable(value)
    if annotation in ("os.PathLike", "Union[os.PathLike, str, bytes]"):
        return isinstance(value, (str, bytes, _os.PathLike))
    if annotation.startswith("omnicam._omnicam."):  # one of omnicam's own classes
        return type(value).__name__ == annotation.rsplit(".", 1)[1]
    return True


def _shown(value: _typing.Any) -> str:
    """A value in an error message: its type and a repr of one short line (an array by its shape)."""
    if hasattr(value, "shape") and hasattr(value, "dtype"):
        return f"{type(value).__name__} of shape {tuple(value.shape)} and dtype {value.dtype}"
    text = " ".join(repr(value).split())
    return f"{type(value).__name__} {text if len(text) <= 80 else text[:77] + '...'}"


def _wrong_argument(message: str, kwargs: _typing.Dict[str, _typing.Any]) -> _typing.Optional[str]:
    """The first argument whose value cannot be its parameter's type, in every overload, described."""
    overloads = [dict(_TYPED.findall(overload)) for overload in _OVERLOAD.findall(message)]
    for key, value in kwargs.items():
        types = [typed[key] for typed in overloads if key in typed]
        if types and not any(_fits(value, annotation) for annotation in types):
            wanted = sorted(set(t.strip().replace("omnicam._omnicam.", "omnicam.") for t in types))
            return f"{key} must be {' or '.join(wanted)} (got {_shown(value)})"
    return None


def _placed_elsewhere(key: str, name: str) -> _typing.Optional[str]:
    """The hint for a render setting given where it does not go: where it goes, or None."""
    from . import _omnicam

    for row in _omnicam._request_fields():
        if row["python"] == key and row["place"]:
            where = "Renderer(...)" if row["place"] == "Renderer" else "Renderer.render()"
            return f" ({key} is an argument of {where}, not of {name}(); docs/render-settings.md)"
    return None


def _checked(function: _typing.Callable[..., _typing.Any], name: str) -> _typing.Callable[..., _typing.Any]:
    @_functools.wraps(function)
    def call(*args: _typing.Any, **kwargs: _typing.Any) -> _typing.Any:
        try:
            return function(*args, **kwargs)
        except TypeError as error:
            message = str(error)
            if not any(words in message for words in _INCOMPATIBLE):
                raise
            overloads = _OVERLOAD.findall(message)
            names = {p for overload in overloads for p in _PARAMETER.findall(overload)} - {"self"}
            for key in kwargs:
                if names and key not in names:
                    close = _difflib.get_close_matches(key, sorted(names), n=1)
                    hint = _placed_elsewhere(key, name) or (
                        f" (did you mean {close[0]}?)" if close else f" (it takes {', '.join(sorted(names))})")
                    raise TypeError(f"{name}(): unknown keyword argument {key!r}{hint}") from None
            # Positional arguments by the first overload's order, up to its bare "*" (what follows
            # is keyword-only): a method's self first, but a constructor's signature has none (its
            # self, not yet made, must not be looked at).
            given = dict(kwargs)
            if overloads:
                positional = args[1:] if "incompatible constructor arguments" in message else args
                head = _re.split(r"(?:^|, )\*(?:, |$)", overloads[0], maxsplit=1)[0]
                parameters = [p for p, _ in _TYPED.findall(head)]
                if len(positional) > len(parameters):
                    shown = [p for p in parameters if p != "self"]
                    raise TypeError(f"{name}(): takes {len(shown)} positional argument{'s' if len(shown) != 1 else ''}"
                                    f" ({', '.join(shown) or 'none'}), got {len(positional) - (len(parameters) - len(shown))};"
                                    " the others by keyword") from None
                for parameter, value in zip(parameters, positional):
                    given.setdefault(parameter, value)
            given.pop("self", None)
            wrong = _wrong_argument(message, given)
            if wrong:
                raise TypeError(f"{name}(): {wrong}") from None
            raise

    return call


def _check_keywords(module: _typing.Any) -> None:
    for name, value in list(vars(module).items()):
        if isinstance(value, type):
            for attribute, method in list(vars(value).items()):
                if type(method).__name__ == "instancemethod":
                    shown = name if attribute == "__init__" else f"{name}.{attribute}"
                    setattr(value, attribute, _checked(method, shown))
        elif type(value).__name__ == "builtin_function_or_method" and not name.startswith("_"):
            setattr(module, name, _checked(value, name))


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
