// The shared attribute and text readers: values read, and the exact message (file:line:col,
// element, attribute, what was expected) for each kind of bad input.
#include <gtest/gtest.h>

#include <array>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rw/common/diagnostic_sink.hpp"
#include "rw/common/xml_attributes.hpp"
#include "rw/common/xml_reader.hpp"
#include "rw/common/xml_tree.hpp"

namespace {

using rw::common::AttributeRule;
using rw::common::DiagnosticSink;
using rw::common::ValueKind;
using rw::common::XmlElement;
using rw::common::XmlValueReader;

// The one element of `xml`, parsed as file "in.xml" (so that positions are real).
XmlElement parseOne(std::string_view xml) {
  DiagnosticSink sink;
  rw::common::XmlReader reader(rw::common::XmlReaderOptions{});
  auto file = std::make_shared<const rw::common::SourceFile>(rw::common::SourceFile{"in.xml", {}});
  auto top = reader.parse(xml, file, sink);
  EXPECT_FALSE(sink.hasErrors());
  EXPECT_TRUE(top && top->size() == 1);
  return top && !top->empty() ? (*top)[0] : XmlElement{};
}

// The single diagnostic of `sink`, formatted; "" if there is not exactly one.
std::string onlyMessage(const DiagnosticSink& sink) {
  if (sink.diagnostics().size() != 1) return "";
  return sink.diagnostics()[0].format();
}

TEST(ParseInteger, ReadsWholeNumbersInRange) {
  EXPECT_EQ(rw::common::parseInteger(" 42 ").value, 42);
  EXPECT_EQ(rw::common::parseInteger("+7").value, 7);
  EXPECT_EQ(rw::common::parseInteger("-3").value, -3);
  EXPECT_TRUE(rw::common::parseInteger("5", 1, 5).error.empty());
}

TEST(ParseInteger, NamesTheExpectedRange) {
  EXPECT_EQ(rw::common::parseInteger("1.5", 1).error, "expected a positive integer, got \"1.5\"");
  EXPECT_EQ(rw::common::parseInteger("-1", 0).error, "expected a non-negative integer, got \"-1\"");
  EXPECT_EQ(rw::common::parseInteger("x").error, "expected an integer, got \"x\"");
  EXPECT_EQ(rw::common::parseInteger("9", 1, 8).error,
            "expected an integer from 1 to 8, got \"9\"");
  EXPECT_EQ(rw::common::parseInteger("+-5").error, "expected an integer, got \"+-5\"");
  EXPECT_EQ(rw::common::parseInteger("").error, "expected an integer, got \"\"");
  EXPECT_EQ(rw::common::parseInteger("99999999999999999999").error,
            "expected an integer, got \"99999999999999999999\"");
}

TEST(ParseNumbers, ChecksTokensThenCount) {
  std::vector<double> v;
  EXPECT_EQ(rw::common::parseNumbers(" 1 2\n3 ", 3, "x y z", v), "");
  EXPECT_EQ(v, (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(rw::common::parseNumbers("1 2", 3, "x y z", v), "expected 3 numbers (x y z), got 2");
  EXPECT_EQ(rw::common::parseNumbers("1 2", 3, "", v), "expected 3 numbers, got 2");
  EXPECT_EQ(rw::common::parseNumbers("1 nan", 2, "", v), "\"nan\" is not a finite number");
  EXPECT_EQ(rw::common::parseNumbers("1 2 3 4", 0, "", v), "");
  EXPECT_EQ(v.size(), 4u);
}

TEST(ParseBoolean, AcceptsTheXsdSpellingsOnly) {
  EXPECT_EQ(rw::common::parseBoolean(" true"), true);
  EXPECT_EQ(rw::common::parseBoolean("1"), true);
  EXPECT_EQ(rw::common::parseBoolean("false "), false);
  EXPECT_EQ(rw::common::parseBoolean("0"), false);
  EXPECT_FALSE(rw::common::parseBoolean("yes").has_value());
  EXPECT_FALSE(rw::common::parseBoolean("True").has_value());
}

TEST(Choices, FindAndList) {
  constexpr std::array<std::string_view, 3> kNames{"a", "b", "c"};
  EXPECT_EQ(rw::common::findChoice("b", kNames), 1u);
  EXPECT_FALSE(rw::common::findChoice("d", kNames).has_value());
  EXPECT_EQ(rw::common::listChoices(kNames), "\"a\", \"b\" or \"c\"");
  EXPECT_EQ(rw::common::listChoices(std::span(kNames).first(1)), "\"a\"");
}

TEST(ExplainAttributeValues, NamesTheFirstBadAttributeInDocumentOrder) {
  constexpr std::array<std::string_view, 2> kSwitch{"Enabled", "Disabled"};
  const std::array<AttributeRule, 5> rules{{
      {"x", ValueKind::kNumber},
      {"rgb", ValueKind::kNumbers, 3, "red green blue"},
      {"id", ValueKind::kInteger, 0, {}, 1},
      {"daf", ValueKind::kBoolean},
      {"colmodel", ValueKind::kChoice, 0, {}, 0, 0, kSwitch},
  }};
  EXPECT_EQ(
      rw::common::explainAttributeValues(parseOne("<E x=\"1\" rgb=\"0 0 1\" id=\"3\"/>"), rules),
      "");
  EXPECT_EQ(
      rw::common::explainAttributeValues(parseOne("<E other=\"a\" x=\"b\" id=\"c\"/>"), rules),
      "attribute x: \"b\" is not a number");
  EXPECT_EQ(rw::common::explainAttributeValues(parseOne("<E rgb=\"1 1\"/>"), rules),
            "attribute rgb: expected 3 numbers (red green blue), got 2");
  EXPECT_EQ(rw::common::explainAttributeValues(parseOne("<E id=\"0\"/>"), rules),
            "attribute id: expected a positive integer, got \"0\"");
  EXPECT_EQ(rw::common::explainAttributeValues(parseOne("<E daf=\"maybe\"/>"), rules),
            "attribute daf: expected true or false, got \"maybe\"");
  EXPECT_EQ(rw::common::explainAttributeValues(parseOne("<E colmodel=\"Off\"/>"), rules),
            "attribute colmodel: expected \"Enabled\" or \"Disabled\", got \"Off\"");
}

TEST(XmlValueReader, ReadsGoodValues) {
  DiagnosticSink sink;
  const XmlValueReader read(sink);
  const XmlElement e = parseOne(
      "<Box name=\"b\" x=\"0.5\" v=\"1 2 3\" n=\"7\" on=\"true\" kind=\"two\">4 5 6</Box>");
  constexpr std::array<std::string_view, 2> kKinds{"one", "two"};
  EXPECT_EQ(read.number(e, "x"), 0.5);
  EXPECT_FALSE(read.optionalNumber(e, "absent").has_value());
  EXPECT_EQ(read.numbers(e, {"x", "n"}), (std::vector<double>{0.5, 7}));
  EXPECT_EQ(read.vector3(e, "v"), (std::array<double, 3>{1, 2, 3}));
  EXPECT_EQ(read.integer(e, "n", 1, 10), 7);
  EXPECT_EQ(read.optionalBoolean(e, "on"), true);
  EXPECT_EQ(read.choice(e, "kind", kKinds), 1u);
  EXPECT_EQ(read.textVector3(e), (std::array<double, 3>{4, 5, 6}));
  EXPECT_FALSE(read.optionalNumberList(e, "absent").has_value());
  EXPECT_TRUE(sink.diagnostics().empty());
}

// Each bad input gives one error at the element's file:line:col naming what was expected.
TEST(XmlValueReader, ReportsAtTheElement) {
  const std::string xml =
      "<Root>\n  <Box name=\"b\" x=\"abc\" v=\"1 2\" n=\"0\" on=\"yes\" "
      "kind=\"3\">x</Box>\n</Root>";
  const XmlElement box = parseOne(xml).children.at(0);
  constexpr std::array<std::string_view, 2> kKinds{"one", "two"};
  const std::string at = "in.xml:2:3: error: <Box name=\"b\">: ";
  struct Case {
    std::function<bool(const XmlValueReader&)> read;  // true if a value came back
    std::string message;
  };
  const std::vector<Case> cases{
      {[&](const XmlValueReader& r) { return r.number(box, "z").has_value(); },
       "missing required attribute \"z\""},
      {[&](const XmlValueReader& r) { return r.number(box, "x").has_value(); },
       "attribute x: \"abc\" is not a number"},
      {[&](const XmlValueReader& r) { return r.optionalNumber(box, "x").has_value(); },
       "attribute x: \"abc\" is not a number"},
      {[&](const XmlValueReader& r) { return r.vector3(box, "v", "x y z").has_value(); },
       "attribute v: expected 3 numbers (x y z), got 2"},
      {[&](const XmlValueReader& r) { return r.integer(box, "n", 1).has_value(); },
       "attribute n: expected a positive integer, got \"0\""},
      {[&](const XmlValueReader& r) { return r.optionalBoolean(box, "on").has_value(); },
       "attribute on: expected true or false, got \"yes\""},
      {[&](const XmlValueReader& r) { return r.choice(box, "kind", kKinds).has_value(); },
       "attribute kind: expected \"one\" or \"two\", got \"3\""},
      {[&](const XmlValueReader& r) { return r.choice(box, "kind", kKinds, "kind").has_value(); },
       "unknown kind \"3\"; expected \"one\" or \"two\""},
      {[&](const XmlValueReader& r) { return r.textNumber(box).has_value(); },
       "\"x\" is not a number"},
      {[&](const XmlValueReader& r) { return r.textBoolean(box).has_value(); },
       "expected true or false, got \"x\""},
      {[&](const XmlValueReader& r) {
         return r.numbers(box, {"x", "q"}).has_value();
       },
       ""},
  };
  for (const Case& c : cases) {
    DiagnosticSink sink;
    const XmlValueReader read(sink);
    EXPECT_FALSE(c.read(read)) << c.message;
    if (c.message.empty()) {
      // numbers(): both attributes are reported.
      ASSERT_EQ(sink.diagnostics().size(), 2u);
      EXPECT_EQ(sink.diagnostics()[0].format(), at + "attribute x: \"abc\" is not a number");
      EXPECT_EQ(sink.diagnostics()[1].format(), at + "missing required attribute \"q\"");
    } else {
      EXPECT_EQ(onlyMessage(sink), at + c.message);
    }
  }
}

TEST(XmlValueReader, UsesTheParsersOwnDescription) {
  DiagnosticSink sink;
  const XmlValueReader read(sink, [](const XmlElement& e) { return "[" + e.name + "]"; });
  EXPECT_FALSE(read.textVector3(parseOne("<Gravity>0 0</Gravity>")).has_value());
  EXPECT_EQ(onlyMessage(sink), "in.xml:1:1: error: [Gravity]: expected 3 numbers, got 2");
}

}  // namespace
