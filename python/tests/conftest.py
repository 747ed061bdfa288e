"""Shared fixtures: the repository's data through OMNICAM_SOURCE_DIR (set by CTest), never the
working directory; the CLI binary for cross-checks through OMNICAM_BINARY."""

import os
import pathlib
import subprocess

import pytest


def _required(name):
    value = os.environ.get(name)
    if not value:
        raise RuntimeError(f"{name} is not set: run the Python tests through ctest (make test)")
    return value


SOURCE = pathlib.Path(_required("OMNICAM_SOURCE_DIR"))
BINARY = _required("OMNICAM_BINARY")


@pytest.fixture
def source():
    return SOURCE


@pytest.fixture
def robocup():
    import omnicam

    return omnicam.load_scene(str(SOURCE / "scenes" / "robocup2006.json"))


def run_cli(*args):
    """The omnicam CLI with `args` (a list, no shell): (exit code, stdout, stderr)."""
    done = subprocess.run([BINARY, *map(str, args)], capture_output=True, text=True)
    return done.returncode, done.stdout, done.stderr
