#include "core/render/render_part.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "core/film/sum_validation.h"
#include "core/io/atomic_file.h"
#include "core/io/image_backend.h"
#include "core/io/image_file.h"
#include "core/limits/error.h"
#include "core/limits/input_limits.h"
#include "core/limits/setting_name.h"
#include "core/render/render.h"
#include "core/render/render_identity.h"
#include "core/render/render_metadata.h"
#include "core/render/sample_share.h"
#include "core/scene_file/scene_digest.h"

namespace rtiow {
namespace {

namespace fs = std::filesystem;

constexpr int kColorChannels = 3, kWordsPerSum = 4;

// The part file's own header fields, beside the render's metadata (render_metadata.h).
const std::string kPartFieldPrefix = std::string(kMetadataPrefix) + "part_";
const std::string kPartFirstSample = kPartFieldPrefix + "first_sample";
const std::string kPartSamples = kPartFieldPrefix + "samples";
const std::string kPartJobSamples = kPartFieldPrefix + "job_samples";
const std::string kDigest = std::string(kMetadataPrefix) + "digest";

// The file channel of word w (low first) of channel c of a group of sums
// (core/film/sum_channels.h): "sum.R.0", "first_hit.albedo.R.3".
std::string word_channel(const SumGroupDeclaration& d, std::size_t c, int w) {
  return std::string(d.name) + "." + std::string(d.channel_names[c]) + "." + std::to_string(w);
}

// A whole number from a header field, or InvalidInput naming the file and the field.
std::uint64_t header_number(const ImageHeader& header, const std::string& path,
                            const std::string& field) {
  const std::string text = header.string_attribute(field);
  std::uint64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size()) {
    throw InvalidInput("part file " + quote_value(path) + ": header field " + field +
                       " is missing or not a whole number (" + quote_value(text, 40) + ")");
  }
  return value;
}

// A count the part recorded (0 where it has none); a part whose count is not a whole number
// is refused by name, not taken for one.
std::int64_t metadata_count(const RenderPart& part, const std::string& key) {
  for (const auto& [k, v] : part.metadata) {
    if (k != key) continue;
    if (const auto* n = std::get_if<std::int64_t>(&v)) return *n;
    throw InvalidInput("part file " + quote_value(part.path) + ": " + kMetadataPrefix + key +
                       " is not a whole number");
  }
  return 0;
}

}  // namespace

RenderPart make_part(const Scene& scene, const RenderSettings& share, std::uint64_t job_samples,
                     const RenderResult& result, Metadata metadata) {
  const RenderSettings s = with_scene_image(scene, share);  // as the render took them
  if (result.film.width() != film_width(s) || result.film.height() != film_height(s) ||
      result.sums.size() != std::size_t(result.film.width()) * std::size_t(result.film.height())) {
    throw InvalidInput("make_part: the result is not of the share's " +
                       std::to_string(film_width(s)) + "x" + std::to_string(film_height(s)) +
                       " film");
  }
  RenderPart part;
  part.width = film_width(s), part.height = film_height(s);
  part.first_sample = s.first_sample;
  part.samples = std::uint64_t(result.samples_completed);
  part.job_samples = job_samples;
  part.digest = shared_digest(render_identity(scene, s));
  part.metadata = std::move(metadata);
  return part;
}

void write_part(const std::string& path, const RenderPart& part, const PixelSums& sums) {
  if (sums.size() != std::size_t(part.width) * std::size_t(part.height)) {
    throw std::invalid_argument("write_part: the sums are not of the part's " +
                                std::to_string(part.width) + "x" + std::to_string(part.height) +
                                " film");
  }
  const ImageBackend& backend = image_backend();
  ImageHeader header;
  header.width = header.full_width = part.width;
  header.height = header.full_height = part.height;
  for (const char* c : {"R", "G", "B"}) {
    header.channel_names.emplace_back(c);
    header.channel_types.push_back(PixelType::Float);
  }
  for (const SumGroupDeclaration& d : kSumGroups) {
    for (std::size_t c = 0; sums.keeps(d.group) && c < d.channels; ++c) {
      for (int w = 0; w < kWordsPerSum; ++w) {
        header.channel_names.push_back(word_channel(d, c, w));
        header.channel_types.push_back(PixelType::UInt32);
      }
    }
  }
  auto& attributes = header.attributes;
  attributes.push_back({"compression", std::string("zip")});
  for (const auto& [key, value] : part.metadata) {
    if (const auto* i = std::get_if<std::int64_t>(&value)) {
      attributes.push_back({kMetadataPrefix + key, std::to_string(*i)});
    } else if (const auto* d = std::get_if<double>(&value)) {
      attributes.push_back({kMetadataPrefix + key, float(*d)});
    } else {
      attributes.push_back({kMetadataPrefix + key, std::get<std::string>(value)});
    }
  }
  attributes.push_back({kPartFirstSample, std::to_string(part.first_sample)});
  attributes.push_back({kPartSamples, std::to_string(part.samples)});
  attributes.push_back({kPartJobSamples, std::to_string(part.job_samples)});
  attributes.push_back({kDigest, part.digest});

  // Native layout: per pixel 3 floats, then the words of every channel of every group kept,
  // all 4 bytes wide; a strip of rows at a time (268 bytes a pixel with the passes).
  const std::size_t channels = header.channel_names.size();
  const std::size_t width = std::size_t(part.width);
  std::vector<std::uint32_t> strip;
  const auto rows = [&](int y_begin, int y_end) -> const void* {
    strip.resize(width * std::size_t(y_end - y_begin) * channels);
    for (std::size_t i = 0; i < width * std::size_t(y_end - y_begin); ++i) {
      const std::size_t p = std::size_t(y_begin) * width + i;
      std::uint32_t* pixel = &strip[i * channels];
      const Color mean = sums.color[p].mean(part.samples);
      std::memcpy(pixel, &mean, sizeof mean);
      std::uint32_t* words = pixel + kColorChannels;
      const PixelSumsRef pixel_sums = sums.at(p);
      for (const SumGroupDeclaration& d : kSumGroups) {
        for (std::size_t c = 0; pixel_sums.has(d.group) && c < d.channels; ++c) {
          const auto bits = static_cast<uint128>(pixel_sums.channel(d.group, c));
          for (int w = 0; w < kWordsPerSum; ++w) *words++ = std::uint32_t(bits >> (32 * w));
        }
      }
    }
    return strip.data();
  };

  std::vector<unsigned char> encoded;
  std::string reason;
  if (!backend.encode(path, header, rows, encoded, reason)) {
    throw std::runtime_error("cannot write '" + path + "': " + reason);
  }
  write_bytes_atomically(path, encoded);
}

namespace {

// Where each 32-bit word of each channel of each group of sums is among the file's channels
// (EXR stores channels sorted by name), for the groups the part keeps: the samples' sums
// always; the spread's two groups, or neither (a part written before parts kept them); the
// passes' with --passes. Nothing if the file is not a part file.
struct SumChannels {
  std::array<bool, kSumGroups.size()> kept{};
  std::array<std::vector<std::array<int, kWordsPerSum>>, kSumGroups.size()> words;
  std::size_t stride = kColorChannels;  // channels per pixel
};

std::optional<SumChannels> find_sum_channels(const ImageHeader& header) {
  const std::vector<std::string>& names = header.channel_names;
  const auto index_of = [&](const std::string& name) {
    const auto it = std::find(names.begin(), names.end(), name);
    return it == names.end() ? -1 : int(it - names.begin());
  };
  SumChannels found;
  for (std::size_t g = 0; g < kSumGroups.size(); ++g) {
    const SumGroupDeclaration& d = kSumGroups[g];
    found.kept[g] = index_of(word_channel(d, 0, 0)) >= 0;
    for (std::size_t c = 0; found.kept[g] && c < d.channels; ++c) {
      std::array<int, kWordsPerSum> at{};
      for (int w = 0; w < kWordsPerSum; ++w) {
        at[std::size_t(w)] = index_of(word_channel(d, c, w));
        if (at[std::size_t(w)] < 0) return {};
      }
      found.words[g].push_back(at);
      found.stride += kWordsPerSum;
    }
  }
  const auto kept = [&](SumGroup g) { return found.kept[std::size_t(g)]; };
  if (!kept(SumGroup::Samples) || kept(SumGroup::Odd) != kept(SumGroup::Squares) ||
      names.size() != found.stride || header.string_attribute(kDigest).empty()) {
    return {};
  }
  return found;
}

// The header decides what is allocated: its size and sample fields are checked first.
void read_part_header(const ImageHeader& header, const std::string& name, RenderPart& part) {
  if (header.width < 1 || header.height < 1 || header.width > limits::kMaxImageSide ||
      header.height > limits::kMaxImageSide || header.depth != 1 || header.x != 0 ||
      header.y != 0 || header.full_width != header.width || header.full_height != header.height) {
    throw InvalidInput(name + ": header field size " + std::to_string(header.width) + "x" +
                       std::to_string(header.height) + " is not an image rtiow renders");
  }
  RenderSettings size;  // only the size is checked here
  size.width = header.width, size.height = header.height, size.samples = FixedSamples{1};
  size.max_depth = 0;
  try {
    validate(size);  // pixel count and memory
  } catch (const InvalidInput& e) {
    throw InvalidInput(name + ": " + e.what());
  }
  part.width = header.width;
  part.height = header.height;
  part.first_sample = header_number(header, part.path, kPartFirstSample);
  part.samples = header_number(header, part.path, kPartSamples);
  part.job_samples = header_number(header, part.path, kPartJobSamples);
  if (part.samples == 0 || part.job_samples == 0 || part.job_samples > limits::kMaxSampleIndex ||
      part.first_sample >= part.job_samples ||
      part.samples > part.job_samples - part.first_sample) {
    throw InvalidInput(name + ": header fields say samples [" + std::to_string(part.first_sample) +
                       ", +" + std::to_string(part.samples) + ") of a job of " +
                       std::to_string(part.job_samples) + ": not a share of it");
  }
  part.digest = header.string_attribute(kDigest);
}

// The render's metadata: every "rtiow:" attribute but the part file's own fields.
Metadata read_part_metadata(const ImageHeader& header) {
  Metadata metadata;
  for (const ImageAttribute& attribute : header.attributes) {
    const std::string& attribute_name = attribute.name;
    if (attribute_name.rfind(kMetadataPrefix, 0) != 0 ||
        attribute_name.rfind(kPartFieldPrefix, 0) == 0 || attribute_name == kDigest) {
      continue;
    }
    const std::string key = attribute_name.substr(std::string_view(kMetadataPrefix).size());
    if (const auto* f = std::get_if<float>(&attribute.value)) {
      metadata.emplace_back(key, double(*f));
      continue;
    }
    const auto* i = std::get_if<int>(&attribute.value);
    const std::string text = i ? std::to_string(*i) : std::get<std::string>(attribute.value);
    std::int64_t number = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), number);
    const bool integer = !text.empty() && text.front() != '-' && error == std::errc() &&
                         end == text.data() + text.size();
    metadata.emplace_back(key, integer ? MetadataValue(number) : MetadataValue(text));
  }
  return metadata;
}

// Rows a part is read by: its 32-bit words are 268 bytes a pixel with the passes, so a whole
// image's would outweigh the sums they add to. A multiple of the 16 rows EXR's zip compresses
// together.
constexpr int kRowsPerRead = 64;

// The exact sums of every group the file keeps, every channel read as 32-bit words whatever
// the file stores, a strip of rows at a time, each pixel's checked as a checkpoint's are
// (core/film/sum_validation.h), and added into `total` in the groups it keeps: a merge holds
// the total and a strip of one part's words, however many parts it adds.
void add_part_sums(ImageReader& in, const std::string& name, const SumChannels& found,
                   const RenderPart& part, PixelSums& total,
                   const std::function<void(int rows)>& rows_read) {
  const std::size_t width = std::size_t(part.width);
  std::vector<std::uint32_t> data(width * std::size_t(std::min(kRowsPerRead, part.height)) *
                                  found.stride);
  const auto kept = [&](SumGroup g) { return found.kept[std::size_t(g)]; };
  PixelSum sum;
  PixelSpread spread;
  FirstHitSum first_hit;
  const PixelSumsOut pixel{&sum, kept(SumGroup::Odd) ? &spread : nullptr,
                           kept(SumGroup::FirstHit) ? &first_hit : nullptr};
  const bool add_spread = total.keeps(SumGroup::Odd);
  const bool add_first_hit = total.keeps(SumGroup::FirstHit);
  for (int y0 = 0; y0 < part.height; y0 += kRowsPerRead) {
    const int y1 = std::min(part.height, y0 + kRowsPerRead);
    std::string reason;
    if (!in.read_rows(PixelType::UInt32, y0, y1, data.data(), reason)) {
      throw InvalidInput(name + ": cannot read its pixels: " + one_line(reason, 200));
    }
    for (std::size_t i = 0; i < width * std::size_t(y1 - y0); ++i) {
      const std::uint32_t* words = &data[i * found.stride];
      for (std::size_t g = 0; g < kSumGroups.size(); ++g) {
        for (std::size_t c = 0; c < found.words[g].size(); ++c) {
          uint128 bits = 0;
          for (int w = kWordsPerSum - 1; w >= 0; --w) {
            bits = (bits << 32) | words[found.words[g][c][std::size_t(w)]];
          }
          pixel.set(kSumGroups[g].group, c, static_cast<int128>(bits));
        }
      }
      const std::size_t p = std::size_t(y0) * width + i;
      const std::string impossible = impossible_sums(pixel.ref(), part.first_sample, part.samples);
      if (!impossible.empty()) {
        throw InvalidInput(name + ": pixel (" + std::to_string(p % width) + ", " +
                           std::to_string(p / width) +
                           ") has sums no samples can add up to: " + impossible);
      }
      total.color[p] += sum;
      if (add_spread) total.spreads[p] += spread;
      if (add_first_hit) total.first_hits[p] += first_hit;
    }
    rows_read(y1);
  }
}

// The rtiow version a part records ("unknown" if none): versions may draw other samples.
std::string part_version(const RenderPart& part) {
  for (const auto& [name, value] : part.metadata) {
    if (name != metadata_key::kVersion) continue;
    if (const auto* text = std::get_if<std::string>(&value)) return *text;
  }
  return "unknown";
}

// A part of the render `reference` is of: same rtiow, same scene and settings (digest), size
// and job.
void check_same_render(const RenderPart& reference, const RenderPart& part) {
  if (part_version(part) != part_version(reference)) {
    throw InvalidInput("merge: " + part.path + " was rendered by rtiow " + part_version(part) +
                       " and " + reference.path + " by rtiow " + part_version(reference) +
                       ": versions may draw other samples, so their shares do not add up");
  }
  if (part.digest != reference.digest || part.width != reference.width ||
      part.height != reference.height || part.job_samples != reference.job_samples) {
    throw InvalidInput("merge: " + part.path + " is a share of a different render than " +
                       reference.path +
                       " (scene, size, depth, seed, sampler, replicates, roulette or spp "
                       "differ; or one was written by an rtiow " +
                       part_version(reference) +
                       " from before its digest named the render's identity: render the "
                       "parts with one rtiow)");
  }
}

// Parts sorted by first sample must tile [0, job) exactly: no overlap, no gap, no missing end.
void check_tiling(const std::vector<const RenderPart*>& sorted) {
  const auto range = [](std::uint64_t a, std::uint64_t b) {
    return "[" + std::to_string(a) + ", " + std::to_string(b) + ")";
  };
  std::uint64_t next = 0;
  const RenderPart* previous = nullptr;
  for (const RenderPart* p : sorted) {
    if (p->first_sample < next) {
      throw InvalidInput("merge: " + previous->path + " and " + p->path +
                         " overlap: both hold samples " +
                         range(p->first_sample, std::min(next, p->first_sample + p->samples)));
    }
    if (p->first_sample > next) {
      throw InvalidInput("merge: samples " + range(next, p->first_sample) + " are missing" +
                         (previous ? " (between " + previous->path + " and " + p->path + ")"
                                   : " (before " + p->path + ")"));
    }
    next = p->first_sample + p->samples;
    previous = p;
  }
  if (next != sorted.front()->job_samples) {
    throw InvalidInput("merge: samples " + range(next, sorted.front()->job_samples) +
                       " of the job are missing (after " + previous->path + ")");
  }
}

// The metadata of `parts.front()` (the first part given), with the per-part counts totalled.
Metadata merged_metadata(const std::vector<RenderPart>& parts, std::uint64_t samples) {
  namespace field = metadata_key;
  std::int64_t rays = 0;
  for (const RenderPart& p : parts) {
    const std::int64_t part_rays = metadata_count(p, field::kRaysTraced);
    if (part_rays > std::numeric_limits<std::int64_t>::max() - rays) {
      throw InvalidInput("part file " + quote_value(p.path) + ": " + kMetadataPrefix +
                         field::kRaysTraced + " makes the total beyond 2^63");
    }
    rays += part_rays;
  }
  Metadata merged;
  for (const auto& [key, value] : parts.front().metadata) {
    if (key == field::kSpp) {
      merged.emplace_back(key, std::int64_t(samples));
    } else if (key == field::kRaysTraced) {
      merged.emplace_back(key, rays);
    } else if (key != field::kRenderSeconds && key != field::kSppRequested &&
               key != field::kStopped && key != field::kEstimatedImageError &&
               key != field::kErrorEstimate) {  // a part's estimate is of its share alone
      merged.emplace_back(key, value);
    }
  }
  return merged;
}

// The passes a part was rendered with (rtiow:passes, recorded by each).
FirstHitPasses recorded_passes(const RenderPart& part) {
  for (const auto& [key, value] : part.metadata) {
    if (key != metadata_key::kPasses) continue;
    const auto* text = std::get_if<std::string>(&value);
    try {
      if (text) return parse_passes(*text);
    } catch (const InvalidInput&) {
    }
    throw InvalidInput("part file " + quote_value(part.path) + ": " + kMetadataPrefix +
                       metadata_key::kPasses + " is not a list of passes");
  }
  return FirstHitPasses{};
}

}  // namespace

void PartMerge::add(const std::string& path) {
  const std::string name = "part file " + quote_value(path);
  auto in = open_input_image(path, name, limits::kMaxPartFileBytes, "part file");
  add(*in, path);
}

void PartMerge::add(ImageReader& in, const std::string& path) {
  const std::string name = "part file " + quote_value(path);
  const std::optional<SumChannels> channels = find_sum_channels(in.header());
  if (!channels) {
    throw InvalidInput(name + ": not a part file (render one with " + setting("sample_range") +
                       " or " + setting("part") + ")");
  }
  RenderPart part;
  part.path = path;
  read_part_header(in.header(), name, part);
  part.metadata = read_part_metadata(in.header());
  // Checked against the first part before any pixel is read. Every part must hold the sums of
  // the passes its render recorded, or the merged passes would lack samples.
  const FirstHitPasses passes = recorded_passes(part);
  if (parts_.empty()) {
    merged_.passes = passes;
  } else {
    check_same_render(parts_.front(), part);
    if (passes != merged_.passes) {
      throw InvalidInput("merge: " + part.path + " was rendered with " +
                         setting("passes", to_string(passes)) + " and " + parts_.front().path +
                         " with " + setting("passes", to_string(merged_.passes)) +
                         ": render every part with the same passes");
    }
  }
  const auto kept = [&](SumGroup g) { return channels->kept[std::size_t(g)]; };
  if (passes.any() && !kept(SumGroup::FirstHit)) {
    throw InvalidInput(name + ": records passes " + to_string(passes) +
                       " but holds no sums of them");
  }
  // The groups every part keeps are added: the variances need every part's spread (a part
  // written before parts kept them has none), the passes their sums as recorded.
  if (!kept(SumGroup::Odd) && merged_.without_spreads.empty()) merged_.without_spreads = path;
  if (parts_.empty()) {
    merged_.sums = PixelSums(std::size_t(part.width) * std::size_t(part.height),
                             kept(SumGroup::Odd), passes.any());
  } else if (!kept(SumGroup::Odd)) {
    merged_.sums.spreads = {};
  }
  const std::uint64_t before = std::uint64_t(parts_.size()) * kPartWork;
  add_part_sums(in, name, *channels, part, merged_.sums, [&](int rows) {
    if (reading_)
      reading_->done = before + kPartWork * std::uint64_t(rows) / std::uint64_t(part.height);
  });
  parts_.push_back(std::move(part));
}

MergedRender PartMerge::finish() && {
  if (parts_.empty()) throw InvalidInput("merge: no parts given");
  std::vector<const RenderPart*> sorted;
  for (const RenderPart& p : parts_) sorted.push_back(&p);
  std::sort(sorted.begin(), sorted.end(), [](const RenderPart* a, const RenderPart* b) {
    return a->first_sample < b->first_sample;
  });
  check_tiling(sorted);
  const RenderPart& reference = parts_.front();
  merged_.samples = reference.job_samples;
  merged_.film = Film(reference.width, reference.height);
  resolve(merged_.sums.color, merged_.samples, merged_.film);
  merged_.metadata = merged_metadata(parts_, merged_.samples);
  return std::move(merged_);
}

RenderResult merged_result(MergedRender&& merged, SamplerKind sampler, int replicates) {
  RenderResult r;
  r.film = std::move(merged.film);
  r.sums = std::move(merged.sums);
  r.sampler = sampler;
  r.replicates = replicates;
  complete_from_shares(merged.samples, r);
  return r;
}

}  // namespace rtiow
