#pragma once
// A share of a render: samples [first, first + count) of every pixel. Shares rendered
// anywhere (separate jobs with --part or --sample-range, MPI ranks) add into the exact sums of
// one render; the arithmetic of splitting a job lives here, once.

#include <cstdint>
#include <string>

#include "core/render/render_settings.h"

namespace rtiow {

struct SampleShare {
  std::uint64_t first = 0, count = 0;
};

// The samples per pixel of a job that is to be shared: its fixed count. Throws InvalidInput
// for any other budget (`what` names what asked to share it, as the front end spells it).
std::uint64_t shareable_samples(const RenderSettings& settings, const std::string& what);

// The index-th of `shares` equal shares of `total` samples (sizes differ by at most one).
// Needs index < shares <= total.
SampleShare equal_share(std::uint64_t total, std::uint64_t index, std::uint64_t shares);

// "i/n": the i-th of n equal shares of a job of `total` samples. Throws InvalidInput naming
// the option (--part) and what is wrong.
SampleShare parse_part(const std::string& text, std::uint64_t total);

// "A:B": samples A..B-1 of a job of `total` samples. Throws InvalidInput (--sample-range).
SampleShare parse_sample_range(const std::string& text, std::uint64_t total);

// Settings that render only `share` of the job.
void restrict_to(const SampleShare& share, RenderSettings& settings);

// The other way, once shares are added together (part files merged, MPI ranks reduced): the
// settings of the whole job of `job_samples` per pixel, and `result`, whose sums and spreads
// hold `samples` per pixel from sample 0, made the result one render of them gives (its film
// resolved from the sums). Both ways of combining shares end here.
void restore_whole_job(std::uint64_t job_samples, RenderSettings& settings);
void complete_from_shares(std::uint64_t samples, RenderResult& result);

}  // namespace rtiow
