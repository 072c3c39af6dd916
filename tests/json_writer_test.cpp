// The JSON writer lays a document out as nlohmann-json's dump() and dump(2) do, byte for byte,
// so the summaries, image descriptions and scene files it writes are those nlohmann-json wrote.

#include "core/io/json_writer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace rtiow {
namespace {

// The same document through the writer, in the layout of `indent`.
std::string written(int indent) {
  JsonWriter w(indent);
  w.begin_object();
  w.key("text").string("quote \" backslash \\ tab \t newline \n bell \x07 é");
  w.key("numbers").begin_array().number(13.0).number(0.1).number(1e-05).number(2.5e300);
  w.number(std::numeric_limits<double>::quiet_NaN()).number(-0.0).end();
  w.key("wholes").begin_array().whole(-7).whole(std::uint64_t(18446744073709551615ull)).end();
  w.key("flags").begin_array().boolean(true).boolean(false).null().end();
  w.key("empty object").begin_object().end();
  w.key("empty array").begin_array().end();
  w.key("nested").begin_object().key("a").begin_array().begin_object().key("b").whole(1);
  w.end().end().end();
  w.key("metadata")
      .begin_object()
      .members({{"n", std::int64_t(3)}, {"x", 0.25}, {"s", std::string("v")}});
  w.end();
  w.end();
  return w.text();
}

nlohmann::ordered_json expected() {
  nlohmann::ordered_json j;
  j["text"] = "quote \" backslash \\ tab \t newline \n bell \x07 é";
  j["numbers"] = {13.0, 0.1, 1e-05, 2.5e300, std::numeric_limits<double>::quiet_NaN(), -0.0};
  j["wholes"] = {-7, std::uint64_t(18446744073709551615ull)};
  j["flags"] = {true, false, nullptr};
  j["empty object"] = nlohmann::ordered_json::object();
  j["empty array"] = nlohmann::ordered_json::array();
  j["nested"] = {{"a", {{{"b", 1}}}}};
  j["metadata"] = {{"n", 3}, {"x", 0.25}, {"s", "v"}};
  return j;
}

TEST(JsonWriter, WritesWhatNlohmannJsonDumps) {
  EXPECT_EQ(written(-1), expected().dump());
  EXPECT_EQ(written(2), expected().dump(2));
  EXPECT_EQ(written(4), expected().dump(4));
  EXPECT_EQ(json_quoted("a\"b"), "\"a\\\"b\"");
  EXPECT_EQ(json_number(13.0), "13.0");
  // A file name in another encoding: its stray bytes as U+FFFD, not an exception.
  EXPECT_EQ(json_quoted("a\xff.png"), "\"a\xef\xbf\xbd.png\"");
}

TEST(JsonWriter, RefusesADocumentItCannotLayOut) {
  JsonWriter no_key;
  no_key.begin_object();
  EXPECT_THROW(no_key.whole(1), std::logic_error);  // an object's value needs its key
  JsonWriter key_in_array;
  key_in_array.begin_array();
  EXPECT_THROW(key_in_array.key("k"), std::logic_error);
  JsonWriter nothing_open;
  EXPECT_THROW(nothing_open.end(), std::logic_error);
  JsonWriter key_without_value;
  key_without_value.begin_object().key("k");
  EXPECT_THROW(key_without_value.end(), std::logic_error);
}

}  // namespace
}  // namespace rtiow
