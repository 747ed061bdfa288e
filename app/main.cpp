// omnicam — simulate catadioptric omnidirectional cameras and prove the images right.
#include <CLI/CLI.hpp>
#include <csignal>
#include <cstdio>
#include <exception>
#include <new>
#include <string>

#include "commands.h"
#include "cpu_independent_math.h"
#include "errors.h"
#include "fast_renderer.h"
#include "interrupts.h"
#include "malloc_tuning.h"
#include "memory_budget.h"

namespace {

// Prints "omnicam: <message>" as one line, whatever the message holds: each echoed user string
// was quoted where the message was made, this catches what slipped through (and CLI11's own).
int reportError(const std::string& message, int exitCode) {
  std::fprintf(stderr, "omnicam: %s\n", omnicam::oneLine(message).c_str());
  return exitCode;
}

}  // namespace

// Exit codes (docs/conventions.md): 0 ok, 1 comparison over threshold, 2 bad input or usage,
// 3 an external renderer failed, 4 internal error (a bug: please report it), 5 an output could
// not be written (disk full, file-size limit, permissions) or the machine lacks the memory the
// work needs (memory_budget.h).
int main(int argc, char** argv) {
  omnicam::restartWithPlainMath(argv);  // first: it may start the program again
  // Past a file-size limit, write() must fail with EFBIG (exit 5, nothing left under the final
  // name) instead of the signal killing the process mid-file.
  std::signal(SIGXFSZ, SIG_IGN);
  omnicam::keepFreedMemoryInTheHeap();
  omnicam::installInterruptHandlers();
  CLI::App app{"omnicam: exact catadioptric omnidirectional camera simulation"};
  app.require_subcommand(1);
  app.set_version_flag("--version", omnicam::fastRendererVersion());
  omnicam::cli::addRenderCommand(app);
  omnicam::cli::addRingsCommand(app);
  omnicam::cli::addProjectCommand(app);
  omnicam::cli::addCameraRaysCommand(app);
  omnicam::cli::addExportCommand(app);
  omnicam::cli::addStudyCommand(app);
  omnicam::cli::addViewCommand(app);
  omnicam::cli::addBenchCommand(app);
  omnicam::cli::addRosCommand(app);
  omnicam::cli::addExperimentCommands(app);
  int exitCode = 0;
  omnicam::cli::addDemoCommand(app, exitCode);
  omnicam::cli::addCompareCommand(app, exitCode);
  omnicam::cli::addDatasetCommand(app, exitCode);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const omnicam::Interrupted& e) {
    // Every external program is ended and its job folder gone; then the usual death by the signal.
    reportError(e.what(), 0);
    omnicam::dieBySignal(e.signal());
  } catch (const CLI::ParseError& e) {
    return reportError(e.what(), 2);
  } catch (const omnicam::InputError& e) {
    return reportError(e.what(), 2);
  } catch (const omnicam::ExternalError& e) {
    // Not one line on purpose: the renderer's last output follows on lines of its own.
    std::fprintf(stderr, "omnicam: %s\n", e.what());
    return 3;
  } catch (const omnicam::OutputError& e) {
    return reportError(e.what(), 5);
  } catch (const omnicam::MemoryShortage& e) {
    return reportError(e.what(), 5);
  } catch (const std::bad_alloc&) {
    return reportError("internal error: out of memory (inputs within the documented limits should not get here)", 4);
  } catch (const std::exception& e) {
    return reportError(std::string("internal error: ") + e.what(), 4);
  }
  return exitCode;
}
