#include "rw/common/content_model.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace rw::common {
namespace {

using Names = std::vector<std::string>;

// The grasp description's model (xml/grasp-description.xsd, as Xerces prints it).
const char* const kGrasp = "(PreShape*,Closing,TauMax,ContactIK?)";

std::string explain(const char* model, const Names& children, std::size_t* at = nullptr) {
  const auto m = ContentModel::parse(model);
  EXPECT_TRUE(m.has_value()) << model;
  return m ? m->explain(children, "<P>", at) : "";
}

TEST(ContentModelTest, AcceptsWhatTheModelAllows) {
  const auto m = ContentModel::parse(kGrasp);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->names(), (Names{"PreShape", "Closing", "TauMax", "ContactIK"}));
  EXPECT_TRUE(m->accepts({"Closing", "TauMax"}));
  EXPECT_TRUE(m->accepts({"PreShape", "PreShape", "Closing", "TauMax", "ContactIK"}));
  EXPECT_FALSE(m->accepts({"PreShape", "Closing"}));
  EXPECT_FALSE(m->accepts({"Closing", "TauMax", "TauMax"}));
  EXPECT_EQ(m->firstRejected({"PreShape", "TauMax"}), 1U);
  EXPECT_EQ(m->firstRejected({"PreShape", "Closing"}), std::nullopt);
  EXPECT_EQ(m->allowedAfter({"PreShape"}), (Names{"PreShape", "Closing"}));
  EXPECT_EQ(m->allowedAfter({"Closing", "TauMax"}), (Names{"ContactIK"}));
  // Choices, nesting, '+' and blanks.
  const auto c = ContentModel::parse("( (A | B)+ , C? , (D , E)* )");
  ASSERT_TRUE(c);
  EXPECT_TRUE(c->accepts({"B", "A", "D", "E", "D", "E"}));
  EXPECT_TRUE(c->accepts({"A", "C"}));
  EXPECT_FALSE(c->accepts({}));
  EXPECT_FALSE(c->accepts({"A", "D"}));
  EXPECT_EQ(c->explain({"A", "C"}, "<P>"), "");
}

TEST(ContentModelTest, TextThatIsNotAModelIsRefused) {
  for (const char* bad : {"", "(", "(A,B", "(A,B|C)", "(A,,B)", "A)", "(A)?x", "(1A)", "(A)(B)"}) {
    EXPECT_FALSE(ContentModel::parse(bad).has_value()) << bad;
  }
  std::string deep(200, '(');
  deep += "A" + std::string(200, ')');
  EXPECT_FALSE(ContentModel::parse(deep).has_value());
  EXPECT_TRUE(ContentModel::parse("A").has_value());
}

// The case: <PreShape> then <TauMax>, without the required <Closing> between them.
TEST(ContentModelTest, AMissingRequiredElementIsNamedWithTheOneItMustPrecede) {
  std::size_t at = 99;
  EXPECT_EQ(explain(kGrasp, {"PreShape", "TauMax", "ContactIK"}, &at),
            "missing <Closing> (required before <TauMax>)");
  EXPECT_EQ(at, 1U);
  EXPECT_EQ(explain(kGrasp, {"ContactIK"}, &at),
            "missing <Closing> and <TauMax> (required before <ContactIK>)");
  EXPECT_EQ(at, 0U);
}

TEST(ContentModelTest, MissingElementsAtTheEndAreNamed) {
  std::size_t at = 99;
  EXPECT_EQ(explain(kGrasp, {"PreShape"}, &at),
            "missing <Closing> and <TauMax> (required after <PreShape>)");
  EXPECT_EQ(at, 1U);
  EXPECT_EQ(explain(kGrasp, {}, &at), "missing <Closing> and <TauMax> (required in <P>)");
  EXPECT_EQ(at, 0U);
  EXPECT_EQ(explain("(A+)", {}), "missing <A> (required in <P>)");
  // Any of a choice would do: all are named.
  const char* object = "((Box|Cylinder|Mesh),Handle?,Appearance?)";
  EXPECT_EQ(explain(object, {}), "missing one of <Box>, <Cylinder> or <Mesh> (required in <P>)");
  EXPECT_EQ(explain(object, {"Appearance"}),
            "missing one of <Box>, <Cylinder> or <Mesh> (required before <Appearance>)");
}

TEST(ContentModelTest, ElementsOutOfOrderAreCalledSo) {
  std::size_t at = 99;
  // <TauMax> before <Closing>, which is given later.
  EXPECT_EQ(explain(kGrasp, {"PreShape", "TauMax", "Closing"}, &at),
            "<TauMax> is out of order: it must come after <Closing>");
  EXPECT_EQ(at, 1U);
  // A <PreShape> after <Closing>: it belongs before it.
  EXPECT_EQ(explain(kGrasp, {"PreShape", "Closing", "PreShape", "TauMax"}, &at),
            "<PreShape> is out of order: it must come before <Closing>");
  EXPECT_EQ(at, 2U);
}

TEST(ContentModelTest, AnElementGivenTwiceIsCalledSo) {
  std::size_t at = 99;
  EXPECT_EQ(explain(kGrasp, {"Closing", "TauMax", "TauMax"}, &at),
            "<TauMax> is given twice; <P> allows only one");
  EXPECT_EQ(at, 2U);
  EXPECT_EQ(explain(kGrasp, {"Closing", "Closing", "TauMax"}, &at),
            "<Closing> is given twice; <P> allows only one");
  EXPECT_EQ(at, 1U);
}

TEST(ContentModelTest, AnUnknownChildGetsADidYouMean) {
  std::size_t at = 99;
  EXPECT_EQ(explain(kGrasp, {"Closing", "TauMx"}, &at),
            "<TauMx> is not allowed in <P>; did you mean <TauMax>? (expected <TauMax> here)");
  EXPECT_EQ(at, 1U);
  EXPECT_EQ(explain(kGrasp, {"PreShape", "Banana"}),
            "<Banana> is not allowed in <P> (expected <PreShape> or <Closing> here)");
  EXPECT_EQ(explain("(A,B?)", {"A", "B", "Zzz"}),
            "<Zzz> is not allowed in <P> (no further element is allowed here)");
}

}  // namespace
}  // namespace rw::common
