// Frame-name patterns of proximity rules: wildcards are literal except * and ?, REGEX is raw.
#include "rw/proximity/name_pattern.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace rw::proximity {
namespace {

TEST(NamePattern, WildcardSyntax) {
  EXPECT_TRUE(NamePattern("a.b").matches("a.b"));
  EXPECT_FALSE(NamePattern("a.b").matches("axb"));
  EXPECT_TRUE(NamePattern("REGEXa.b").matches("axb"));
  EXPECT_TRUE(NamePattern("*").matches(""));
  EXPECT_TRUE(NamePattern("Hand.*").matches("Hand.f1.Link2"));
  EXPECT_FALSE(NamePattern("Link?").matches("Link12"));
  EXPECT_TRUE(NamePattern("f(1)+[x]^$|{2}\\").matches("f(1)+[x]^$|{2}\\"));
  EXPECT_FALSE(NamePattern("Base").matches("BaseX"));
}

TEST(NamePattern, BadRegexNamesThePattern) {
  try {
    NamePattern pattern("REGEX(unclosed");
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("REGEX(unclosed"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rw::proximity
