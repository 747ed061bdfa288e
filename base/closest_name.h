#pragma once
// "Did you mean …?": the known name a mistyped one most likely meant, for messages about
// unknown commands, flags and fields.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace omnicam {

// Edits (insert, delete, substitute, swap two neighbours) from `a` to `b`: the optimal string
// alignment distance.
int editDistance(std::string_view a, std::string_view b);

// The name in `names` fewest edits from `given`, if that is few enough to be a typo: at most one
// edit per three characters of `given` (at least one), and not `given` itself. On a tie, the first.
// None for a `given` of one character (every other is one edit away) or of more than 64. Failing
// a typo, the one name whose first word `given` is ("colour" → "colour_class"), if only one is.
std::optional<std::string> closestName(std::string_view given, const std::vector<std::string>& names);

// " (did you mean X?)" for closestName's answer, or "": for names omnicam defines (fields, flags).
std::string didYouMean(std::string_view given, const std::vector<std::string>& names);
// The same with the name quoted and escaped (" (did you mean "x"?)"): for names a user wrote
// (a scene's paths and materials), which may hold anything.
std::string didYouMeanQuoted(std::string_view given, const std::vector<std::string>& names);

}  // namespace omnicam
