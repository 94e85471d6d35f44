// BodyId and DeviceId: construction, none, ordering and text.
#include <gtest/gtest.h>

#include <sstream>
#include <type_traits>

#include "rwsim/dynamics/ids.hpp"

namespace {

using rwsim::dynamics::BodyId;
using rwsim::dynamics::DeviceId;

// Ids are not ints, and a body id is no device id.
static_assert(!std::is_convertible_v<int, BodyId>);
static_assert(!std::is_convertible_v<BodyId, std::size_t>);
static_assert(!std::is_convertible_v<BodyId, DeviceId>);
static_assert(!std::is_constructible_v<DeviceId, BodyId>);

TEST(Ids, DefaultIsNone) {
  EXPECT_FALSE(BodyId().valid());
  EXPECT_EQ(BodyId(), BodyId::none());
  EXPECT_FALSE(DeviceId::none().valid());
}

TEST(Ids, KeepTheirIndex) {
  const BodyId b(7);
  EXPECT_TRUE(b.valid());
  EXPECT_EQ(b.index(), 7u);
  EXPECT_TRUE(BodyId(0).valid());
  EXPECT_EQ(DeviceId(0).index(), 0u);
}

TEST(Ids, OrderByIndexWithNoneFirst) {
  EXPECT_LT(BodyId(2), BodyId(3));
  EXPECT_EQ(BodyId(3), BodyId(3));
  EXPECT_NE(BodyId(3), BodyId(4));
  EXPECT_LT(BodyId::none(), BodyId(0));
}

TEST(Ids, WriteTheIndexOrNone) {
  std::ostringstream out;
  out << BodyId(12) << ' ' << DeviceId::none();
  EXPECT_EQ(out.str(), "12 none");
  EXPECT_EQ(toString(DeviceId(3)), "3");
  EXPECT_EQ(toString(BodyId::none()), "none");
}

}  // namespace
