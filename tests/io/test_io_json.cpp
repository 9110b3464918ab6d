// io: JSON writer for summary.json.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>

#include "particula/io/json.hpp"

using namespace particula::io;

TEST(Json, SummaryLayoutKeepsInsertionOrder) {
  JsonObject inner;
  inner.set("threads", 4).set("backend", "cpu");
  JsonObject j;
  j.set("particles", std::size_t{12000})
      .set("wall_seconds", 1.5)
      .set("status", std::string("ok"))
      .set("converged", true)
      .set("run", inner)
      .set("drag", std::vector<double>{1.0, 0.5});
  EXPECT_EQ(j.dump(),
            "{\n"
            "  \"particles\": 12000,\n"
            "  \"wall_seconds\": 1.5,\n"
            "  \"status\": \"ok\",\n"
            "  \"converged\": true,\n"
            "  \"run\": {\n"
            "    \"threads\": 4,\n"
            "    \"backend\": \"cpu\"\n"
            "  },\n"
            "  \"drag\": [1, 0.5]\n"
            "}");
  EXPECT_EQ(inner.dump(0), R"({"threads": 4,"backend": "cpu"})");
  EXPECT_EQ(JsonObject().dump(), "{}");
}

TEST(Json, SettingAKeyAgainReplacesItInPlace) {
  JsonObject j;
  j.set("a", 1).set("b", 2).set("a", 3.25);
  EXPECT_EQ(j.size(), 2u);
  EXPECT_EQ(j.dump(0), R"({"a": 3.25,"b": 2})");
}

TEST(Json, NonFiniteNumbersBecomeNull) {
  JsonObject j;
  j.set("nan", std::numeric_limits<double>::quiet_NaN())
      .set("inf", -std::numeric_limits<double>::infinity())
      .set("list", std::vector<double>{1.0, std::nan("")});
  EXPECT_EQ(j.dump(0), R"({"nan": null,"inf": null,"list": [1, null]})");
  EXPECT_TRUE(std::isnan(json_number_field(j.dump(), "nan")));
}

TEST(Json, StringsAreEscaped) {
  JsonObject j;
  j.set("path \"x\"", "C:\\runs\n\ttab\x01 \xc3\xa9");
  EXPECT_EQ(j.dump(0), "{\"path \\\"x\\\"\": \"C:\\\\runs\\n\\ttab\\u0001 \xc3\xa9\"}");
}

TEST(Json, DoublesRoundTripThroughTheText) {
  const double values[] = {1.0 / 3.0, 1e-300, 12345678.9, 6.02214076e23, -0.0};
  const std::string keys[] = {"v0", "v1", "v2", "v3", "v4"};
  JsonObject j;
  for (int i = 0; i < 5; ++i) j.set(keys[i], values[i]);
  j.set("big", std::int64_t{1} << 60);
  const std::string text = j.dump();
  for (int i = 0; i < 5; ++i) {
    const double back = json_number_field(text, keys[i]);
    EXPECT_EQ(std::signbit(back), std::signbit(values[i]));
    EXPECT_EQ(back, values[i]) << i;
  }
  EXPECT_EQ(json_number_field(text, "big"), std::ldexp(1.0, 60));
}

TEST(Json, NumberFieldFindsKeysNotValues) {
  const std::string text = R"({"name": "steps", "steps": 42, "nested": {"x": -1.5e-3}})";
  EXPECT_EQ(json_number_field(text, "steps"), 42.0);
  EXPECT_EQ(json_number_field(text, "x"), -1.5e-3);
  EXPECT_THROW(json_number_field(text, "missing"), std::runtime_error);
  EXPECT_THROW(json_number_field(text, "name"), std::runtime_error);
}

TEST(Json, ListsOfStringsObjectsAndRawValues) {
  JsonObject a, b;
  a.set("name", "cylinder");
  b.set("name", "wall \"0\"");
  JsonObject j;
  j.set("required", std::vector<std::string>{"d0", "c"})
      .set("default", JsonRaw{"[false, true]"})
      .set("bodies", std::vector<JsonObject>{a, b})
      .set("none", std::vector<JsonObject>{});
  EXPECT_EQ(j.dump(),
            "{\n"
            "  \"required\": [\"d0\", \"c\"],\n"
            "  \"default\": [false, true],\n"
            "  \"bodies\": [\n"
            "    {\n"
            "      \"name\": \"cylinder\"\n"
            "    },\n"
            "    {\n"
            "      \"name\": \"wall \\\"0\\\"\"\n"
            "    }\n"
            "  ],\n"
            "  \"none\": []\n"
            "}");
  EXPECT_EQ(j.dump(0), R"({"required": ["d0", "c"],"default": [false, true],"bodies": [{"name": "cylinder"},)"
                       R"({"name": "wall \"0\""}],"none": []})");
}

TEST(Json, NumbersAreShortestAndExact) {
  EXPECT_EQ(json_number(0.35), "0.35");
  EXPECT_EQ(json_number(7 * 0.05), "0.35000000000000003");
  EXPECT_EQ(json_number(2.0), "2");
  EXPECT_EQ(json_number(std::numeric_limits<double>::quiet_NaN()), "null");
}
