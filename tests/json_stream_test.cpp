// The streaming JSON reader under the scene parser: numbers read exactly as strtod reads
// them (RapidJSON's own full-precision reader has known misroundings), tokens and error
// positions right across buffer boundaries and short reads, and names interned densely.

#include "core/scene_file/json_stream.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "core/limits/error.h"
#include "core/scene_file/name_index.h"

namespace rtiow {
namespace {

// Parses `text` delivered in reads of at most `chunk` bytes.
void parse(const std::string& text, JsonDocument& root, std::size_t chunk = 1 << 20,
           const std::map<std::string, StreamedMember, std::less<>>& streamed = {}) {
  std::size_t offset = 0;
  JsonInput input(
      [&](char* buffer, std::size_t size) {
        const std::size_t n = std::min({size, chunk, text.size() - offset});
        std::memcpy(buffer, text.data() + offset, n);
        offset += n;
        return n;
      },
      std::uint64_t(1) << 32, "t.json");
  parse_json_stream(input, "t.json", streamed, root);
}

std::string error_of(const std::string& text, std::size_t chunk = 1 << 20) {
  try {
    JsonDocument root;
    parse(text, root, chunk);
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "accepted";
}

TEST(JsonStream, NumbersReadAsStrtodReadsThem) {
  std::vector<std::string> numbers = {
      // RapidJSON 1.1's kParseFullPrecisionFlag got these wrong (issues #340 and #2326).
      "2.220446049250313e-16",
      "7.450580596923828e-9",
      "0.184467440737095516159",
      "-122.39864863336066",
      "7e23",
      "4.9e-324",
      "2.2250738585072011e-308",
      "1.7976931348623157e308",
      "0.1",
      "1e-400",
      "-0.0",
      "123456789012345678901234567890"};
  std::mt19937_64 random(7);
  for (int i = 0; i < 2000; ++i) {
    double d = 0;
    do {
      d = std::bit_cast<double>(std::uint64_t(random()));
    } while (!std::isfinite(d));
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.17g", d);
    numbers.push_back(buffer);
    std::snprintf(buffer, sizeof buffer, "%.9g", float(random() % 100000) / 997.0f);
    numbers.push_back(buffer);
  }
  std::string text = "[";
  for (const std::string& n : numbers) text += (text.size() > 1 ? "," : "") + n;
  text += "]";
  JsonDocument root;
  parse(text, root);
  ASSERT_EQ(root.Size(), numbers.size());
  for (rapidjson::SizeType i = 0; i < root.Size(); ++i) {
    const double expected = std::strtod(numbers[i].c_str(), nullptr);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(root[i].GetDouble()),
              std::bit_cast<std::uint64_t>(expected))
        << numbers[i];
  }
}

TEST(JsonStream, WholeNumbersStayExactIntegers) {
  JsonDocument root;
  parse("[18446744073709551615, -9223372036854775808, 18446744073709551616, 0, -0]", root);
  EXPECT_TRUE(root[0].IsUint64());
  EXPECT_EQ(root[0].GetUint64(), 18446744073709551615u);
  EXPECT_TRUE(root[1].IsInt64());
  EXPECT_EQ(root[1].GetInt64(), std::numeric_limits<std::int64_t>::min());
  EXPECT_TRUE(root[2].IsDouble());  // beyond 64 bits: a double, as in JSON
  EXPECT_TRUE(root[3].IsUint64());
  EXPECT_TRUE(root[4].IsInt64());
}

TEST(JsonStream, TokensAcrossBufferBoundariesAndShortReads) {
  // A string and a number placed across the 64 KiB buffer boundary at every offset nearby,
  // delivered whole and one byte per read.
  for (std::size_t pad = 65500; pad < 65560; pad += 3) {
    const std::string text = "{\"a\":" + std::string(pad, ' ') + "\"abcdefghij\", \"b\": 1.25e3}";
    for (std::size_t chunk : {std::size_t(1) << 20, std::size_t(1), std::size_t(4093)}) {
      JsonDocument root;
      parse(text, root, chunk);
      EXPECT_EQ(std::string(text_of(root["a"])), "abcdefghij") << pad;
      EXPECT_EQ(root["b"].GetDouble(), 1250.0) << pad;
    }
  }
}

TEST(JsonStream, ErrorPositionsCountLinesOverManyBuffers) {
  std::string text = "[\n";
  for (int i = 0; i < 40000; ++i) text += "  1,\n";  // 200 kB: four buffers
  text += "  x]\n";
  for (std::size_t chunk : {std::size_t(1) << 20, std::size_t(7)}) {
    const std::string what = error_of(text, chunk);
    EXPECT_NE(what.find("t.json: line 40002, column 3: syntax error"), std::string::npos) << what;
  }
}

TEST(JsonStream, NulAfterTheValueIsNotTheEnd) {
  EXPECT_NE(error_of(std::string("{}\0{}", 5)).find("expected end of input"), std::string::npos);
  EXPECT_NE(error_of(std::string("{}   \0", 6)).find("line 1, column 6"), std::string::npos);
  EXPECT_EQ(error_of("{}  \n"), "accepted");
}

TEST(JsonStream, StreamedMembersArriveOneByOneAndStayEmpty) {
  std::vector<std::string> seen;
  std::map<std::string, StreamedMember, std::less<>> streamed;
  streamed["list"] = {false, [&](std::string_view, std::size_t i, const JsonValue& v) {
                        seen.push_back(std::to_string(i) + ":" +
                                       std::to_string(v.IsObject() ? v.MemberCount() : 99));
                      }};
  streamed["map"] = {
      true, [&](std::string_view key, std::size_t, const JsonValue& v) {
        seen.push_back(std::string(key) + "=" + (v.IsString() ? std::string(text_of(v)) : "?"));
      }};
  JsonDocument root;
  parse(R"({"list": [{"a": 1}, {}, 3], "map": {"x": "1", "y": "2"}, "other": [1]})", root, 1 << 20,
        streamed);
  EXPECT_EQ(seen, (std::vector<std::string>{"0:1", "1:0", "2:99", "x=1", "y=2"}));
  EXPECT_TRUE(root["list"].IsArray() && root["list"].Empty());
  EXPECT_TRUE(root["map"].IsObject() && root["map"].MemberCount() == 0);
  EXPECT_EQ(root["other"].Size(), 1u);
}

TEST(JsonStream, DuplicateKeysAreFoundInBigObjectsToo) {
  std::string text = "{";
  for (int i = 0; i < 5000; ++i) text += "\"k" + std::to_string(i) + "\": 0, ";
  text += "\"k4321\": 1}";
  EXPECT_NE(error_of(text).find("the key 'k4321' appears twice in one object"), std::string::npos);
}

TEST(NameIndex, GivesDenseIndicesInFirstSeenOrder) {
  NameIndex names;
  std::vector<std::string> inserted;
  for (int i = 0; i < 100000; ++i) {
    std::string name = "m";  // (append: GCC 12 warns falsely, -Wrestrict, on "m" + string)
    name.append(std::to_string((i * 7919) % 100000));
    ASSERT_EQ(names.intern(name, NameIndex::hash(name)), std::uint32_t(i));
    inserted.push_back(name);
  }
  EXPECT_EQ(names.size(), inserted.size());
  for (std::size_t i = 0; i < inserted.size(); i += 997) {
    EXPECT_EQ(names.intern(inserted[i], NameIndex::hash(inserted[i])), std::uint32_t(i));
    EXPECT_EQ(names.name(std::uint32_t(i)), inserted[i]);
  }
  const std::string with_nul("a\0b", 3);
  const std::uint32_t a = names.intern("a", NameIndex::hash("a"));
  const std::uint32_t nul = names.intern(with_nul, NameIndex::hash(with_nul));
  EXPECT_NE(a, nul);
  EXPECT_EQ(names.name(nul), with_nul);
}

TEST(NameIndex, KeepsEveryNameThroughGrowthWhenHashesCollide) {
  // The caller gives the hash: names that share one (and whose first slot is the table's
  // last, so that their probes wrap around) or share its top bits, across many doublings.
  NameIndex names;
  std::vector<std::pair<std::string, std::uint64_t>> inserted;
  for (int i = 0; i < 5000; ++i) {
    const std::uint64_t hash = i % 3 == 0   ? ~std::uint64_t(0)
                               : i % 3 == 1 ? (std::uint64_t(i % 7) << 61) | std::uint64_t(i)
                                            : NameIndex::hash(std::to_string(i));
    std::string name = "n";  // (append: GCC 12 warns falsely, -Wrestrict, on "n" + string)
    name.append(std::to_string(i));
    inserted.push_back({name, hash});
    ASSERT_EQ(names.intern(inserted.back().first, hash), std::uint32_t(i));
  }
  for (std::size_t i = 0; i < inserted.size(); ++i) {
    EXPECT_EQ(names.intern(inserted[i].first, inserted[i].second), std::uint32_t(i));
    EXPECT_EQ(names.name(std::uint32_t(i)), inserted[i].first);
  }
  EXPECT_EQ(names.size(), inserted.size());
  EXPECT_EQ(names.intern("", 0), std::uint32_t(inserted.size()));
  EXPECT_EQ(names.name(std::uint32_t(inserted.size())), "");
}

}  // namespace
}  // namespace rtiow
