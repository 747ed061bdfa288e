// `omnicam ros` in the CLI's help: the verb itself is the omnicam-ros executable (ros_main.cpp),
// the only one that links ROS, which the launcher starts directly. Started some other way (the
// CLI run by hand), the CLI hands the whole command line over to it.
#include "commands.h"
#include "errors.h"
#include "sibling_program.h"

namespace omnicam::cli {

void addRosHandoff(CLI::App& app, char** argv) {
  CLI::App* cmd = app.add_subcommand("ros", "Run as a live ROS 1 camera: render the spec's cameras for each pose ROS sends "
                                            "(`omnicam ros --help` for its flags; docs/ros.md)");
  cmd->prefix_command();  // everything after `ros` is omnicam-ros's to read, --help too
  cmd->set_help_flag();
  cmd->callback([argv] { throw ExternalError(execSibling("omnicam-ros", argv)); });  // returns only if it failed
}

}  // namespace omnicam::cli
