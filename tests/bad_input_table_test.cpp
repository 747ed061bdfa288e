// The bad-input table of docs/robustness.md, run row by row: the documentation is the test.
// Every row must exit with its code, print exactly one line containing its fragment, and leave
// the output folder empty (and no temporary file anywhere in the inputs).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>

#include "shell_command.h"
#include <string>
#include <vector>

namespace omnicam {
namespace {

namespace fs = std::filesystem;
using testing::isOneLine;

struct Row {
  int number;
  std::string command, fragment;
  int exitCode;
};

std::vector<Row> readTable(const std::string& markdown) {
  std::ifstream in(markdown);
  std::vector<Row> rows;
  bool inside = false;
  std::string line;
  // | N | `command` | exit | `fragment` |
  const std::regex row(R"(^\| (\d+) \| `(.+)` \| (\d) \| `(.+)` \|$)");
  while (std::getline(in, line)) {
    if (line.find("<!-- bad-inputs:begin -->") != std::string::npos) inside = true;
    if (line.find("<!-- bad-inputs:end -->") != std::string::npos) inside = false;
    std::smatch m;
    if (inside && std::regex_match(line, m, row)) rows.push_back({std::stoi(m[1]), m[2], m[4], std::stoi(m[3])});
  }
  return rows;
}

std::string replaceAll(std::string text, const std::string& from, const std::string& to) {
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

// The row's command in its own shell (rows may set limits with ulimit), stderr captured too.
testing::CommandResult shell(const std::string& command) {
  return testing::runShell("sh -c '" + replaceAll(command, "'", "'\\''") + "' 2>&1");
}

std::vector<std::string> temporaries(const fs::path& folder) {
  std::vector<std::string> found;
  for (const auto& f : fs::recursive_directory_iterator(folder))
    if (f.path().filename().string().find(".tmp-") != std::string::npos) found.push_back(f.path().string());
  return found;
}

TEST(BadInputTable, EveryRowExitsWithItsCodeOneLineAndWritesNothing) {
  const std::vector<Row> rows = readTable(OMNICAM_SOURCE_DIR "/docs/robustness.md");
  ASSERT_GE(rows.size(), 60u) << "the table in docs/robustness.md was not found or lost rows";
  const fs::path work = fs::temp_directory_path() / ("omnicam_bad_inputs_" + std::to_string(::getpid()));
  fs::remove_all(work);
  const fs::path inputs = work / "inputs", outputs = work / "out";
  fs::create_directories(outputs);
  fs::copy(OMNICAM_SOURCE_DIR "/tests/bad_inputs", inputs, fs::copy_options::recursive | fs::copy_options::copy_symlinks);
  const auto substitute = [&](std::string text) {
    text = replaceAll(text, "{R}", OMNICAM_SOURCE_DIR "/scenes");
    text = replaceAll(text, "{S}", (inputs / "scenes").string());
    text = replaceAll(text, "{I}", inputs.string());
    return replaceAll(text, "{O}", outputs.string());
  };
  int number = 0;
  for (const Row& row : rows) {
    EXPECT_EQ(row.number, ++number) << "rows are numbered 1, 2, 3, ...";
    const std::string command = std::regex_replace(substitute(row.command), std::regex(R"((^|; )omnicam )"),
                                                   "$1" + std::string(OMNICAM_BINARY) + " ");
    const auto [code, out] = shell(command);
    SCOPED_TRACE("row " + std::to_string(row.number) + ": " + command + "\n" + out);
    EXPECT_EQ(code, row.exitCode);
    EXPECT_NE(out.find(substitute(row.fragment)), std::string::npos) << "expected: " << substitute(row.fragment);
    EXPECT_TRUE(isOneLine(out)) << "one line, no control characters";
    EXPECT_TRUE(fs::is_empty(outputs)) << "wrote something";
    EXPECT_TRUE(temporaries(inputs).empty()) << "left a temporary file";
    fs::remove_all(outputs);
    fs::create_directories(outputs);
  }
  fs::remove_all(work);
}

}  // namespace
}  // namespace omnicam
