#pragma once
// What every omnicam executable's main does around its CLI11 app: the process set up the same
// way, and the same exit codes and one-line errors (docs/conventions.md) for every verb.
#include <CLI/CLI.hpp>

namespace omnicam::cli {

// First in main: CPU-independent math (it may start the program again), SIGXFSZ ignored, the
// heap tuned, SIGINT/SIGTERM recorded (interrupts.h).
void prepareProcess(char** argv);
// Parses and runs `app`: the exit code, `exitCode` as the verb set it if it succeeded.
int runCommandLine(CLI::App& app, int argc, char** argv, const int& exitCode);

}  // namespace omnicam::cli
