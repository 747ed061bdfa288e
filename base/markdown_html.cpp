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

// The cells of a pipe-table row: "| a | b |" → {"a", "b"}.
std::vector<std::string> cellsOf(const std::string& row) {
  std::vector<std::string> cells;
  std::string inner = row.substr(1);
  if (!inner.empty() && inner.back() == '|') inner.pop_back();
  std::istringstream in(inner);
  for (std::string cell; std::getline(in, cell, '|');) {
    const size_t first = cell.find_first_not_of(' '), last = cell.find_last_not_of(' ');
    cells.push_back(first == std::string::npos ? "" : cell.substr(first, last - first + 1));
  }
  return cells;
}

bool startsWith(const std::string& line, const std::string& prefix) { return line.compare(0, prefix.size(), prefix) == 0; }

}  // namespace

std::string htmlFromMarkdown(const std::string& markdown) {
  std::istringstream in(markdown);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  std::string html;
  for (size_t k = 0; k < lines.size();) {
    const std::string& line = lines[k];
    if (line.empty()) {
      ++k;
    } else if (line[0] == '#') {
      const size_t level = line.find_first_not_of('#');
      const size_t text = line.find_first_not_of(' ', level);
      const std::string tag = "h" + std::to_string(std::min<size_t>(level, 6));
      html += "<" + tag + ">" + inlineHtml(text == std::string::npos ? "" : line.substr(text)) + "</" + tag + ">\n";
      ++k;
    } else if (line[0] == '|') {
      html += "<table>\n";
      for (size_t row = 0; k < lines.size() && startsWith(lines[k], "|"); ++k, ++row) {
        if (row == 1) continue;  // the separator under the header
        const char* cell = row == 0 ? "th" : "td";
        html += "<tr>";
        for (const std::string& c : cellsOf(lines[k])) html += std::string("<") + cell + ">" + inlineHtml(c) + "</" + cell + ">";
        html += "</tr>\n";
      }
      html += "</table>\n";
    } else if (startsWith(line, "![") && line.find("](") != std::string::npos && line.back() == ')') {
      const size_t middle = line.find("](");
      html += "<p><img src=\"" + escapeMarkup(line.substr(middle + 2, line.size() - middle - 3)) + "\" alt=\"" +
              escapeMarkup(line.substr(2, middle - 2)) + "\" style=\"max-width:100%\"></p>\n";
      ++k;
    } else if (startsWith(line, "- ")) {
      html += "<ul>\n";
      for (; k < lines.size() && startsWith(lines[k], "- "); ++k) html += "<li>" + inlineHtml(lines[k].substr(2)) + "</li>\n";
      html += "</ul>\n";
    } else {
      std::string paragraph;
      for (; k < lines.size() && !lines[k].empty() && lines[k][0] != '#' && lines[k][0] != '|' && !startsWith(lines[k], "- ") &&
             !startsWith(lines[k], "![");
           ++k)
        paragraph += (paragraph.empty() ? "" : " ") + lines[k];
      html += "<p>" + inlineHtml(paragraph) + "</p>\n";
    }
  }
  return html;
}

}  // namespace omnicam
