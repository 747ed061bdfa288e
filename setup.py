"""Builds the Python package with the project's one CMake build (pyproject.toml, docs/python.md).

The extension `omnicam._omnicam`, the CLI and the data files it reads are what CMake builds and
installs with OMNICAM_PACKAGE=ON (component python_package): the same targets, flags and libraries
as `make build`. setuptools adds the pure-Python part and packs the wheel.

The CMake build folder is `build-package/` in the source tree, or $OMNICAM_PACKAGE_BUILD_DIR.
"""

import os
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE = Path(__file__).resolve().parent
PACKAGE_BUILD = Path(os.environ.get("OMNICAM_PACKAGE_BUILD_DIR", SOURCE / "build-package"))
PACKAGE_BUILD.mkdir(parents=True, exist_ok=True)  # egg_info writes there first


class CMakeBuiltExtension(Extension):
    def __init__(self) -> None:
        super().__init__("omnicam._omnicam", sources=[])


class BuildWithCMake(build_ext):
    def build_extension(self, ext: Extension) -> None:
        if self.inplace:  # it would put binaries and data into python/omnicam/ of the source tree
            sys.exit("omnicam: editable installs (pip install -e) are not supported: install with "
                     "`pip install --no-build-isolation --no-index .`, or use PYTHONPATH=build/python")
        # The folder that holds omnicam/ in the wheel's tree.
        package_root = Path(self.get_ext_fullpath(ext.name)).resolve().parent.parent
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        run(["cmake", "-S", str(SOURCE), "-B", str(PACKAGE_BUILD), "-DCMAKE_BUILD_TYPE=Release", "-DOMNICAM_PACKAGE=ON",
             f"-DPython_EXECUTABLE={sys.executable}"])
        run(["cmake", "--build", str(PACKAGE_BUILD), "-j", jobs])
        run(["cmake", "--install", str(PACKAGE_BUILD), "--component", "python_package", "--strip",
             "--prefix", str(package_root)])


def run(command: list) -> None:
    print(" ".join(command), flush=True)
    subprocess.run(command, check=True)


setup(
    ext_modules=[CMakeBuiltExtension()],
    cmdclass={"build_ext": BuildWithCMake},
    # setuptools' own folders beside CMake's, out of the way of a `make build` tree.
    options={"build": {"build_base": str(PACKAGE_BUILD / "setuptools")},
             "egg_info": {"egg_base": str(PACKAGE_BUILD)}},
)
