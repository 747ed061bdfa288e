"""`omnicam ...` and `python3 -m omnicam ...` of the installed package: the CLI itself.

The package carries the CLI's binaries in `omnicam/bin/` (docs/python.md, "Installing"). This
replaces the Python process with the CLI's launcher, which sets CPU-independent math
(docs/conventions.md, "Reproducible pixels") and starts the CLI: the same pixels, exit codes and
signals as `build/bin/omnicam`.
"""

import os
import sys
from pathlib import Path


def _launcher() -> Path:
    package = Path(__file__).resolve().parent
    installed = package / "bin" / "omnicam"
    # In a CMake build tree (PYTHONPATH=build/python) the CLI is build/bin/omnicam.
    build_tree = package.parent.parent / "bin" / "omnicam"
    return installed if installed.exists() or not build_tree.exists() else build_tree


def main() -> None:
    launcher = _launcher()
    try:
        os.execv(launcher, ["omnicam", *sys.argv[1:]])
    except OSError as error:
        sys.stderr.write(f"omnicam: cannot start {launcher}: {error.strerror} (is the package built?)\n")
        sys.exit(2)


if __name__ == "__main__":
    main()
