#include "experiment_folder.h"

#include <filesystem>
#include <utility>

#include "errors.h"
#include "input_limits.h"
#include "json_text.h"
#include "safe_files.h"

namespace omnicam {

namespace {

// The study a results.json belongs to: its "study", or for texture-realism runs written before
// it carried one, their "conditions".
std::optional<std::string> studyOf(const nlohmann::json& results) {
  if (!results.is_object()) return std::nullopt;
  if (results.contains("study")) {
    if (!results["study"].is_string()) return std::nullopt;
    return results["study"].get<std::string>();
  }
  if (results.contains("conditions")) return "texture-realism";
  return std::nullopt;
}

// The results file by which a folder written before marks tells its study, for the studies
// whose results.json names none.
constexpr std::pair<const char*, const char*> kResultsFileOfStudy[] = {{"convergence.json", "realistic-convergence"},
                                                                       {"path-convergence.json", "path-convergence"}};

// The study an earlier run's mark in `dir` names; nullopt without a mark.
std::optional<std::string> markedStudy(const std::string& dir) {
  const EntryKind kind = entryInside(dir, kExperimentMark);
  if (kind == EntryKind::Missing) return std::nullopt;
  const std::string where = showPath(dir + "/" + kExperimentMark);
  if (kind != EntryKind::File)
    throw InputError(where + (kind == EntryKind::Link ? ": a link (omnicam follows none in its outputs)" : ": not a regular file") +
                     ": give another folder");
  const nlohmann::json mark = parseJsonText(readFileInside(dir, kExperimentMark, limits::kMaxJsonFileBytes), where);
  if (!mark.is_object() || !mark.contains("study") || !mark["study"].is_string())
    throw InputError(where + ": not written by an omnicam experiment (it names no study): give another folder");
  return mark["study"].get<std::string>();
}

// The first entry of `dir` by name (for the message about a folder of other files).
std::string firstEntry(const std::string& dir) {
  std::string first;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (first.empty() || name < first) first = name;
  }
  return first;
}

}  // namespace

void checkExperimentFolder(const std::string& dir, const std::string& study) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec) || std::filesystem::is_empty(dir, ec)) return;
  const auto refuseOther = [&](const std::string& where, const std::string& theirs) {
    throw InputError(showPath(where) + ": holds the results of experiment " + quote(theirs) + ", not " + study +
                     ": give another folder");
  };
  if (const std::optional<std::string> marked = markedStudy(dir)) {
    if (*marked != study) refuseOther(dir + "/" + kExperimentMark, *marked);
    earlierExperimentResults(dir, study);  // its results, if any, are the study's too
    return;
  }
  if (earlierExperimentResults(dir, study)) return;
  for (const auto& [file, theirs] : kResultsFileOfStudy)
    if (entryInside(dir, file) == EntryKind::File) {
      if (theirs != study) refuseOther(dir + "/" + file, theirs);
      return;
    }
  throw InputError(showPath(dir) + ": holds files no omnicam experiment wrote (" + quote(firstEntry(dir)) +
                   "): give an empty or new folder");
}

void markExperimentFolder(const std::string& dir, const std::string& study) {
  if (entryInside(dir, kExperimentMark) == EntryKind::File) return;
  SafeFolder(dir).writeFile(kExperimentMark, nlohmann::json({{"study", study}}).dump(1) + "\n", Durability::Synced);
}

std::optional<nlohmann::json> earlierExperimentResults(const std::string& dir, const std::string& study) {
  const EntryKind kind = entryInside(dir, "results.json");
  if (kind == EntryKind::Missing) return std::nullopt;
  const std::string where = showPath(dir + "/results.json");
  if (kind != EntryKind::File)
    throw InputError(where + (kind == EntryKind::Link ? ": a link (omnicam follows none in its outputs)" : ": not a regular file") +
                     ": give another folder");
  const nlohmann::json results = parseJsonText(readFileInside(dir, "results.json", limits::kMaxJsonFileBytes), where);
  const std::optional<std::string> theirs = studyOf(results);
  if (!theirs) throw InputError(where + ": not written by an omnicam experiment (it names no study): give another folder");
  if (*theirs != study)
    throw InputError(where + ": holds the results of experiment " + quote(*theirs) + ", not " + study +
                     ": give another folder");
  return results;
}

}  // namespace omnicam
