#include "core/film/sum_validation.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/film/replicate_variance.h"

namespace rtiow {
namespace {

// The most one value's rounding to 2^-32 moves it (half a step), and a relative allowance for
// the double arithmetic of the checks (and of squares past 2^53 in fixed point).
constexpr double kRounding = 0.5 / PixelSum::kScale;
constexpr double kRelative = 1e-9;

std::string channel_name(const SumGroupDeclaration& d, std::size_t c) {
  return std::string(d.name) + "." + std::string(d.channel_names[c]);
}

std::string samples_text(std::uint64_t n) {
  return std::to_string(n) + (n == 1 ? " sample" : " samples");
}

double value_of(int128 fixed) {
  return double(fixed) / PixelSum::kScale;
}

// Whether `count` samples, each within `range`, can add up to `fixed`.
bool within(int128 fixed, std::uint64_t count, const SampleRange& range) {
  const double n = double(count), v = value_of(fixed);
  const double most = n * (range.most * (1 + kRelative) + kRounding);
  const double least = range.least >= 0 ? 0.0 : n * (range.least * (1 + kRelative) - kRounding);
  return fixed >= 0 ? v <= most : range.least < 0 && v >= least;
}

// Every channel of every group the pixel keeps within what its samples can add.
std::string out_of_range(const PixelSumsRef& sums, std::uint64_t first, std::uint64_t n) {
  for (const SumGroupDeclaration& d : kSumGroups) {
    if (!sums.has(d.group)) continue;
    const std::uint64_t count = d.group == SumGroup::Odd ? odd_samples(first, n) : n;
    for (std::size_t c = 0; c < d.channels; ++c) {
      if (!within(sums.channel(d.group, c), count, d.ranges[c])) {
        return channel_name(d, c) + " is beyond what " + samples_text(count) +
               (d.group == SumGroup::Odd ? " of odd index" : "") + " can add up to";
      }
    }
  }
  return {};
}

// The spread against the sums, per colour channel: the odd samples are some of the samples;
// the squares are at least what each replicate's sum forces (the sum of k values whose sum is
// s squares to at least s^2 / k) and at most the most a sample can be times the sum (v^2 <=
// max v for 0 <= v <= max). Each sum read as the least its rounded values allow, each square
// as the most.
std::string inconsistent_spread(const PixelSumsRef& sums, std::uint64_t first, std::uint64_t n) {
  const std::uint64_t n_odd = odd_samples(first, n), n_even = n - n_odd;
  for (std::size_t c = 0; c < 3; ++c) {
    const std::string colour(kColorChannelNames[c]);
    const int128 all = sums.channel(SumGroup::Samples, c), odd = sums.channel(SumGroup::Odd, c);
    if (odd > all) return "odd." + colour + " is more than sum." + colour + ", which holds it";
    if (n_even == 0 && odd != all) {
      return "sum." + colour + " is not odd." + colour +
             ", though all its samples are of odd index";
    }
    const double squares_most =
        (value_of(sums.channel(SumGroup::Squares, c)) + double(n) * kRounding) * (1 + kRelative);
    double forced = 0.0;
    for (const auto& [sum, count] : {std::pair{odd, n_odd}, std::pair{all - odd, n_even}}) {
      if (count == 0) continue;
      const double least = std::max(0.0, value_of(sum) - double(count) * kRounding);
      forced += least * least / double(count);
    }
    if (forced > squares_most) {
      return "squares." + colour + " is less than the squares of samples whose sum is sum." +
             colour + " can add up to";
    }
    const double sum_most = value_of(all) + double(n) * kRounding;
    const double squares_least =
        std::max(0.0, value_of(sums.channel(SumGroup::Squares, c)) - double(n) * kRounding);
    if (squares_least > PixelSum::kMaxSample * sum_most * (1 + kRelative)) {
      return "squares." + colour + " is more than samples whose sum is sum." + colour +
             " can square to";
    }
  }
  return {};
}

// A sum of unit normals is no longer than the number of samples that met a surface.
std::string normal_too_long(const FirstHitSum& hits, std::uint64_t n) {
  double length2 = 0.0;
  for (std::size_t c = 3; c < 6; ++c)
    length2 += value_of(hits.channel(c)) * value_of(hits.channel(c));
  const double most = double(n) * (kUnitSlack + 3 * kRounding) * (1 + kRelative);
  return std::sqrt(length2) > most
             ? "first_hit.N is longer than " + samples_text(n) + " of unit normals can add up to"
             : std::string();
}

}  // namespace

std::string impossible_sums(const PixelSumsRef& sums, std::uint64_t first, std::uint64_t samples) {
  std::string why = out_of_range(sums, first, samples);
  if (why.empty() && sums.spread) why = inconsistent_spread(sums, first, samples);
  if (why.empty() && sums.first_hit) why = normal_too_long(*sums.first_hit, samples);
  return why;
}

}  // namespace rtiow
