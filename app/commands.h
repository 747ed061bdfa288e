#pragma once
// CLI verbs (docs/conventions.md §5). Each registers its flags on the CLI11 app and runs as a thin wrapper
// over library functions. Errors propagate as InputError (exit 2) / ExternalError (exit 3).
#include <CLI/CLI.hpp>

namespace omnicam::cli {

void addRenderCommand(CLI::App& app);
void addRingsCommand(CLI::App& app);
void addProjectCommand(CLI::App& app);
// Exit 3 when the calibration fails (too few views, OpenCV's initialisation).
void addCalibrateCommand(CLI::App& app);
void addCameraRaysCommand(CLI::App& app);
// Sets exitCode: 64 + a bit per section that fell short (demo_sections.h).
void addDemoCommand(CLI::App& app, int& exitCode);
void addExportCommand(CLI::App& app);
void addStudyCommand(CLI::App& app);
void addViewCommand(CLI::App& app);
void addBenchCommand(CLI::App& app);
// The live ROS 1 sensor (ros/live_sensor.h): the verb of omnicam-ros (ros_main.cpp).
void addRosCommand(CLI::App& app);
// `ros` in omnicam-cli: hands `argv` over to omnicam-ros (ros_handoff.cpp).
void addRosHandoff(CLI::App& app, char** argv);
// experiment texture-realism and arena hall.
void addExperimentCommands(CLI::App& app);
// Sets exitCode: 1 when a verified dataset has problems or is incomplete, 130 when interrupted.
void addDatasetCommand(CLI::App& app, int& exitCode);
// Sets exitCode to 1 when a threshold fails.
void addCompareCommand(CLI::App& app, int& exitCode);

}  // namespace omnicam::cli
