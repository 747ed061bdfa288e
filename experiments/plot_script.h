#pragma once
// An experiment's matplotlib figures: its plot script run by Debian's python3 (make deps installs
// python3-matplotlib for it, not whatever python3 comes first on PATH) in the results folder,
// which it reads and whose figures/ it writes.
#include <string>

namespace omnicam {

// Runs `plotScript` with the results folder as its argument (both made absolute: the process
// starts in that folder), its log in figures/plot.log. OutputError when it fails.
void runPlotScript(const std::string& plotScript, const std::string& resultsFolder);

}  // namespace omnicam
