// omnicam-ros: the `omnicam ros` verb (ros_command.cpp) as an executable of its own, the one that
// links ROS 1, so that no other verb loads ROS's libraries. build/bin/omnicam starts it for
// `omnicam ros ...`, with the same exit codes and errors as every verb (cli_main.h).
#include <CLI/CLI.hpp>

#include "cli_main.h"
#include "commands.h"
#include "fast_renderer.h"

int main(int argc, char** argv) {
  omnicam::cli::prepareProcess(argv);
  CLI::App app{"omnicam: exact catadioptric omnidirectional camera simulation"};
  app.require_subcommand(1);
  app.set_version_flag("--version", omnicam::fastRendererVersion());
  omnicam::cli::addRosCommand(app);
  return omnicam::cli::runCommandLine(app, argc, argv, 0);
}
