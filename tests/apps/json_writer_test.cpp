// The JSON writer: layout, escaping, non-finite numbers as null, numbers that read back exact.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "json_writer.hpp"

namespace {

using visgrab::app::JsonWriter;

TEST(JsonWriter, WritesNestedObjectsAndArrays) {
  std::ostringstream out;
  JsonWriter j(out);
  j.beginObject().key("a").value(1).key("b").beginArray().value("x").value(true).null();
  j.endArray().key("c").beginObject().endObject().key("d").numbers({1.5, -2.0});
  j.key("e").beginArray().endArray().endObject().finish();
  EXPECT_EQ(out.str(),
            "{\n  \"a\": 1,\n  \"b\": [\n    \"x\",\n    true,\n    null\n  ],\n  \"c\": {},\n"
            "  \"d\": [1.5, -2],\n  \"e\": []\n}\n");
}

TEST(JsonWriter, EscapesQuotesBackslashesAndControlCharacters) {
  EXPECT_EQ(JsonWriter::quoted("a\"b\\c"), "\"a\\\"b\\\\c\"");
  EXPECT_EQ(JsonWriter::quoted("\n\r\t\b\f"), "\"\\n\\r\\t\\b\\f\"");
  EXPECT_EQ(JsonWriter::quoted(std::string("\x01\x1f", 2)), "\"\\u0001\\u001f\"");
  EXPECT_EQ(JsonWriter::quoted(std::string("nul\0x", 5)), "\"nul\\u0000x\"");
  // UTF-8 passes unchanged.
  EXPECT_EQ(JsonWriter::quoted("Gr\xc3\xbc\xc3\x9f"), "\"Gr\xc3\xbc\xc3\x9f\"");
}

TEST(JsonWriter, NonFiniteNumbersAreNull) {
  EXPECT_EQ(JsonWriter::number(std::numeric_limits<double>::quiet_NaN()), "null");
  EXPECT_EQ(JsonWriter::number(std::numeric_limits<double>::infinity()), "null");
  EXPECT_EQ(JsonWriter::number(-std::numeric_limits<double>::infinity()), "null");
  std::ostringstream out;
  JsonWriter j(out);
  j.numbers({0.25, std::nan("")});
  EXPECT_EQ(out.str(), "[0.25, null]");
}

TEST(JsonWriter, NumbersReadBackExactly) {
  for (const double v : {0.1, 1.0 / 3.0, -1e-300, 6.02214076e23, 0.017, 123456789.0}) {
    const std::string text = JsonWriter::number(v);
    EXPECT_EQ(std::strtod(text.c_str(), nullptr), v) << text;
  }
  EXPECT_EQ(JsonWriter::number(0.017), "0.017");
}

TEST(JsonWriter, MisuseIsAProgrammerError) {
  std::ostringstream out;
  JsonWriter j(out);
  j.beginObject();
  EXPECT_THROW(j.value(1), std::logic_error);  // a member without a key
  EXPECT_THROW(j.endArray(), std::logic_error);
  EXPECT_THROW(j.finish(), std::logic_error);  // unclosed
}

}  // namespace
