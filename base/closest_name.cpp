#include "closest_name.h"

#include <algorithm>
#include <cstdlib>

#include "errors.h"

namespace omnicam {

int editDistance(std::string_view a, std::string_view b) {
  // Three rows of the dynamic programme: the one before the previous is needed for swaps.
  std::vector<int> before(b.size() + 1), previous(b.size() + 1), current(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) previous[j] = static_cast<int>(j);
  for (size_t i = 1; i <= a.size(); ++i) {
    current[0] = static_cast<int>(i);
    for (size_t j = 1; j <= b.size(); ++j) {
      const int substitution = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitution});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) current[j] = std::min(current[j], before[j - 2] + 1);
    }
    std::swap(before, previous);
    std::swap(previous, current);
  }
  return previous[b.size()];
}

std::optional<std::string> closestName(std::string_view given, const std::vector<std::string>& names) {
  // One letter is one edit from every other: no suggestion. Past a long word's length, none is a
  // typo of it (and the distance's cost stays small whatever a file holds).
  constexpr size_t kLongestName = 64;
  if (given.size() < 2 || given.size() > kLongestName) return std::nullopt;
  const int allowed = std::max(1, static_cast<int>(given.size()) / 3);
  std::optional<std::string> best;
  int bestDistance = allowed + 1;
  for (const std::string& name : names) {
    if (name == given) continue;
    const int lengths = std::abs(static_cast<int>(name.size()) - static_cast<int>(given.size()));
    if (lengths > allowed) continue;  // at least that many edits
    const int distance = editDistance(given, name);
    if (distance < bestDistance) best = name, bestDistance = distance;
  }
  if (best || given.size() < 3) return best;
  // No typo: the first word of exactly one name ("colour" for "colour_class").
  for (const std::string& name : names)
    if (name.size() > given.size() && name.compare(0, given.size(), given) == 0 && name[given.size()] == '_') {
      if (best) return std::nullopt;  // two names begin so: neither is the one meant
      best = name;
    }
  return best;
}

std::string didYouMean(std::string_view given, const std::vector<std::string>& names) {
  const auto best = closestName(given, names);
  return best ? " (did you mean " + *best + "?)" : "";
}

std::string didYouMeanQuoted(std::string_view given, const std::vector<std::string>& names) {
  const auto best = closestName(given, names);
  return best ? " (did you mean " + quote(*best) + "?)" : "";
}

}  // namespace omnicam
