#include "plot_script.h"

#include <filesystem>

#include "errors.h"
#include "external_process.h"

namespace omnicam {

namespace fs = std::filesystem;

void runPlotScript(const std::string& plotScript, const std::string& resultsFolder) {
  const fs::path root = fs::absolute(resultsFolder);
  const ProcessResult plot = runProcess({"/usr/bin/python3", fs::absolute(plotScript).string(), root.string()}, root.string(),
                                        (root / "figures/plot.log").string(), 600.0);
  if (plot.notFound) throw OutputError("/usr/bin/python3: not found (make deps installs python3 and python3-matplotlib)");
  if (plot.exitCode != 0)
    throw OutputError(showPath(plotScript) + ": the figures failed (exit " + std::to_string(plot.exitCode) + "): " + plot.logTail);
}

}  // namespace omnicam
