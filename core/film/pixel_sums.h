#pragma once
// A film's exact sums, in one shape wherever they go: the render's accumulators and result, a
// part file's, a merge's, the MPI reduction's, a checkpoint's, a preview's. Each group of
// core/film/sum_channels.h is a row-major, film-sized vector, or empty where the render keeps
// no such group (first hits without --passes; spreads in a part written before parts kept
// them). Adding, comparing and walking the channels go through that one declaration, so a new
// group of sums is a field here, its row in the table and the code that fills it.

#include <cstddef>
#include <vector>

#include "core/film/first_hit_sum.h"
#include "core/film/pixel_variance.h"
#include "core/film/sample_sum.h"
#include "core/film/sum_channels.h"

namespace rtiow {

struct PixelSums {
  std::vector<PixelSum> color;          // SumGroup::Samples: what the image is the mean of
  std::vector<PixelSpread> spreads;     // SumGroup::Squares and SumGroup::Odd: the variances'
  std::vector<FirstHitSum> first_hits;  // SumGroup::FirstHit: the passes'

  PixelSums() = default;
  // `pixels` pixels of zeros, keeping the spreads and the first hits as asked.
  PixelSums(std::size_t pixels, bool keep_spreads, bool keep_first_hits)
      : color(pixels),
        spreads(keep_spreads ? pixels : 0),
        first_hits(keep_first_hits ? pixels : 0) {}

  std::size_t size() const { return color.size(); }

  // Whether group `g` is kept: the colour's always, the others where they have every pixel.
  bool keeps(SumGroup g) const {
    switch (g) {
      case SumGroup::Samples:
        return true;
      case SumGroup::Squares:
      case SumGroup::Odd:
        return !spreads.empty() && spreads.size() == color.size();
      case SumGroup::FirstHit:
        return !first_hits.empty() && first_hits.size() == color.size();
    }
    return false;
  }
  // Pixel p's sums, group by group (null where a group is not kept).
  PixelSumsRef at(std::size_t p) const {
    return {&color[p], keeps(SumGroup::Odd) ? &spreads[p] : nullptr,
            keeps(SumGroup::FirstHit) ? &first_hits[p] : nullptr};
  }
  PixelSumsOut at(std::size_t p) {
    return {&color[p], keeps(SumGroup::Odd) ? &spreads[p] : nullptr,
            keeps(SumGroup::FirstHit) ? &first_hits[p] : nullptr};
  }

  // Adds `other`'s sums, pixel by pixel, into every group this keeps (`other` must keep them
  // too): how shares of a render combine (a merge of parts, the MPI reduction). Exact, so the
  // order never matters.
  PixelSums& operator+=(const PixelSums& other) {
    for_each_vector(other, [](auto& into, const auto& from) {
      for (std::size_t i = 0; i < into.size() && i < from.size(); ++i) into[i] += from[i];
    });
    return *this;
  }

  // Calls f(vector) for each group's vector, kept or not: what moves the sums as a whole
  // (the MPI reduction) walks them so, and knows no group by name.
  template <typename F>
  void for_each_vector(F&& f) {
    f(color), f(spreads), f(first_hits);
  }
  // The same, pairing each of this's vectors with `other`'s.
  template <typename F>
  void for_each_vector(const PixelSums& other, F&& f) {
    f(color, other.color), f(spreads, other.spreads), f(first_hits, other.first_hits);
  }

  bool operator==(const PixelSums&) const = default;
};

}  // namespace rtiow
