// A float written as JSON (core/scene_file/json_float.h) reads back to the same float, in the
// fewest significant digits that do, laid out as nlohmann::json lays out the double it
// reads as (the writer rtiow used before, and still uses for everything but floats).

#include <gtest/gtest.h>

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/scene_file/json_float.h"
#include "core/scene_file/json_reader.h"

namespace rtiow {
namespace {

float read_back(const std::string& text) {
  double d = 0;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), d);
  EXPECT_EQ(result.ptr, text.data() + text.size()) << text;
  return float(d);
}

int significant_digits(const std::string& text) {
  std::string digits;
  for (const char c : text) {
    if (c == 'e') break;
    if (c >= '0' && c <= '9') digits.push_back(c);
  }
  const auto first = digits.find_first_not_of('0');
  if (first == std::string::npos) return 0;
  const auto last = digits.find_last_not_of('0');
  return int(last - first + 1);
}

std::string as_nlohmann_writes(float f) {
  return nlohmann::ordered_json(scene_json::shortest(f)).dump();
}

TEST(JsonFloat, WritesCommonValuesAsNlohmannDid) {
  const std::vector<float> values = {0.0f,
                                     -0.0f,
                                     1.0f,
                                     -1.0f,
                                     0.5f,
                                     0.1f,
                                     1.5f,
                                     1000.0f,
                                     1e15f,
                                     1e16f,
                                     1.5e16f,
                                     1e-4f,
                                     1.2e-4f,
                                     1e-5f,
                                     1.25e-5f,
                                     13.0f,
                                     0.001f,
                                     100.0f,
                                     1e-45f,
                                     3e38f,
                                     -2.5e-7f,
                                     123456789.0f,
                                     0.3f,
                                     0.7f,
                                     1e10f,
                                     9.999999e14f,
                                     std::numeric_limits<float>::max(),
                                     std::numeric_limits<float>::min(),
                                     std::numeric_limits<float>::denorm_min()};
  for (const float f : values) {
    EXPECT_EQ(json_float_text(f), as_nlohmann_writes(f)) << f;
  }
  EXPECT_EQ(json_float_text(std::numeric_limits<float>::infinity()), "null");
  EXPECT_EQ(json_float_text(std::nanf("")), "null");
}

TEST(JsonFloat, EveryKindOfFloatReadsBackInTheFewestDigits) {
  // Random bit patterns (every exponent), and values near the layout's edges.
  std::mt19937 rng(7);
  int differ = 0;
  const int kTrials = 2'000'000;
  for (int trial = 0; trial < kTrials; ++trial) {
    float f = std::bit_cast<float>(std::uint32_t(rng()));
    if (trial % 4 == 1) f = float(std::ldexp(double(rng()) / 4294967296.0, int(rng() % 80) - 30));
    if (trial % 4 == 2) f = float(int(rng() % 100000)) / float(1 + rng() % 1000);
    if (!std::isfinite(f)) continue;
    const std::string mine = json_float_text(f);
    ASSERT_EQ(std::bit_cast<std::uint32_t>(read_back(mine)), std::bit_cast<std::uint32_t>(f))
        << mine;
    const std::string theirs = as_nlohmann_writes(f);
    if (mine != theirs) {
      ++differ;
      // Only where nlohmann's Grisu2 fell short of the shortest digits (it wrote 196.24512
      // as 196.24511999999999): about one float in 300.
      ASSERT_LT(significant_digits(mine), significant_digits(theirs)) << mine << " " << theirs;
    }
  }
  RecordProperty("fewer_digits_than_nlohmann", differ);
  EXPECT_LT(differ, kTrials / 100);
}

}  // namespace
}  // namespace rtiow
