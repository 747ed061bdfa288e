// omnicam — simulate catadioptric omnidirectional cameras and prove the images right.
#include <CLI/CLI.hpp>
#include <csignal>
#include <cstdio>
#include <exception>
#include <new>

#include "commands.h"
#include "errors.h"

// Exit codes (docs/conventions.md): 0 ok, 1 comparison over threshold, 2 bad input or usage,
// 3 an external renderer failed, 4 internal error (a bug: please report it), 5 an output could
// not be written (disk full, file-size limit, permissions).
int main(int argc, char** argv) {
  // Past a file-size limit, write() must fail with EFBIG (exit 5, nothing left under the final
  // name) instead of the signal killing the process mid-file.
  std::signal(SIGXFSZ, SIG_IGN);
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
  omnicam::cli::addExperimentCommands(app);
  int exitCode = 0;
  omnicam::cli::addCompareCommand(app, exitCode);
  omnicam::cli::addDatasetCommand(app, exitCode);
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
  } catch (const omnicam::OutputError& e) {
    std::fprintf(stderr, "omnicam: %s\n", e.what());
    return 5;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "omnicam: internal error: out of memory (inputs within the documented limits should not get here)\n");
    return 4;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "omnicam: internal error: %s\n", e.what());
    return 4;
  }
  return exitCode;
}
