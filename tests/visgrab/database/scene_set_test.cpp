#include "visgrab/database/scene_set.hpp"

#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>

namespace visgrab::database {
namespace {

// The paper's definitions (§2.1, Table 3), written out independently of the enumerator.
const std::map<char, std::pair<int, int>> kPaperPairs = {
    {'a', {1, 18}}, {'b', {2, 11}}, {'c', {3, 7}},   {'d', {4, 15}}, {'e', {5, 14}},
    {'f', {6, 8}},  {'g', {9, 13}}, {'h', {10, 12}}, {'i', {16, 17}}};

TEST(SceneSetTest, ObjectNamesAreThePapersAlphabeticalList) {
  const char* names[] = {"amicelli", "breadbox", "burti",    "cleaningbottle", "cocacola",
                         "corny",    "denkmit",  "greencup", "icecoffee",      "marmelade",
                         "peachcan", "pure",     "saltbox",  "saltcylinder",   "sucker",
                         "tomato",   "waterjug", "whitecup"};
  for (int id = 1; id <= 18; ++id) {
    EXPECT_EQ(objectName(id), names[id - 1]);
    EXPECT_EQ(objectIdByName(names[id - 1]), id);
  }
  EXPECT_THROW(objectName(0), std::out_of_range);
  EXPECT_THROW(objectName(19), std::out_of_range);
  EXPECT_FALSE(objectIdByName("CocaCola"));
}

TEST(SceneSetTest, CountsPerConditionMatchThePaper) {
  // 2 textures x (18 objects x 8 poses + 9 pairs x 8 placements).
  const int paperTotal = 2 * (18 * 8 + 9 * 8);
  const auto scenes = enumerateScenes();
  ASSERT_EQ(static_cast<int>(scenes.size()), paperTotal);
  ASSERT_EQ(paperTotal, 432);

  std::map<Texture, int> perTexture;
  std::map<std::pair<Texture, Arrangement>, int> perArrangement;
  std::map<std::pair<Texture, SceneKind>, int> perKind;
  std::map<std::pair<Texture, int>, int> singlesPerObject;
  std::map<std::pair<Texture, char>, int> perPair;
  std::set<std::string> ids;
  for (const SceneConditions& c : scenes) {
    EXPECT_EQ(validate(c), "");
    ++perTexture[c.texture];
    ++perKind[{c.texture, c.kind}];
    ++perArrangement[{c.texture, c.arrangement()}];
    if (c.kind == SceneKind::kSingle) {
      ASSERT_EQ(c.objects.size(), 1u);
      ++singlesPerObject[{c.texture, c.objects[0]}];
      // Poses 1-4 standing, 5-8 lying.
      EXPECT_EQ(c.arrangement() == Arrangement::kStanding, c.pose <= 4);
    } else {
      ASSERT_EQ(c.objects.size(), 2u);
      bool found = false;
      for (const auto& [letter, members] : kPaperPairs) {
        if (members.first == c.objects[0] && members.second == c.objects[1]) {
          ++perPair[{c.texture, letter}];
          ASSERT_TRUE(c.pair());
          EXPECT_EQ(c.pair()->letter, letter);
          found = true;
        }
      }
      EXPECT_TRUE(found) << describe(c);
      EXPECT_EQ(c.arrangement() == Arrangement::kApart, c.pose <= 4);
    }
    EXPECT_TRUE(ids.insert(sceneIdOf(c)).second) << "duplicate " << sceneIdOf(c);
  }
  for (Texture t : {Texture::kPlain, Texture::kTextured}) {
    EXPECT_EQ(perTexture[t], 216);
    EXPECT_EQ((perKind[{t, SceneKind::kSingle}]), 144);
    EXPECT_EQ((perKind[{t, SceneKind::kDouble}]), 72);
    EXPECT_EQ((perArrangement[{t, Arrangement::kStanding}]), 72);
    EXPECT_EQ((perArrangement[{t, Arrangement::kLying}]), 72);
    EXPECT_EQ((perArrangement[{t, Arrangement::kApart}]), 36);
    EXPECT_EQ((perArrangement[{t, Arrangement::kClose}]), 36);
    for (int object = 1; object <= 18; ++object) {
      EXPECT_EQ((singlesPerObject[{t, object}]), 8) << object;
    }
    for (const auto& [letter, members] : kPaperPairs) {
      EXPECT_EQ((perPair[{t, letter}]), 8) << letter;
    }
  }
}

TEST(SceneSetTest, EveryObjectIsInExactlyOnePair) {
  std::map<int, int> count;
  for (const ObjectPair& p : kObjectPairs) {
    ++count[p.first];
    ++count[p.second];
    EXPECT_EQ(kPaperPairs.at(p.letter), std::make_pair(p.first, p.second));
  }
  EXPECT_EQ(count.size(), 18u);
  for (const auto& [object, n] : count) EXPECT_EQ(n, 1) << object;
}

TEST(SceneSetTest, IdsAndOriginalIdsRoundTripForAllScenes) {
  const auto scenes = enumerateScenes();
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    const SceneConditions& c = scenes[i];
    const std::string id = sceneIdOf(c);
    const std::string original = originalIdOf(c);
    EXPECT_EQ(parseSceneId(id), c) << id;
    EXPECT_EQ(parseOriginalId(original), c) << original;
    EXPECT_EQ(sceneIndex(c), static_cast<int>(i));
    // Both spellings name the same scene.
    EXPECT_EQ(sceneIdOf(*parseOriginalId(original)), id);
  }
}

TEST(SceneSetTest, IdSpellings) {
  const auto cola = SceneConditions::single(Texture::kTextured, 5, 3);
  EXPECT_EQ(sceneIdOf(cola), "textured/single/cocacola/03");
  EXPECT_EQ(originalIdOf(cola), "textured/cocacola/img_03");
  const auto pair = SceneConditions::pairScene(Texture::kPlain, 'e', 6);
  EXPECT_EQ(sceneIdOf(pair), "plain/double/cocacola_saltcylinder/06");
  EXPECT_EQ(originalIdOf(pair), "non-textured/cocacola_saltcylinder/img_06");
  EXPECT_EQ(describe(pair),
            "plain, double, close, pair e: 5 cocacola + 14 saltcylinder, placement 6");
  EXPECT_EQ(describe(cola), "textured, single, standing, object 5 cocacola, pose 3");
}

TEST(SceneSetTest, MalformedIdsAreRejected) {
  for (const char* bad :
       {"", "textured/single/cocacola/3", "textured/single/cocacola/09",
        "textured/single/cocacola/00", "textured/double/cocacola/03",
        "textured/single/cocacola_saltcylinder/03", "textured/double/saltcylinder_cocacola/03",
        "textured/double/cocacola_pure/03", "Textured/single/cocacola/03",
        "textured/single/cocacola/03/", "textured/single/pepsi/03", "textured/single/cocacola"}) {
    EXPECT_FALSE(parseSceneId(bad)) << bad;
  }
  for (const char* bad : {"textured/cocacola/03", "plain/cocacola/img_03",
                          "textured/cocacola/img_9", "non-textured/pure_marmelade/img_01"}) {
    EXPECT_FALSE(parseOriginalId(bad)) << bad;
  }
}

TEST(SceneSetTest, ValidateExplainsProblems) {
  EXPECT_NE(validate(SceneConditions::single(Texture::kPlain, 19, 1)).find("object id 19"),
            std::string::npos);
  EXPECT_NE(validate(SceneConditions::single(Texture::kPlain, 1, 9)).find("pose 9"),
            std::string::npos);
  SceneConditions wrongOrder{Texture::kPlain, SceneKind::kDouble, {14, 5}, 1};
  EXPECT_NE(validate(wrongOrder).find("order"), std::string::npos);
  SceneConditions notPair{Texture::kPlain, SceneKind::kDouble, {1, 2}, 1};
  EXPECT_NE(validate(notPair).find("not one of the pairs"), std::string::npos);
  EXPECT_THROW(sceneIdOf(notPair), std::invalid_argument);
  EXPECT_THROW(SceneConditions::pairScene(Texture::kPlain, 'j', 1), std::invalid_argument);
}

}  // namespace
}  // namespace visgrab::database
