#pragma once
// The files omnicam reads at run time besides its inputs: the Blender driver, the ROS bag writer,
// the plotting scripts and the bundled scenes. They keep their places in the source tree
// (`refrender/blender_driver.py`, `scenes/robocup2006.json`, ...) under one data root:
// - a CMake build reads them from its source tree;
// - an installed Python package (pyproject.toml) carries them in `omnicam/data/` and finds them
//   beside its own binaries, wherever it was installed, never in a source or build tree.
#include <filesystem>
#include <string>
#include <string_view>

namespace omnicam {

// The data root this build reads from (see above). An installed binary that cannot find itself
// throws std::runtime_error rather than read files relative to the working directory.
std::filesystem::path dataRoot();

// dataRoot() / relative, e.g. dataFile("refrender/blender_driver.py").
std::filesystem::path dataFile(std::string_view relative);

// For an input `name` that does not exist here: "; omnicam comes with PATH" when omnicam's own
// files have it — a bare name in `folder` ("robocup2006.json" in scenes), or the path as the
// docs write it from the repository ("docs/examples/dataset.json") — else "".
std::string bundledFileHint(const std::string& name, std::string_view folder);

}  // namespace omnicam
