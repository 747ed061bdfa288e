#include "plot_script.h"

#include <stdlib.h>

#include <filesystem>

#include "errors.h"
#include "external_process.h"

namespace omnicam {

namespace fs = std::filesystem;

void runPlotScript(const std::string& plotScript, const std::string& resultsFolder) {
  const fs::path root = fs::absolute(resultsFolder);
  // The script runs in a folder of its own (its HOME: matplotlib's .cache and .config go there,
  // not into the results), removed afterwards; it writes into the results folder it is given.
  std::string pattern = (fs::temp_directory_path() / "omnicam_plot_XXXXXX").string();
  if (!::mkdtemp(pattern.data())) throw OutputError(showPath(pattern) + ": cannot make a folder for the plot script");
  struct RemoveFolder {
    const std::string& path;
    ~RemoveFolder() {
      std::error_code ignored;
      fs::remove_all(path, ignored);
    }
  } removeFolder{pattern};
  const ProcessResult plot = runProcess({"/usr/bin/python3", fs::absolute(plotScript).string(), root.string()}, pattern,
                                        (root / "figures/plot.log").string(), 600.0);
  if (plot.notFound) throw OutputError("/usr/bin/python3: not found (make deps installs python3 and python3-matplotlib)");
  if (plot.exitCode != 0)
    throw OutputError(showPath(plotScript) + ": the figures failed (exit " + std::to_string(plot.exitCode) + "): " + plot.logTail);
}

}  // namespace omnicam
