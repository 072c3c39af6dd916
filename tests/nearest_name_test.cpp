// The name a slip meant, as the refusals of options, choices, commands and scenes suggest it.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/limits/nearest_name.h"

namespace {

using rtiow::did_you_mean;
using rtiow::nearest_name;

const std::vector<std::string> kRoulette{"on", "off"};
const std::vector<std::string> kSamplers{"independent", "sobol", "padded-sobol"};

TEST(NearestName, OneEditOrASwapIsASlip) {
  EXPECT_EQ(nearest_name("sobel", kSamplers), "sobol");  // a letter changed
  EXPECT_EQ(nearest_name("sobl", kSamplers), "sobol");   // one left out
  EXPECT_EQ(nearest_name("--widht", {"--width", "--height", "--seed"}), "--width");  // a swap
  EXPECT_EQ(nearest_name("padded-sbool", kSamplers), "padded-sobol");
}

// "of" is one edit from both "on" and "off"; a word cut short is the likelier slip, whatever
// the order of the choices.
TEST(NearestName, AtEqualDistanceANameTheWordBeginsWins) {
  EXPECT_EQ(nearest_name("of", kRoulette), "off");
  EXPECT_EQ(nearest_name("of", {"off", "on"}), "off");
  EXPECT_EQ(nearest_name("o", kRoulette), "on");  // nearer: one edit against two
}

TEST(NearestName, NothingNearEnoughSuggestsNothing) {
  EXPECT_EQ(nearest_name("zzz", kSamplers), "");
  EXPECT_EQ(nearest_name("random", kSamplers), "");
  EXPECT_EQ(did_you_mean("zzz", kSamplers), "");
  EXPECT_EQ(nearest_name("sobel", {}), "");
}

TEST(NearestName, TheSuggestionReadsAsPartOfARefusal) {
  EXPECT_EQ(did_you_mean("embre", {"embree", "naive"}), "; did you mean embree?");
}

}  // namespace
