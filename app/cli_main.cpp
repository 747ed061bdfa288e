#include "cli_main.h"

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <exception>
#include <new>
#include <regex>
#include <string>
#include <vector>

#include "closest_name.h"
#include "cpu_independent_math.h"
#include "errors.h"
#include "file_confinement.h"
#include "interrupts.h"
#include "malloc_tuning.h"
#include "memory_budget.h"

namespace omnicam::cli {

namespace {

// Prints "omnicam: <message>" as one line, whatever the message holds: each echoed user string
// was quoted where the message was made, this catches what slipped through (and CLI11's own).
int reportError(const std::string& message, int exitCode) {
  std::fprintf(stderr, "omnicam: %s\n", oneLine(message).c_str());
  return exitCode;
}

// The names a user may type for the options of `command`: each long and short name.
std::vector<std::string> optionNames(const CLI::App& command) {
  std::vector<std::string> names;
  for (const CLI::Option* option : command.get_options()) {
    for (const std::string& name : option->get_lnames()) names.push_back("--" + name);
    for (const std::string& name : option->get_snames()) names.push_back("-" + name);
  }
  return names;
}

// " (did you mean --size?)" for an option, its letters compared without their dashes.
std::string optionSuggestion(const std::string& given, const CLI::App& command) {
  const auto bare = [](const std::string& name) { return name.substr(std::min(name.find_first_not_of('-'), name.size())); };
  std::vector<std::string> names;
  for (const std::string& name : optionNames(command)) names.push_back(bare(name));
  const auto best = closestName(bare(given), names);
  if (!best) return "";
  for (const std::string& name : optionNames(command))
    if (bare(name) == *best) return " (did you mean " + name + "?)";
  return "";
}

// CLI11's message, or a clearer one where the words show the mistake: an unknown command, or an
// unknown option (reported before a missing argument it may have caused) of the program or of the
// command it was given to, with the name it most likely meant.
std::string parseErrorMessage(const CLI::App& app, int argc, char** argv, const CLI::ParseError& error) {
  std::vector<std::string> commands;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) commands.push_back(sub->get_name());
  if (argc > 1 && argv[1][0] != '-' && std::find(commands.begin(), commands.end(), argv[1]) == commands.end())
    return "unknown command " + quote(argv[1]) + didYouMean(argv[1], commands) + "; omnicam --help lists them";
  // The program, then each command the words chose, deepest last.
  std::string words = "omnicam";
  for (const CLI::App* command = &app; command;
       command = command->get_subcommands().empty() ? nullptr : command->get_subcommands().front()) {
    if (command != &app) words += " " + command->get_name();
    for (const std::string& word : command->remaining()) {
      if (word.size() < 2 || word[0] != '-') continue;
      const std::string name = word.substr(0, word.find('='));
      return (command == &app ? std::string() : command->get_name() + ": ") + "unknown option " + quote(name) +
             optionSuggestion(name, *command) + "; " + words + " --help lists them";
    }
  }
  // CLI11's words for an option given twice ("--pose: At Most 1 required but received 2").
  static const std::regex givenTwice(R"(^(-[-\w]*): At Most 1 required but received (\d+)$)");
  std::smatch twice;
  const std::string what = error.what();
  if (std::regex_match(what, twice, givenTwice)) return twice[1].str() + ": given " + twice[2].str() + " times; give it once";
  return what;
}

// The first argument that is not UTF-8, or null.
const char* firstNotUtf8(int argc, char** argv) {
  for (int k = 1; k < argc; ++k)
    if (!isValidUtf8(argv[k])) return argv[k];
  return nullptr;
}

// Whether the command only reads the names it is given: dataset --status, --verify and --merge
// (a manifest records names relative to its folder), compare without a report, JUnit file or diff
// image. Every other command records a name it is given in JSON, HTML or XML, which hold UTF-8
// only — some after their work, or beside files already written — so a name that is not UTF-8 is
// refused before anything starts.
bool onlyReadsItsNames(int argc, char** argv) {
  const auto has = [&](const char* word) {
    for (int k = 1; k < argc; ++k)
      if (std::string(argv[k]) == word || std::string(argv[k]).rfind(std::string(word) + "=", 0) == 0) return true;
    return false;
  };
  const std::string verb = argc > 1 ? argv[1] : "";
  if (verb == "dataset") return has("--status") || has("--verify") || has("--merge");
  if (verb == "compare") return !has("--report") && !has("--junit") && !has("--diff");
  return false;
}

std::string notUtf8Message(const char* name) {
  return quote(name, kEchoedPathChars) +
         ": not UTF-8: omnicam records the names it is given in JSON, HTML and XML (sidecars, manifests, reports), "
         "which hold UTF-8 only: rename it";
}

}  // namespace

void prepareProcess(char** argv) {
  restartWithPlainMath(argv);  // first: it may start the program again
  // Past a file-size limit, write() must fail with EFBIG (exit 5, nothing left under the final
  // name) instead of the signal killing the process mid-file.
  std::signal(SIGXFSZ, SIG_IGN);
  keepFreedMemoryInTheHeap();
  installInterruptHandlers();
}

// Exit codes (docs/conventions.md): 0 ok, 1 comparison over threshold, 2 bad input or usage,
// 3 an external renderer failed, 4 internal error (a bug: please report it), 5 an output could
// not be written (disk full, file-size limit, permissions) or the machine lacks the memory the
// work needs (memory_budget.h).
int runCommandLine(CLI::App& app, int argc, char** argv, const int& exitCode) {
  if (const char* name = firstNotUtf8(argc, argv); name && !onlyReadsItsNames(argc, argv))
    return reportError(notUtf8Message(name), 2);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const Interrupted& e) {
    // Every external program is ended and its job folder gone; then the usual death by the signal.
    reportError(e.what(), 0);
    dieBySignal(e.signal());
  } catch (const CLI::ParseError& e) {
    return reportError(parseErrorMessage(app, argc, argv, e), 2);
  } catch (const InputError& e) {
    return reportError(withOutsideFilesHint(e.what(), "pass --allow-outside-files to permit it"), 2);
  } catch (const ExternalError& e) {
    // Not one line on purpose: the renderer's last output follows on lines of its own.
    std::fprintf(stderr, "omnicam: %s\n", e.what());
    return 3;
  } catch (const OutputError& e) {
    return reportError(e.what(), 5);
  } catch (const MemoryShortage& e) {
    return reportError(e.what(), 5);
  } catch (const std::bad_alloc&) {
    return reportError("internal error: out of memory (inputs within the documented limits should not get here)", 4);
  } catch (const std::exception& e) {
    return reportError(std::string("internal error: ") + e.what(), 4);
  }
  return exitCode;
}

}  // namespace omnicam::cli
