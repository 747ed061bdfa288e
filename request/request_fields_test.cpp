// The request's settings as rows (issue #47): every row complete, each name used once per front,
// and the docs' table the rows' own (docs/render-settings.md).
#include "request_fields.h"

#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>

#include "render_request.h"

namespace omnicam {
namespace {

TEST(RequestFields, EveryRowIsCompleteAndEachNameIsUsedOncePerFront) {
  std::set<std::string> cli, json, python;
  for (const RequestFieldRow& row : requestFieldRows()) {
    ASSERT_NE(row.python, nullptr) << "every setting has the library's (Python's) name";
    EXPECT_NE(row.shown, nullptr) << row.python;
    EXPECT_FALSE(row.help.empty()) << row.python;
    EXPECT_FALSE(row.range.empty()) << row.python;
    EXPECT_EQ(&requestFieldRow(row.field), &row) << row.python << ": one row per setting";
    EXPECT_TRUE(python.insert(row.python).second) << row.python;
    if (row.cli) {
      EXPECT_TRUE(cli.insert(row.cli).second) << row.cli;
      EXPECT_NE(row.cliGroup, 0u) << row.cli << ": a flag no verb registers";
      if (row.type == RequestFieldType::Number) {
        EXPECT_GT(row.cliNumberMax, 0.0) << row.cli;
      }
    }
    if (row.json) {
      EXPECT_TRUE(json.insert(row.json).second) << row.json;
    }
  }
  EXPECT_EQ(python.size(), 15u);
}

TEST(RequestFields, DefaultsAreTheRequestsOwn) {
  EXPECT_EQ(requestFieldRow(RequestField::Spp).defaultText(), "1");
  EXPECT_EQ(requestFieldRow(RequestField::Shading).defaultText(), "unlit");
  EXPECT_EQ(requestFieldRow(RequestField::Bounces).defaultText(), std::to_string(kDefaultBounces));
  EXPECT_EQ(requestFieldRow(RequestField::Timeout).defaultText(), "600");
  EXPECT_EQ(requestFieldRow(RequestField::FaceSize).defaultText(), std::to_string(CubeMapOptions{}.faceSize));
  EXPECT_EQ(requestFieldRow(RequestField::Denoise).defaultText(), "off");
  // The sampling's defaults are declared once: the settings an engine reads are the request's.
  const RenderSettings settings = RenderRequest{}.settings(RigSpec{});
  EXPECT_EQ(settings.spp, RenderSampling{}.spp);
  EXPECT_EQ(settings.bounces, RenderSampling{}.bounces);
}

TEST(RequestFields, ValuesKeepTheRowsType) {
  RequestFields fields{{RequestField::Spp, int64_t{4}}, {RequestField::Shading, "path"}};
  EXPECT_EQ(fields.integer(RequestField::Spp), 4);
  EXPECT_EQ(fields.text(RequestField::Shading), "path");
  EXPECT_FALSE(fields.has(RequestField::Seed));
  EXPECT_THROW(fields.set(RequestField::Spp, 4.0), std::logic_error);
  EXPECT_THROW(fields.set(RequestField::Denoise, "yes"), std::logic_error);
  EXPECT_THROW((void)fields.number(RequestField::Spp), std::logic_error);
}

TEST(RequestFields, TheDocsTableIsTheRows) {
  const std::string file = OMNICAM_SOURCE_DIR "/docs/render-settings.md";
  std::ifstream in(file);
  ASSERT_TRUE(in) << file << ": missing";
  std::stringstream text;
  text << in.rdbuf();
  const std::string doc = text.str(), begin = "<!-- request-fields:begin -->\n", end = "<!-- request-fields:end -->";
  const size_t from = doc.find(begin), to = doc.find(end);
  ASSERT_TRUE(from != std::string::npos && to != std::string::npos && from < to) << file << ": no table between the markers";
  if (doc.substr(from + begin.size(), to - from - begin.size()) != requestFieldsMarkdown())
    ADD_FAILURE() << file << " is out of date: put this table between its markers:\n" << requestFieldsMarkdown();
}

}  // namespace
}  // namespace omnicam
