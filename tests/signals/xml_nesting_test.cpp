// The depth measure that guards the recursive XML parser: it counts elements as the parser
// nests them, skips what the parser skips, and names the line where a limit is passed.
#include "signals/xml_nesting.hpp"

#include <gtest/gtest.h>

#include <string>

namespace deepnav {
namespace {

TEST(XmlNesting, CountsStartAndEndTagsAndNamesTheLineOfTheFirstTooDeep) {
  EXPECT_EQ(line_nested_deeper_than("<a><b><c/></b></a>", 3), std::nullopt);
  EXPECT_EQ(line_nested_deeper_than("<a><b><c/></b></a>", 2), 1);
  EXPECT_EQ(line_nested_deeper_than("<a>\n<b>\n</b>\n<b>\n<c>\n</c></b></a>", 2), 5);
  // Siblings do not add up; end tags close whatever is open, as the parser takes them.
  std::string siblings = "<a>";
  for (int i = 0; i < 1000; ++i) siblings += "<b></b><c/>";
  EXPECT_EQ(line_nested_deeper_than(siblings + "</a>", 2), std::nullopt);
  std::string deep;
  for (int i = 0; i < 50000; ++i) deep += "<a>";
  EXPECT_EQ(line_nested_deeper_than(deep, 64), 1);
}

TEST(XmlNesting, SkipsWhatTheParserSkips) {
  // Tags inside comments, CDATA, processing instructions, a doctype's internal subset and
  // quoted attribute values are no elements.
  EXPECT_EQ(line_nested_deeper_than("<?xml version=\"1.0\"?><a><!-- <b><b><b> --></a>", 1), std::nullopt);
  EXPECT_EQ(line_nested_deeper_than("<a><![CDATA[<b><b><b>]]></a>", 1), std::nullopt);
  EXPECT_EQ(line_nested_deeper_than("<a><?pi <b><b> ?></a>", 1), std::nullopt);
  EXPECT_EQ(line_nested_deeper_than("<!DOCTYPE a [<!ELEMENT a (b)> <!ENTITY x \"<b>\">]><a/>", 1), std::nullopt);
  EXPECT_EQ(line_nested_deeper_than("<!other <b> ><a/>", 1), std::nullopt);
  EXPECT_EQ(line_nested_deeper_than("<a x=\"/>\" y='>'><b/></a>", 1), 1) << "the quoted '/>' does not close <a>";
  EXPECT_EQ(line_nested_deeper_than("<a x=\"/>\" y='>'><b/></a>", 2), std::nullopt);
  // The parser stops at a NUL byte; so does the count.
  EXPECT_EQ(line_nested_deeper_than(std::string("<a>\0<b><c>", 10), 1), std::nullopt);
  // Comments spanning lines are counted in the line numbers.
  EXPECT_EQ(line_nested_deeper_than("<a><!--\n\n--><b>", 1), 3);
}

}  // namespace
}  // namespace deepnav
