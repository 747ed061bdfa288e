#include "markup.h"

#include <gtest/gtest.h>

namespace omnicam {
namespace {

// RFC 3986: a path keeps unreserved characters and '/'; '#' would start a fragment, '%' an escape
// and '?' a query, so a folder named "r#1 50%" must reach the browser as "r%231%2050%25".
TEST(UrlPath, PercentEncodesEverythingButUnreservedCharactersAndSlashes) {
  EXPECT_EQ(urlPath("report_files/000000_cam0_a.png"), "report_files/000000_cam0_a.png");
  EXPECT_EQ(urlPath("r#1 50%_files/a.png"), "r%231%2050%25_files/a.png");
  EXPECT_EQ(urlPath("a?b&c\"d'e<f>.png"), "a%3Fb%26c%22d%27e%3Cf%3E.png");
  EXPECT_EQ(urlPath("\xC3\xA9t\xC3\xA9~x"), "%C3%A9t%C3%A9~x");  // "été~x": UTF-8 bytes, each encoded
}

// A path pasted into a shell stays one word and is never taken for an option.
TEST(ShellPath, QuotesWhatTheShellWouldSplitAndGuardsALeadingDash) {
  EXPECT_EQ(shellPath("out/job"), "out/job");
  EXPECT_EQ(shellPath("my job"), "'my job'");
  EXPECT_EQ(shellPath("-o"), "./-o");
  EXPECT_EQ(shellPath("-a b"), "'./-a b'");
  EXPECT_EQ(shellPath("it's"), "'it'\\''s'");
}

}  // namespace
}  // namespace omnicam
