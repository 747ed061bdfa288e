// omnicam — simulate catadioptric omnidirectional cameras and prove the images right.
#include <CLI/CLI.hpp>

#include "cli_main.h"
#include "commands.h"
#include "fast_renderer.h"

int main(int argc, char** argv) {
  omnicam::cli::prepareProcess(argv);
  CLI::App app{"omnicam: exact catadioptric omnidirectional camera simulation"};
  app.require_subcommand(1);
  app.set_version_flag("--version", omnicam::fastRendererVersion());
  omnicam::cli::addRenderCommand(app);
  omnicam::cli::addRingsCommand(app);
  omnicam::cli::addProjectCommand(app);
  omnicam::cli::addCalibrateCommand(app);
  omnicam::cli::addCameraRaysCommand(app);
  omnicam::cli::addExportCommand(app);
  omnicam::cli::addStudyCommand(app);
  omnicam::cli::addViewCommand(app);
  omnicam::cli::addBenchCommand(app);
  omnicam::cli::addRosHandoff(app, argv);
  omnicam::cli::addExperimentCommands(app);
  int exitCode = 0;
  omnicam::cli::addDemoCommand(app, exitCode);
  omnicam::cli::addCompareCommand(app, exitCode);
  omnicam::cli::addDatasetCommand(app, exitCode);
  return omnicam::cli::runCommandLine(app, argc, argv, exitCode);
}
