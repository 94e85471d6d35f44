#include "rw/graspplanning/cm_dist_ccp.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "support/test_support.hpp"

namespace {

using rw::graspplanning::cmDistCcp;
using rw::graspplanning::Contact3D;
using rw::math::Vector3D;

Contact3D at(double x, double y, double z) {
  Contact3D c;
  c.position = Vector3D(x, y, z);
  return c;
}

TEST(CmDistCcp, WorkedByHand) {
  // Mean of (0.01, 0, 0) and (0.03, 0.02, 0) is (0.02, 0.01, 0); from cm (0, 0.01, 0) that is
  // d = 0.02, so with maxDist 0.1 the quality is (0.1 - 0.02) / 0.1 = 0.8.
  const std::vector<Contact3D> contacts = {at(0.01, 0, 0), at(0.03, 0.02, 0)};
  EXPECT_NEAR(cmDistCcp(contacts, Vector3D(0, 0.01, 0), 0.1), 0.8, 1e-12);
}

TEST(CmDistCcp, ContactCentroidAtCentreOfMassGivesOne) {
  const std::vector<Contact3D> contacts = {at(0.05, 0, 0), at(-0.025, 0.04, 0),
                                           at(-0.025, -0.04, 0)};
  EXPECT_DOUBLE_EQ(cmDistCcp(contacts, Vector3D::Zero(), 0.1), 1.0);
}

TEST(CmDistCcp, BeyondMaxDistGivesZero) {
  const std::vector<Contact3D> contacts = {at(0.3, 0, 0)};
  EXPECT_EQ(cmDistCcp(contacts, Vector3D::Zero(), 0.1), 0.0);
  // Exactly at maxDist: (maxDist - d) / maxDist = 0.
  EXPECT_EQ(cmDistCcp(contacts, Vector3D::Zero(), 0.3), 0.0);
}

TEST(CmDistCcp, DuplicatesCountAsInRobWork) {
  // (0, 0, 0) twice and (0.06, 0, 0): mean (0.02, 0, 0), d = 0.02, quality 0.8.
  const std::vector<Contact3D> contacts = {at(0, 0, 0), at(0, 0, 0), at(0.06, 0, 0)};
  EXPECT_NEAR(cmDistCcp(contacts, Vector3D::Zero(), 0.1), 0.8, 1e-12);
}

TEST(CmDistCcp, DegenerateInputGivesZero) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Contact3D> one = {at(0.01, 0, 0)};
  EXPECT_EQ(cmDistCcp({}, Vector3D::Zero(), 0.1), 0.0);
  EXPECT_EQ(cmDistCcp(one, Vector3D::Zero(), 0.0), 0.0);
  EXPECT_EQ(cmDistCcp(one, Vector3D::Zero(), -1.0), 0.0);
  EXPECT_EQ(cmDistCcp(one, Vector3D(nan, 0, 0), 0.1), 0.0);
  EXPECT_EQ(cmDistCcp(std::vector<Contact3D>{at(nan, 0, 0)}, Vector3D::Zero(), 0.1), 0.0);
}

}  // namespace
