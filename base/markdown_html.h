#pragma once
// The Markdown the experiments' reports write, as HTML, so report.html shows what the .md shows.
// A subset, the one those reports use: ATX headings, pipe tables (the row under the header is
// the separator), images on a line of their own, "- " and "1. " list items, paragraphs, and inline
// **bold** and `code`. Every character of the text is escaped (escapeMarkup): names in the
// tables come from users' files.
#include <string>

namespace omnicam {

std::string htmlFromMarkdown(const std::string& markdown);

}  // namespace omnicam
