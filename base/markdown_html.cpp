#include "markdown_html.h"

#include <algorithm>
#include <sstream>
#include <vector>

#include "markup.h"

namespace omnicam {

namespace {

// Escaped text with **bold** and `code` spans; an unpaired marker stays as it is.
std::string inlineHtml(const std::string& text) {
  std::string out;
  for (size_t i = 0; i < text.size();) {
    const bool bold = text.compare(i, 2, "**") == 0, code = text[i] == '`';
    const std::string marker = bold ? "**" : code ? "`" : "";
    const size_t close = marker.empty() ? std::string::npos : text.find(marker, i + marker.size());
    if (close == std::string::npos) {
      out += escapeMarkup(std::string(1, text[i]));
      ++i;
      continue;
    }
    const std::string inner = text.substr(i + marker.size(), close - i - marker.size());
    out += bold ? "<strong>" + inlineHtml(inner) + "</strong>" : "<code>" + escapeMarkup(inner) + "</code>";
    i = close + marker.size();
  }
  return out;
}

// The cells of a pipe-table row: "| a | b |" → {"a", "b"}; "| a ||" → {"a", ""}.
std::vector<std::string> cellsOf(const std::string& row) {
  std::vector<std::string> cells;
  const size_t end = row.size() > 1 && row.back() == '|' ? row.size() - 1 : row.size();
  for (size_t from = 1; from <= end;) {
    const size_t bar = std::min(row.find('|', from), end);
    const std::string cell = row.substr(from, bar - from);
    const size_t first = cell.find_first_not_of(' '), last = cell.find_last_not_of(' ');
    cells.push_back(first == std::string::npos ? "" : cell.substr(first, last - first + 1));
    from = bar + 1;
  }
  return cells;
}

// "![alt](src)" and nothing else on the line, src a relative path (the reports' own figures; no
// scheme such as javascript:).
bool isImageLine(const std::string& line) {
  const size_t middle = line.find("](");
  return line.starts_with("![") && middle != std::string::npos && line.back() == ')' &&
         line.find(':', middle) == std::string::npos;
}

// Whether a line begins a block of its own (and so ends a paragraph).
// "3. text": where an ordered list item's text starts, or 0 when the line is none.
size_t orderedItemText(const std::string& line) {
  const size_t digits = line.find_first_not_of("0123456789");
  if (digits == 0 || digits == std::string::npos || digits > 9 || line.compare(digits, 2, ". ") != 0) return 0;
  return digits + 2;
}

bool startsBlock(const std::string& line) {
  return line.empty() || line[0] == '#' || line[0] == '|' || line.starts_with("- ") || orderedItemText(line) || isImageLine(line);
}

}  // namespace

std::string htmlFromMarkdown(const std::string& markdown) {
  std::istringstream in(markdown);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  std::string html;
  for (size_t k = 0; k < lines.size();) {
    const std::string& line = lines[k];
    if (line.empty()) {
      ++k;
    } else if (line[0] == '#') {
      const size_t level = std::min(line.find_first_not_of('#'), line.size());
      const size_t text = line.find_first_not_of(' ', level);
      const std::string tag = "h" + std::to_string(std::min<size_t>(level, 6));
      html += "<" + tag + ">" + inlineHtml(text == std::string::npos ? "" : line.substr(text)) + "</" + tag + ">\n";
      ++k;
    } else if (line[0] == '|') {
      html += "<table>\n";
      for (size_t row = 0; k < lines.size() && lines[k].starts_with("|"); ++k, ++row) {
        if (row == 1) continue;  // the separator under the header
        const char* cell = row == 0 ? "th" : "td";
        html += "<tr>";
        for (const std::string& c : cellsOf(lines[k])) html += std::string("<") + cell + ">" + inlineHtml(c) + "</" + cell + ">";
        html += "</tr>\n";
      }
      html += "</table>\n";
    } else if (isImageLine(line)) {
      const size_t middle = line.find("](");
      html += "<p><img src=\"" + escapeMarkup(line.substr(middle + 2, line.size() - middle - 3)) + "\" alt=\"" +
              escapeMarkup(line.substr(2, middle - 2)) + "\" style=\"max-width:100%\"></p>\n";
      ++k;
    } else if (orderedItemText(line)) {
      html += "<ol>\n";
      for (; k < lines.size() && orderedItemText(lines[k]); ++k) html += "<li>" + inlineHtml(lines[k].substr(orderedItemText(lines[k]))) + "</li>\n";
      html += "</ol>\n";
    } else if (line.starts_with("- ")) {
      html += "<ul>\n";
      for (; k < lines.size() && lines[k].starts_with("- "); ++k) html += "<li>" + inlineHtml(lines[k].substr(2)) + "</li>\n";
      html += "</ul>\n";
    } else {
      std::string paragraph = line;  // this line starts no other block, so the paragraph has it
      for (++k; k < lines.size() && !startsBlock(lines[k]); ++k) paragraph += " " + lines[k];
      html += "<p>" + inlineHtml(paragraph) + "</p>\n";
    }
  }
  return html;
}

}  // namespace omnicam
