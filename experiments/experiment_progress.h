#pragma once
// How every experiment reports its progress: the stage it is in, and how much of it is done, for
// the CLI's progress bar (app/ draws it; the experiments only count).
#include <functional>
#include <string>

namespace omnicam {

using ExperimentProgress = std::function<void(const std::string& stage, int done, int total)>;

}  // namespace omnicam
