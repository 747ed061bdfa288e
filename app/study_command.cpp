// omnicam study -o FILE.md: the thesis' mirror polygon-count study (experiments/polygon_study.h):
// the flags, the checks before any work, and the report's command line.
#include <cstdio>
#include <filesystem>
#include <memory>

#include "atomic_file.h"
#include "cli_util.h"
#include "commands.h"
#include "errors.h"
#include "markup.h"
#include "number_format.h"
#include "polygon_study.h"
#include "safe_files.h"

namespace omnicam::cli {

namespace {

struct StudyArgs {
  std::string out;
  int spp = 16;
  double timingSeconds = 1.0;
};

// The command that writes this report again, with the flags it was given.
std::string studyCommand(const StudyArgs& a) {
  const StudyArgs defaults;
  std::string command = "omnicam study -o " + shellPath(a.out);
  if (a.spp != defaults.spp) command += " --spp " + std::to_string(a.spp);
  if (a.timingSeconds != defaults.timingSeconds) command += " --timing-seconds " + roundTrip(a.timingSeconds);
  return command;
}

void runStudy(const StudyArgs& a) {
  namespace fs = std::filesystem;
  checkSpp(a.spp, "--spp");  // before any folder is made
  if (fs::path(a.out).extension() != ".md") throw InputError("-o: " + showPath(a.out) + ": the report is Markdown: give FILE.md");
  const std::vector<std::string> files = polygonStudyFiles(a.out);
  const fs::path figures = fs::path(files[1]).parent_path();
  // The report's folder may be new (made with its figures/); an existing one must not hold a
  // folder under the report's name, nor figures/ under a figure's: a folder under the last one's
  // name would otherwise end the study after the others were written.
  std::error_code ec;
  const fs::path folder = fs::path(a.out).parent_path().empty() ? fs::path(".") : fs::path(a.out).parent_path();
  if (fs::is_directory(folder, ec)) {
    checkOutputFile(a.out, "-o");
    checkFoldersInside(folder.string(), "figures");  // a link planted there is not followed
  }
  if (fs::is_directory(figures, ec))
    for (size_t k = 1; k < files.size(); ++k) checkOutputFile(files[k], "-o (its figures)");
  ensureDirectory(folder.string(), "-o");
  makeFoldersInside(folder.string(), "figures");
  const PolygonStudyOptions options{scenesDir() + "/robocup2006.json", scenesDir() + "/incidence-rings.json", a.out, a.spp,
                                    a.timingSeconds, studyCommand(a)};
  runPolygonStudy(options, [](const std::string& mode) { std::printf("study: %s\n", mode.c_str()); });
  std::printf("study: wrote %s and its figures %s\n", showPath(a.out).c_str(), showPath((figures / (fs::path(a.out).stem().string() + "_*")).string()).c_str());
}

}  // namespace

void addStudyCommand(CLI::App& app) {
  auto args = std::make_shared<StudyArgs>();
  CLI::App* cmd = app.add_subcommand("study", "Measure the thesis' cube-map/mirror-mesh method (writes Markdown + figures)");
  // Required: a default would write docs/ into whatever folder the user stands in.
  cmd->add_option("-o,--output", args->out, "Markdown file FILE.md (its figures go to figures/FILE_* beside it)")->required();
  addSppOption(*cmd, args->spp, "Samples per pixel for the quality columns (default 16)");
  cmd->add_option("--timing-seconds", args->timingSeconds, "Seconds timed per mode (default 1)")->check(numberIn(0, 3600, true));
  cmd->callback([args] { runStudy(*args); });
}

}  // namespace omnicam::cli
