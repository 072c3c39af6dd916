#include "core/render/sample_share.h"

#include <charconv>
#include <optional>
#include <utility>
#include <variant>

#include "core/film/sample_sum.h"
#include "core/limits/error.h"
#include "core/limits/setting_name.h"

namespace rtiow {
namespace {

// "A<sep>B" as two whole numbers, or nothing (no sign, no spaces, no overflow).
std::optional<std::pair<std::uint64_t, std::uint64_t>> parse_pair(const std::string& text,
                                                                  char separator) {
  const auto at = text.find(separator);
  if (at == std::string::npos) return std::nullopt;
  std::uint64_t a = 0, b = 0;
  const char* end = text.data() + text.size();
  const auto first = std::from_chars(text.data(), text.data() + at, a);
  const auto second = std::from_chars(text.data() + at + 1, end, b);
  if (at == 0 || first.ec != std::errc() || first.ptr != text.data() + at ||
      second.ec != std::errc() || second.ptr != end || at + 1 == text.size()) {
    return std::nullopt;
  }
  return std::pair{a, b};
}

}  // namespace

SampleShare equal_share(std::uint64_t total, std::uint64_t index, std::uint64_t shares) {
  // total < 2^32 (validate(RenderSettings)) and index < shares <= total: no overflow.
  const std::uint64_t first = total * index / shares;
  return {first, total * (index + 1) / shares - first};
}

SampleShare parse_part(const std::string& text, std::uint64_t total) {
  const auto share = parse_pair(text, '/');
  const std::string part = setting("part", quote_value(text));
  if (!share) throw InvalidInput(part + ": expected i/n, e.g. 0/4");
  const auto [i, n] = *share;
  if (n == 0 || i >= n) throw InvalidInput(part + ": need 0 <= i < n");
  if (n > total) {
    throw InvalidInput(part + ": " + std::to_string(total) + " samples per pixel do not make " +
                       std::to_string(n) + " shares");
  }
  return equal_share(total, i, n);
}

SampleShare parse_sample_range(const std::string& text, std::uint64_t total) {
  const auto range = parse_pair(text, ':');
  const std::string option = setting("sample_range", quote_value(text));
  if (!range) throw InvalidInput(option + ": expected A:B, e.g. 0:100");
  const auto [a, b] = *range;
  if (a >= b || b > total) {
    throw InvalidInput(option + ": need A < B <= the job's " + std::to_string(total) +
                       " samples per pixel (" + setting("spp") + ")");
  }
  return {a, b - a};
}

std::uint64_t shareable_samples(const RenderSettings& settings, const std::string& what) {
  const auto* fixed = std::get_if<FixedSamples>(&settings.samples);
  if (!fixed) {
    throw InvalidInput(what + " shares a fixed number of samples per pixel: give " +
                       setting("spp") + " (and no adaptive mode)");
  }
  return std::uint64_t(fixed->per_pixel);
}

void restrict_to(const SampleShare& share, RenderSettings& settings) {
  settings.first_sample = share.first;
  settings.samples = FixedSamples{int(share.count)};
}

void restore_whole_job(std::uint64_t job_samples, RenderSettings& settings) {
  settings.first_sample = 0;
  settings.samples = FixedSamples{int(job_samples)};
}

void complete_from_shares(std::uint64_t samples, RenderResult& result) {
  result.first_sample = 0;
  result.samples_completed = int(samples);
  result.replicate_ratios.reset();  // the share's, not the whole's
  result.pixel_samples.assign(result.sums.size(), std::uint32_t(samples));
  resolve(result.sums.color, samples, result.film);
}

}  // namespace rtiow
