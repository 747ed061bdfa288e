#include "experiment_folder.h"

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

}  // namespace

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
