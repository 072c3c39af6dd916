#pragma once
// The exact sums a pixel keeps, declared once: their groups, the channels of each, and what
// one sample can add to each channel. Every reader and writer of sums from outside the
// process (the part file's channels, the checkpoint's records) and the one validator that
// checks them (core/film/sum_validation.h) walk this table, so a channel has one name and
// one bound wherever it travels.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/film/first_hit_sum.h"
#include "core/film/pixel_variance.h"
#include "core/film/sample_sum.h"

namespace rtiow {

// Where a group's sums live in a pixel's accumulators.
enum class SumGroup : std::uint8_t {
  Samples,   // the samples' own sum (PixelSum)
  Squares,   // the sum of the squared samples (PixelSpread::squares)
  Odd,       // the sum of the samples of odd index, the second replicate (PixelSpread::odd)
  FirstHit,  // the passes' sums of what the camera ray first met (FirstHitSum)
};

// What one sample can add to a channel, before rounding: [least, most].
struct SampleRange {
  double least, most;
};

struct SumGroupDeclaration {
  SumGroup group;
  std::string_view name;  // the part file's channel prefix, and the name in messages
  std::size_t channels;
  const std::string_view* channel_names;
  const SampleRange* ranges;  // one per channel
  bool is_signed;
};

inline constexpr std::array<std::string_view, 3> kColorChannelNames{"R", "G", "B"};
inline constexpr std::array<std::string_view, FirstHitSum::kChannels> kFirstHitChannelNames{
    "albedo.R", "albedo.G", "albedo.B", "N.X", "N.Y", "N.Z", "Z"};

// A float albedo or unit normal component can round a little past 1.
inline constexpr double kUnitSlack = 1.0 + 1e-6;
inline constexpr double kMostSample = PixelSum::kMaxSample;
inline constexpr std::array<SampleRange, 3> kRadianceRanges{
    {{0, kMostSample}, {0, kMostSample}, {0, kMostSample}}};
inline constexpr std::array<SampleRange, 3> kSquareRanges{
    {{0, kMostSample* kMostSample}, {0, kMostSample* kMostSample}, {0, kMostSample* kMostSample}}};
inline constexpr std::array<SampleRange, FirstHitSum::kChannels> kFirstHitRanges{{
    {0, kUnitSlack},
    {0, kUnitSlack},
    {0, kUnitSlack},
    {-kUnitSlack, kUnitSlack},
    {-kUnitSlack, kUnitSlack},
    {-kUnitSlack, kUnitSlack},
    {0, FirstHitSum::kMaxValue},
}};

// In the order checkpoints store them (part files name their channels, which EXR sorts).
inline constexpr std::array<SumGroupDeclaration, 4> kSumGroups{{
    {SumGroup::Samples, "sum", 3, kColorChannelNames.data(), kRadianceRanges.data(), false},
    {SumGroup::Squares, "squares", 3, kColorChannelNames.data(), kSquareRanges.data(), false},
    {SumGroup::Odd, "odd", 3, kColorChannelNames.data(), kRadianceRanges.data(), false},
    {SumGroup::FirstHit, "first_hit", FirstHitSum::kChannels, kFirstHitChannelNames.data(),
     kFirstHitRanges.data(), true},
}};

// One pixel's sums as the table sees them: its group sums, the spread and first hits where
// the pixel keeps them (null where it does not: a part written before spreads, a render
// without passes).
struct PixelSumsRef {
  const PixelSum* sum = nullptr;
  const PixelSpread* spread = nullptr;
  const FirstHitSum* first_hit = nullptr;

  bool has(SumGroup g) const {
    return g == SumGroup::Samples    ? sum != nullptr
           : g == SumGroup::FirstHit ? first_hit != nullptr
                                     : spread != nullptr;
  }
  int128 channel(SumGroup g, std::size_t c) const {
    switch (g) {
      case SumGroup::Samples:
        return sum->channel(int(c));
      case SumGroup::Odd:
        return spread->odd.channel(int(c));
      case SumGroup::Squares:
        return spread->squares.channel(int(c));
      case SumGroup::FirstHit:
        return first_hit->channel(c);
    }
    return 0;
  }
};

// The same, to fill: what a reader of a file sets, channel by channel.
struct PixelSumsOut {
  PixelSum* sum = nullptr;
  PixelSpread* spread = nullptr;
  FirstHitSum* first_hit = nullptr;

  bool has(SumGroup g) const { return PixelSumsRef{sum, spread, first_hit}.has(g); }
  void set(SumGroup g, std::size_t c, int128 value) const {
    switch (g) {
      case SumGroup::Samples:
        sum->set_channel(int(c), value);
        return;
      case SumGroup::Odd:
        spread->odd.set_channel(int(c), value);
        return;
      case SumGroup::Squares:
        spread->squares.set_channel(int(c), value);
        return;
      case SumGroup::FirstHit:
        first_hit->set_channel(c, value);
        return;
    }
  }
  PixelSumsRef ref() const { return {sum, spread, first_hit}; }
};

}  // namespace rtiow
