#include "plot_script.h"

#include <filesystem>

#include "errors.h"
#include "external_process.h"
#include "job_folder.h"
#include "safe_files.h"

namespace omnicam {

namespace fs = std::filesystem;

void runPlotScript(const std::string& plotScript, const std::string& resultsFolder) {
  const fs::path root = fs::absolute(resultsFolder);
  // The script runs in a job folder of its own (its HOME: matplotlib's .cache and .config go
  // there, not into the results), removed afterwards; it writes into the results folder it is given.
  const JobFolder job("omnicam-plot", /*keep=*/false);
  const ProcessResult plot = runProcess({"/usr/bin/python3", fs::absolute(plotScript).string(), root.string()}, job.path(),
                                        (root / "figures/plot.log").string(), 600.0);
  if (plot.notFound) throw OutputError("/usr/bin/python3: not found (make deps installs python3 and python3-matplotlib)");
  if (plot.exitCode != 0)
    throw OutputError(showPath(plotScript) + ": the figures failed (exit " + std::to_string(plot.exitCode) + "): " + plot.logTail);
  // A log that says nothing is not kept among the results (one with warnings is).
  const SafeFolder results(root.string());
  std::error_code ec;
  if (results.entry("figures/plot.log") == EntryKind::File && fs::file_size(root / "figures/plot.log", ec) == 0 && !ec)
    results.removeFile("figures/plot.log");
}

}  // namespace omnicam
