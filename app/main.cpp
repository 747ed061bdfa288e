// omnicam — simulate catadioptric omnidirectional cameras and prove the images right.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "commands.h"
#include "errors.h"

int main(int argc, char** argv) {
  CLI::App app{"omnicam: exact catadioptric omnidirectional camera simulation"};
  app.require_subcommand(1);
  omnicam::cli::addRenderCommand(app);
  omnicam::cli::addRingsCommand(app);
  omnicam::cli::addProjectCommand(app);
  omnicam::cli::addDemoCommand(app);
  omnicam::cli::addExportCommand(app);
  omnicam::cli::addStudyCommand(app);
  omnicam::cli::addViewCommand(app);
  omnicam::cli::addBenchCommand(app);
  int exitCode = 0;
  omnicam::cli::addCompareCommand(app, exitCode);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "omnicam: %s\n", e.what());
    return 2;
  } catch (const omnicam::InputError& e) {
    std::fprintf(stderr, "omnicam: %s\n", e.what());
    return 2;
  } catch (const omnicam::ExternalError& e) {
    std::fprintf(stderr, "omnicam: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "omnicam: internal error: %s\n", e.what());
    return 4;
  }
  return exitCode;
}
