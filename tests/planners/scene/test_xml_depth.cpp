// The XML nesting bound checked before urdfdom and assimp parse a file:
// depths and lines on hand-made text, the markup the scan must skip, and
// the error for a file nested past the limit.
#include <gtest/gtest.h>

#include <string>

#include "scene_detail.h"
#include "scene_test_util.h"

namespace mddual::scene::detail {
namespace {

using testing::expectSceneError;
using testing::TempDir;

/// `depth` nested <a> elements, each start tag on its own line.
std::string nested(int depth) {
  std::string s;
  for (int i = 0; i < depth; ++i) s += "<a>\n";
  for (int i = 0; i < depth; ++i) s += "</a>";
  return s;
}

TEST(XmlDepth, CountsNestingAndTheLineThatReachedIt) {
  EXPECT_EQ(xmlElementDepth("").depth, 0);
  EXPECT_EQ(xmlElementDepth("just text").depth, 0);
  const XmlDepth one = xmlElementDepth("<robot name='r'></robot>");
  EXPECT_EQ(one.depth, 1);
  EXPECT_EQ(one.line, 1);
  const XmlDepth three = xmlElementDepth("<r>\n<l>\n<c/>\n<c><g>\n</g></c></l><l></l></r>");
  EXPECT_EQ(three.depth, 4);  // r > l > c > g; the self-closing <c/> adds none
  EXPECT_EQ(three.line, 4);
  EXPECT_EQ(xmlElementDepth(nested(10)).depth, 10);
  EXPECT_EQ(xmlElementDepth(nested(10)).line, 10);
}

TEST(XmlDepth, SkipsCommentsCdataDeclarationsAndQuotedValues) {
  const std::string deep_in_markup = nested(1000);
  const std::string text = "<?xml version=\"1.0\"?>\n<!DOCTYPE robot [ <!ENTITY e \"<a><a>\"> ]>\n<!-- " +
                           deep_in_markup + " -->\n<robot name=\"a > b\" note='<a><a><a>'>\n<![CDATA[" +
                           deep_in_markup + "]]>\n<?pi <a><a> ?>\n<link/>\n</robot>";
  const XmlDepth found = xmlElementDepth(text);
  EXPECT_EQ(found.depth, 1);
  EXPECT_EQ(found.line, 4 + 1000);  // the comment's 1000 lines are counted
}

TEST(XmlDepth, StopsPastTheLimitAndToleratesMalformedText) {
  const XmlDepth found = xmlElementDepth(nested(50000), 256);
  EXPECT_EQ(found.depth, 257);
  EXPECT_EQ(found.line, 257);
  // Unbalanced and unterminated markup: no crash, a depth that can be checked.
  EXPECT_EQ(xmlElementDepth("</a></a><b><c").depth, 2);
  EXPECT_EQ(xmlElementDepth("<!-- never closed <a><a>").depth, 0);
  EXPECT_EQ(xmlElementDepth("<a x='unterminated>").depth, 1);  // a start tag to the end of the text
}

TEST(XmlDepth, FileNestedPastTheLimitIsAnError) {
  TempDir dir;
  EXPECT_NO_THROW(requireShallowXml(dir.write("ok.xml", nested(kMaxXmlElementDepth))));
  const auto deep = dir.write("deep.xml", nested(kMaxXmlElementDepth + 1));
  expectSceneError([&] { requireShallowXml(deep); },
                   {"deep.xml:" + std::to_string(kMaxXmlElementDepth + 1) + ": XML elements nested more than " +
                    std::to_string(kMaxXmlElementDepth) + " deep"});
}

TEST(XmlDepth, OnlyColladaIsAnXmlMesh) {
  EXPECT_TRUE(isXmlMesh("a/robot.dae"));
  EXPECT_TRUE(isXmlMesh("ROBOT.DAE"));
  EXPECT_FALSE(isXmlMesh("robot.stl"));
  EXPECT_FALSE(isXmlMesh("robot.urdf"));
}

}  // namespace
}  // namespace mddual::scene::detail
