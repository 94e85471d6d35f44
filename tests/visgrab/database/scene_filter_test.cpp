#include "visgrab/database/scene_filter.hpp"

#include <gtest/gtest.h>

#include <string>

namespace visgrab::database {
namespace {

int countMatches(const SceneFilter& filter) {
  int n = 0;
  for (const SceneConditions& c : enumerateScenes()) {
    if (filter.matches(sceneIdOf(c), &c)) ++n;
  }
  return n;
}

std::string errorOf(const std::string& text) {
  try {
    SceneFilter::parse(text);
  } catch (const FilterError& e) {
    return e.what();
  }
  return "no error";
}

TEST(SceneFilterTest, ConditionWordsSelectThePapersGroups) {
  EXPECT_EQ(countMatches(SceneFilter::parse("")), 432);
  EXPECT_EQ(countMatches(SceneFilter::parse("all")), 432);
  EXPECT_EQ(countMatches(SceneFilter::parse("textured")), 216);
  EXPECT_EQ(countMatches(SceneFilter::parse("non-textured")), 216);
  EXPECT_EQ(countMatches(SceneFilter::parse("textured,single")), 144);
  EXPECT_EQ(countMatches(SceneFilter::parse("textured,single,standing")), 72);
  EXPECT_EQ(countMatches(SceneFilter::parse(" plain , lying ")), 72);
  EXPECT_EQ(countMatches(SceneFilter::parse("double,close")), 72);
  EXPECT_EQ(countMatches(SceneFilter::parse("textured,far")), 36);
  EXPECT_EQ(countMatches(SceneFilter::parse("pair=e")), 16);
  EXPECT_EQ(countMatches(SceneFilter::parse("pose=3")), 54);
  EXPECT_EQ(countMatches(SceneFilter::parse("kind=double,arrangement=touching")), 72);
}

TEST(SceneFilterTest, ObjectsAndNegation) {
  // Object 5: 8 single + 8 double scenes per texture.
  EXPECT_EQ(countMatches(SceneFilter::parse("object=5")), 32);
  EXPECT_EQ(countMatches(SceneFilter::parse("object=cocacola")), 32);
  EXPECT_EQ(countMatches(SceneFilter::parse("cocacola,single")), 16);
  EXPECT_EQ(countMatches(SceneFilter::parse("object=5,!double")), 16);
  EXPECT_EQ(countMatches(SceneFilter::parse("!textured")), 216);
}

TEST(SceneFilterTest, OrAndRepeatedOptions) {
  EXPECT_EQ(countMatches(SceneFilter::parse("textured,single,standing;pair=e,close")), 72 + 8);
  const auto repeated = SceneFilter::parse(std::vector<std::string>{"pair=a", "pair=b"});
  EXPECT_EQ(countMatches(repeated), 32);
  EXPECT_EQ(repeated.toString(), "pair=a;pair=b");
  EXPECT_TRUE(SceneFilter::parse(std::vector<std::string>{}).selectsAll());
  EXPECT_TRUE(SceneFilter::parse("single;all").selectsAll());
}

TEST(SceneFilterTest, IdGlobs) {
  EXPECT_EQ(countMatches(SceneFilter::parse("id=textured/single/cocacola/03")), 1);
  EXPECT_EQ(countMatches(SceneFilter::parse("textured/single/*")), 144);
  EXPECT_EQ(countMatches(SceneFilter::parse("*/cocacola*/0?")), 32);
  EXPECT_EQ(countMatches(SceneFilter::parse("id=*_*")), 144);
  EXPECT_TRUE(globMatch("a*b?c", "aXXbYc"));
  EXPECT_FALSE(globMatch("a*b?c", "aXXbc"));
  EXPECT_TRUE(globMatch("*", ""));
}

TEST(SceneFilterTest, ScenesWithoutConditionsMatchOnlyIdTerms) {
  const auto textured = SceneFilter::parse("textured");
  EXPECT_FALSE(textured.matches("bottle_flat_03", nullptr));
  EXPECT_TRUE(SceneFilter::parse("id=bottle_*").matches("bottle_flat_03", nullptr));
  EXPECT_TRUE(SceneFilter::parse("!textured").matches("bottle_flat_03", nullptr));
}

TEST(SceneFilterTest, CanonicalSpelling) {
  EXPECT_EQ(SceneFilter::parse("non-textured,laying;object=cocacola,!far").toString(),
            "plain,lying;object=5,!apart");
}

TEST(SceneFilterTest, ErrorsNameTheWordAndWhatWasExpected) {
  EXPECT_EQ(errorOf("textured,standign"),
            "scene filter \"textured,standign\": unknown word \"standign\" (did you mean "
            "\"standing\"?); expected plain, textured, single, double, standing, lying, apart, "
            "close, an object name, all, an id glob (with / * ?) or KEY=VALUE with KEY one of "
            "texture, kind, arrangement, object, pair, pose, id");
  EXPECT_EQ(errorOf("object=19"),
            "scene filter \"object=19\": bad value \"19\" for object=; expected an object id "
            "1..18 or an object name");
  EXPECT_EQ(errorOf("pair=j"),
            "scene filter \"pair=j\": bad value \"j\" for pair=; expected a pair letter a..i");
  EXPECT_EQ(errorOf("pose=0"),
            "scene filter \"pose=0\": bad value \"0\" for pose=; expected a pose index 1..8");
  EXPECT_EQ(errorOf("colour=red"),
            "scene filter \"colour=red\": unknown key \"colour\"; expected texture, kind, "
            "arrangement, object, pair, pose or id");
  EXPECT_EQ(errorOf("textured,,single"),
            "scene filter \"textured,,single\": empty term (two separators in a row, or one at "
            "an end)");
  EXPECT_EQ(errorOf("single;"),
            "scene filter \"single;\": empty term (two separators in a row, "
            "or one at an end)");
  EXPECT_EQ(errorOf("!"), "scene filter \"!\": '!' must be followed by a term");
  EXPECT_EQ(errorOf("texture=wood"),
            "scene filter \"texture=wood\": bad value \"wood\" for texture=; expected plain or "
            "textured");
  EXPECT_EQ(errorOf("id="),
            "scene filter \"id=\": bad value \"\" for id=; expected a scene id or glob");
}

// A database of your own objects: names, ids and pair letters are its catalog's.
TEST(SceneFilter, NamesIdsAndPairsOfAnotherCatalog) {
  const ObjectCatalog mine =
      ObjectCatalog::make({{101, "mug"}, {102, "jam"}, {5, "tin"}}, {{101, 102}});
  const auto mug = SceneConditions::single(Texture::kPlain, 101, 2);
  const auto tin = SceneConditions::single(Texture::kTextured, 5, 6);
  SceneConditions pair = SceneConditions::single(Texture::kPlain, 101, 5);
  pair.kind = SceneKind::kDouble;
  pair.objects = {101, 102};
  const auto matches = [&](std::string_view text, const SceneConditions& c) {
    return SceneFilter::parse(text, mine).matches(sceneIdOf(c, mine), &c);
  };
  EXPECT_TRUE(matches("mug", mug));
  EXPECT_TRUE(matches("mug", pair));
  EXPECT_FALSE(matches("mug", tin));
  EXPECT_TRUE(matches("object=102", pair));
  EXPECT_TRUE(matches("object=tin,lying", tin));  // id 5 is this catalog's tin, not cocacola
  EXPECT_TRUE(matches("pair=a", pair));
  EXPECT_FALSE(matches("pair=a", mug));
  EXPECT_TRUE(matches("!jam", tin));
  const auto errorOf = [&](std::string_view text) {
    try {
      SceneFilter::parse(text, mine);
    } catch (const FilterError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  // The benchmark's names and letters are not this database's.
  EXPECT_NE(errorOf("cocacola").find("unknown word \"cocacola\""), std::string::npos);
  EXPECT_EQ(errorOf("object=7"),
            "scene filter \"object=7\": bad value \"7\" for object=; expected an object id or "
            "name of this database's objects");
  EXPECT_EQ(errorOf("pair=b"),
            "scene filter \"pair=b\": bad value \"b\" for pair=; expected a pair letter a..a");
  // The benchmark's catalog gives the same filter as parse() without one.
  const auto cola = SceneConditions::single(Texture::kPlain, 5, 1);
  EXPECT_TRUE(SceneFilter::parse("cocacola,pair=e;object=5", ObjectCatalog::benchmark())
                  .matches(sceneIdOf(cola), &cola));
}

}  // namespace
}  // namespace visgrab::database
