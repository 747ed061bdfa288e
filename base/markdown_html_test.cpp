#include "markdown_html.h"

#include <gtest/gtest.h>

namespace omnicam {
namespace {

TEST(HtmlFromMarkdown, HeadingsParagraphsAndInlineSpans) {
  EXPECT_EQ(htmlFromMarkdown("### A **b** c\n\nOne line\nand the next, `x < y`.\n"),
            "<h3>A <strong>b</strong> c</h3>\n<p>One line and the next, <code>x &lt; y</code>.</p>\n");
  EXPECT_EQ(htmlFromMarkdown("an unpaired ** and ` stay\n"), "<p>an unpaired ** and ` stay</p>\n");
}

TEST(HtmlFromMarkdown, APipeTableDropsItsSeparatorRow) {
  EXPECT_EQ(htmlFromMarkdown("| a | **b** |\n|---|---:|\n| 1 |  |\n| <x> | 2 |\nafter\n"),
            "<table>\n<tr><th>a</th><th><strong>b</strong></th></tr>\n<tr><td>1</td><td></td></tr>\n"
            "<tr><td>&lt;x&gt;</td><td>2</td></tr>\n</table>\n<p>after</p>\n");
}

TEST(HtmlFromMarkdown, ListsAndImagesAndEscapedUserText) {
  EXPECT_EQ(htmlFromMarkdown("- one\n- two & \"three\"\n\n![a \"strip\"](figures/x.png)\n"),
            "<ul>\n<li>one</li>\n<li>two &amp; &quot;three&quot;</li>\n</ul>\n"
            "<p><img src=\"figures/x.png\" alt=\"a &quot;strip&quot;\" style=\"max-width:100%\"></p>\n");
  // Numbered items, each a line (the report's findings), numbered by the list; a number without
  // ". " after it is text.
  EXPECT_EQ(htmlFromMarkdown("1. In the **plain** hall\n2. Classifiers\n\n2008 was the year.\n"),
            "<ol>\n<li>In the <strong>plain</strong> hall</li>\n<li>Classifiers</li>\n</ol>\n<p>2008 was the year.</p>\n");
  // Markup in the text is shown, never interpreted.
  EXPECT_EQ(htmlFromMarkdown("<script>alert(1)</script>"), "<p>&lt;script&gt;alert(1)&lt;/script&gt;</p>\n");
}

TEST(HtmlFromMarkdown, WhatIsNotAWholeImageLineIsText) {
  EXPECT_EQ(htmlFromMarkdown("![not an image\nx\n![a](b.png) trailing\n![a](javascript:x)\n"),
            "<p>![not an image x ![a](b.png) trailing ![a](javascript:x)</p>\n");
  EXPECT_EQ(htmlFromMarkdown("text\n![a](b.png)\n"), "<p>text</p>\n<p><img src=\"b.png\" alt=\"a\" style=\"max-width:100%\"></p>\n");
  EXPECT_EQ(htmlFromMarkdown("![a](fig<1>.png)"), "<p><img src=\"fig&lt;1&gt;.png\" alt=\"a\" style=\"max-width:100%\"></p>\n");
}

TEST(HtmlFromMarkdown, WindowsLineEndsEmptyCellsAndBareHeadings) {
  EXPECT_EQ(htmlFromMarkdown("| a ||\r\n|---|---|\r\n| 1 | 2 |\r\none\r\ntwo\r\n"),
            "<table>\n<tr><th>a</th><th></th></tr>\n<tr><td>1</td><td>2</td></tr>\n</table>\n<p>one two</p>\n");
  EXPECT_EQ(htmlFromMarkdown("#\n"), "<h1></h1>\n");
  EXPECT_EQ(htmlFromMarkdown(""), "");
}

}  // namespace
}  // namespace omnicam
