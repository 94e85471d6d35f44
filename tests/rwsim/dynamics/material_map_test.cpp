// MaterialMap: declarations, symmetric friction and restitution, RobWork's defaults.
#include <gtest/gtest.h>

#include "rwsim/dynamics/material_map.hpp"

namespace {

using rwsim::dynamics::FrictionData;
using rwsim::dynamics::MaterialMap;

TEST(MaterialMap, DeclaresMaterialsOnceInOrder) {
  MaterialMap m;
  EXPECT_TRUE(m.addMaterial("Plastic"));
  EXPECT_TRUE(m.addMaterial("Rubber", "soft"));
  EXPECT_FALSE(m.addMaterial("Plastic"));
  EXPECT_EQ(m.materials(), (std::vector<std::string>{"Plastic", "Rubber"}));
  EXPECT_TRUE(m.hasMaterial("Rubber"));
  EXPECT_FALSE(m.hasMaterial("Steel"));
  EXPECT_TRUE(m.defaultMaterial().empty());
  m.setDefaultMaterial("Plastic");
  EXPECT_EQ(m.defaultMaterial(), "Plastic");
  EXPECT_TRUE(m.addObjectType("hardObj"));
  EXPECT_FALSE(m.addObjectType("hardObj"));
  EXPECT_TRUE(m.hasObjectType("hardObj"));
}

TEST(MaterialMap, FrictionIsSymmetricAndDefaultsToPointFour) {
  MaterialMap m;
  FrictionData data;
  data.parameters = {{"Mu", {0.7}}, {"Mud", {0.5}}};
  m.setFriction("Rubber", "Plastic", data);
  EXPECT_DOUBLE_EQ(m.mu("Plastic", "Rubber"), 0.7);
  EXPECT_DOUBLE_EQ(m.mu("Rubber", "Plastic"), 0.7);
  ASSERT_NE(m.friction("Plastic", "Rubber"), nullptr);
  EXPECT_EQ(m.friction("Plastic", "Rubber")->type, "Coulomb");
  EXPECT_EQ(m.friction("Plastic", "Plastic"), nullptr);
  EXPECT_DOUBLE_EQ(m.mu("Plastic", "Plastic"), MaterialMap::kDefaultMu);
  EXPECT_EQ(m.frictionPairCount(), 1u);
}

TEST(MaterialMap, MuIsTheFirstValueOfTheFirstParameterWhateverItsName) {
  FrictionData data;
  data.parameters = {{"Static", {0.9, 0.1}}, {"Mu", {0.2}}};
  EXPECT_DOUBLE_EQ(data.mu(), 0.9);
  data.parameters = {{"Mu", {}}};
  EXPECT_DOUBLE_EQ(data.mu(), MaterialMap::kDefaultMu);
  EXPECT_DOUBLE_EQ(FrictionData{}.mu(), MaterialMap::kDefaultMu);
}

TEST(MaterialMap, RestitutionIsSymmetricAndDefaultsToZero) {
  MaterialMap m;
  m.setRestitution("soft", "hard", 0.3);
  EXPECT_DOUBLE_EQ(m.restitution("hard", "soft"), 0.3);
  EXPECT_DOUBLE_EQ(m.restitution("hard", "hard"), 0.0);
}

}  // namespace
