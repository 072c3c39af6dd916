#include "core/render/render_part.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <string_view>

#include "core/io/atomic_file.h"
#include "core/io/image_backend.h"
#include "core/io/image_file.h"
#include "core/limits/error.h"
#include "core/limits/input_limits.h"
#include "core/render/render_metadata.h"
#include "core/render/sample_share.h"
#include "core/sampling/rng.h"
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
// The exact sums a part holds per pixel, in this order: the samples' (always), and the
// spread's (the odd samples' and the squares') that the variances need.
constexpr std::array<const char*, 3> kSumGroups{"sum", "odd", "squares"};
constexpr int kWordsPerGroup = kColorChannels * kWordsPerSum;

// The passes' sums (core/film/first_hit_sum.h), in their order, as first_hit.<name>.<word>.
constexpr std::array<const char*, FirstHitSum::kChannels> kFirstHitNames{
    "albedo.R", "albedo.G", "albedo.B", "N.X", "N.Y", "N.Z", "Z"};
constexpr int kFirstHitWords = int(FirstHitSum::kChannels) * kWordsPerSum;

std::string first_hit_channel(std::size_t c, int word) {
  return std::string("first_hit.") + kFirstHitNames[c] + "." + std::to_string(word);
}

int channel_count(std::size_t groups, bool first_hits = false) {
  return kColorChannels + int(groups) * kWordsPerGroup + (first_hits ? kFirstHitWords : 0);
}

// Group g of pixel p's exact sums.
const PixelSum& group_sum(const RenderPart& part, std::size_t p, std::size_t g) {
  if (g == 0) return part.sums[p];
  return g == 1 ? part.spreads[p].odd : part.spreads[p].squares;
}

void set_group_sum(RenderPart& part, std::size_t p, std::size_t g, const PixelSum& sum) {
  PixelSum& into = g == 0 ? part.sums[p] : g == 1 ? part.spreads[p].odd : part.spreads[p].squares;
  for (int c = 0; c < kColorChannels; ++c) into.set_channel(c, sum.channel(c));
}

std::string hex(std::uint64_t v) {
  char buffer[17];
  std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(v));
  return buffer;
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

std::string render_digest(const Scene& scene, const RenderSettings& settings) {
  std::string text = scene_digest(scene);
  for (const std::uint64_t v : {std::uint64_t(settings.width), std::uint64_t(settings.height),
                                std::uint64_t(settings.max_depth), settings.seed}) {
    text.append("|").append(std::to_string(v));
  }
  text.append("|").append(to_string(settings.sampler));
  if (settings.crop) text.append("|crop ").append(to_string(*settings.crop));
  if (replicates(settings) == 1) text.append("|one sequence");  // other samples than replicates'
  if (!settings.russian_roulette) text.append("|no roulette");
  std::uint64_t h = 0x6a09e667f3bcc908ull;
  for (unsigned char c : text) h = hash_combine(h, c);
  return hex(h);
}

void write_part(const std::string& path, const RenderPart& part) {
  const ImageBackend& backend = image_backend();
  ImageHeader header;
  header.width = header.full_width = part.width;
  header.height = header.full_height = part.height;
  for (const char* c : {"R", "G", "B"}) {
    header.channel_names.emplace_back(c);
    header.channel_types.push_back(PixelType::Float);
  }
  const std::size_t groups = part.spreads.empty() ? 1 : kSumGroups.size();
  for (std::size_t g = 0; g < groups; ++g) {
    for (const char* c : {"R", "G", "B"}) {
      for (int w = 0; w < kWordsPerSum; ++w) {
        header.channel_names.push_back(std::string(kSumGroups[g]) + "." + c + "." +
                                       std::to_string(w));
        header.channel_types.push_back(PixelType::UInt32);
      }
    }
  }
  const bool first_hits = !part.first_hits.empty();
  for (std::size_t c = 0; first_hits && c < FirstHitSum::kChannels; ++c) {
    for (int w = 0; w < kWordsPerSum; ++w) {
      header.channel_names.push_back(first_hit_channel(c, w));
      header.channel_types.push_back(PixelType::UInt32);
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

  // Native layout: per pixel 3 floats, 12 words per group, then the passes' 28 words, all 4
  // bytes wide.
  const auto channels = std::size_t(channel_count(groups, first_hits));
  std::vector<std::uint32_t> data(std::size_t(part.width) * std::size_t(part.height) * channels);
  for (std::size_t p = 0; p < part.sums.size(); ++p) {
    std::uint32_t* pixel = &data[p * channels];
    const Color mean = part.sums[p].mean(part.samples);
    std::memcpy(pixel, &mean, sizeof mean);
    for (std::size_t g = 0; g < groups; ++g) {
      for (int c = 0; c < kColorChannels; ++c) {
        const auto bits = static_cast<uint128>(group_sum(part, p, g).channel(c));
        for (int w = 0; w < kWordsPerSum; ++w) {
          pixel[kColorChannels + int(g) * kWordsPerGroup + c * kWordsPerSum + w] =
              std::uint32_t(bits >> (32 * w));
        }
      }
    }
    std::uint32_t* words = pixel + channel_count(groups);
    for (std::size_t c = 0; first_hits && c < FirstHitSum::kChannels; ++c) {
      const auto bits = static_cast<uint128>(part.first_hits[p].channel(c));
      for (int w = 0; w < kWordsPerSum; ++w) *words++ = std::uint32_t(bits >> (32 * w));
    }
  }

  std::vector<unsigned char> encoded;
  std::string reason;
  if (!backend.encode(path, header, data.data(), encoded, reason)) {
    throw std::runtime_error("cannot write '" + path + "': " + reason);
  }
  write_bytes_atomically(path, encoded);
}

namespace {

// Where each 32-bit word of each colour's sum of each group is among the file's channels
// (EXR stores channels sorted by name): the samples' sums alone (a part written before parts
// kept their spreads) or every group; nothing if the file is not a part file.
using WordChannels = std::array<std::array<int, kWordsPerSum>, kColorChannels>;

// Where the passes' sums are among the file's channels; empty in a part without them.
struct SumChannels {
  std::vector<WordChannels> groups;
  std::vector<std::array<int, kWordsPerSum>> first_hits;
};

std::optional<SumChannels> find_sum_channels(const ImageHeader& header) {
  const std::vector<std::string>& names = header.channel_names;
  const bool first_hits =
      std::find(names.begin(), names.end(), first_hit_channel(0, 0)) != names.end();
  const auto count = [&](std::size_t groups) {
    return std::size_t(channel_count(groups, first_hits));
  };
  const std::size_t groups = names.size() == count(1)                   ? 1
                             : names.size() == count(kSumGroups.size()) ? 3
                                                                        : 0;
  if (groups == 0 || header.string_attribute(kDigest).empty()) return {};
  SumChannels found;
  for (std::size_t c = 0; first_hits && c < FirstHitSum::kChannels; ++c) {
    std::array<int, kWordsPerSum> words{};
    for (int w = 0; w < kWordsPerSum; ++w) {
      const auto it = std::find(names.begin(), names.end(), first_hit_channel(c, w));
      if (it == names.end()) return {};
      words[std::size_t(w)] = int(it - names.begin());
    }
    found.first_hits.push_back(words);
  }
  std::vector<WordChannels>& channels = found.groups;
  channels.resize(groups);
  for (std::size_t g = 0; g < groups; ++g) {
    for (int c = 0; c < kColorChannels; ++c) {
      for (int w = 0; w < kWordsPerSum; ++w) {
        const std::string channel =
            std::string(kSumGroups[g]) + "." + "RGB"[c] + "." + std::to_string(w);
        const auto it = std::find(names.begin(), names.end(), channel);
        if (it == names.end()) return {};
        channels[g][std::size_t(c)][std::size_t(w)] = int(it - names.begin());
      }
    }
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

// The exact sums (and spreads, where the file has them), every channel read as 32-bit words
// whatever the file stores.
void read_part_sums(ImageReader& in, const std::string& name, const SumChannels& found,
                    RenderPart& part) {
  const ImageHeader& header = in.header();
  const std::vector<WordChannels>& channels = found.groups;
  const std::size_t pixels = std::size_t(header.width) * std::size_t(header.height);
  const auto stride = std::size_t(channel_count(channels.size(), !found.first_hits.empty()));
  std::vector<std::uint32_t> data(pixels * stride);
  std::string reason;
  if (!in.read_pixels(PixelType::UInt32, data.data(), reason)) {
    throw InvalidInput(name + ": cannot read its pixels: " + one_line(reason, 200));
  }
  part.sums.assign(pixels, PixelSum{});
  if (channels.size() > 1) part.spreads.assign(pixels, PixelSpread{});
  if (!found.first_hits.empty()) part.first_hits.assign(pixels, FirstHitSum{});
  const auto word128 = [](const std::uint32_t* pixel, const std::array<int, kWordsPerSum>& at) {
    uint128 bits = 0;
    for (int w = kWordsPerSum - 1; w >= 0; --w) bits = (bits << 32) | pixel[at[std::size_t(w)]];
    return static_cast<int128>(bits);
  };
  for (std::size_t p = 0; p < pixels; ++p) {
    const std::uint32_t* pixel = &data[p * stride];
    for (std::size_t c = 0; c < found.first_hits.size(); ++c) {
      part.first_hits[p].set_channel(c, word128(pixel, found.first_hits[c]));
    }
    for (std::size_t g = 0; g < channels.size(); ++g) {
      PixelSum sum;
      for (std::size_t c = 0; c < kColorChannels; ++c) {
        sum.set_channel(int(c), word128(pixel, channels[g][c]));
      }
      set_group_sum(part, p, g, sum);
    }
  }
}

}  // namespace

RenderPart read_part(const std::string& path) {
  const std::string name = "part file " + quote_value(path);
  auto in = open_input_image(path, name, limits::kMaxPartFileBytes, "part file");
  return read_part(*in, path);
}

RenderPart read_part(ImageReader& in, const std::string& path) {
  const std::string name = "part file " + quote_value(path);
  const std::optional<SumChannels> channels = find_sum_channels(in.header());
  if (!channels) {
    throw InvalidInput(name + ": not a part file (render one with --sample-range or --part)");
  }
  RenderPart part;
  part.path = path;
  read_part_header(in.header(), name, part);
  part.metadata = read_part_metadata(in.header());
  read_part_sums(in, name, *channels, part);
  return part;
}

namespace {

// The rtiow version a part records ("unknown" if none): versions may draw other samples.
std::string part_version(const RenderPart& part) {
  for (const auto& [name, value] : part.metadata) {
    if (name != metadata_key::kVersion) continue;
    if (const auto* text = std::get_if<std::string>(&value)) return *text;
  }
  return "unknown";
}

// Parts of one render: same rtiow, same scene and settings (digest), size and job.
void check_same_render(const std::vector<const RenderPart*>& parts) {
  const RenderPart& reference = *parts.front();
  for (const RenderPart* p : parts) {
    if (part_version(*p) != part_version(reference)) {
      throw InvalidInput("merge: " + p->path + " was rendered by rtiow " + part_version(*p) +
                         " and " + reference.path + " by rtiow " + part_version(reference) +
                         ": versions may draw other samples, so their shares do not add up");
    }
    if (p->digest != reference.digest || p->width != reference.width ||
        p->height != reference.height || p->job_samples != reference.job_samples) {
      throw InvalidInput("merge: " + p->path + " is a share of a different render than " +
                         reference.path +
                         " (scene, size, depth, seed, sampler, roulette or spp differ)");
    }
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

// The metadata of `reference` (the first part given), with the per-part counts totalled.
Metadata merged_metadata(const RenderPart& reference, const std::vector<const RenderPart*>& parts,
                         std::uint64_t samples) {
  namespace field = metadata_key;
  std::int64_t rays = 0;
  for (const RenderPart* p : parts) {
    const std::int64_t part_rays = metadata_count(*p, field::kRaysTraced);
    if (part_rays > std::numeric_limits<std::int64_t>::max() - rays) {
      throw InvalidInput("part file " + quote_value(p->path) + ": " + kMetadataPrefix +
                         field::kRaysTraced + " makes the total beyond 2^63");
    }
    rays += part_rays;
  }
  Metadata merged;
  for (const auto& [key, value] : reference.metadata) {
    if (key == field::kSpp) {
      merged.emplace_back(key, std::int64_t(samples));
    } else if (key == field::kRaysTraced) {
      merged.emplace_back(key, rays);
    } else if (key != field::kRenderSeconds && key != field::kSppRequested &&
               key != field::kStopped) {
      merged.emplace_back(key, value);
    }
  }
  return merged;
}

// The passes the parts were rendered with (rtiow:passes, recorded by each) and the sums they
// are the mean of, added: every part must hold them, or the merged passes would lack samples.
void merge_first_hits(const RenderPart& reference, const std::vector<const RenderPart*>& parts,
                      MergedRender& merged) {
  const auto recorded = [](const RenderPart& part) {
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
  };
  merged.passes = recorded(reference);
  for (const RenderPart* p : parts) {
    if (recorded(*p) != merged.passes) {
      throw InvalidInput("merge: " + p->path + " was rendered with --passes " +
                         to_string(recorded(*p)) + " and " + reference.path + " with --passes " +
                         to_string(merged.passes) + ": render every part with the same passes");
    }
    if (merged.passes.any() && p->first_hits.empty()) {
      throw InvalidInput("part file " + quote_value(p->path) + ": records passes " +
                         to_string(merged.passes) + " but holds no sums of them");
    }
  }
  if (!merged.passes.any()) return;
  merged.first_hits = reference.first_hits;
  for (const RenderPart* p : parts) {
    if (p == &reference) continue;
    for (std::size_t i = 0; i < merged.first_hits.size(); ++i) {
      merged.first_hits[i] += p->first_hits[i];
    }
  }
}

}  // namespace

MergedRender merge_parts(const std::vector<RenderPart>& input) {
  if (input.empty()) throw InvalidInput("merge: no parts given");
  std::vector<const RenderPart*> parts;
  for (const RenderPart& p : input) parts.push_back(&p);
  check_same_render(parts);
  std::sort(parts.begin(), parts.end(), [](const RenderPart* a, const RenderPart* b) {
    return a->first_sample < b->first_sample;
  });
  check_tiling(parts);

  const RenderPart& reference = input.front();
  MergedRender merged;
  merged.samples = reference.job_samples;
  merged.sums = reference.sums;
  for (const RenderPart* p : parts) {
    if (p != &reference) add_sums(merged.sums.data(), p->sums.data(), merged.sums.size());
  }
  // The variances need every part's spread; a part written before parts kept them has none.
  const bool spreads = std::all_of(parts.begin(), parts.end(),
                                   [](const RenderPart* p) { return !p->spreads.empty(); });
  if (spreads) {
    merged.spreads = reference.spreads;
    for (const RenderPart* p : parts) {
      if (p == &reference) continue;
      for (std::size_t i = 0; i < merged.spreads.size(); ++i) merged.spreads[i] += p->spreads[i];
    }
  }
  merge_first_hits(reference, parts, merged);
  merged.film = Film(reference.width, reference.height);
  resolve(merged.sums, merged.samples, merged.film);
  merged.metadata = merged_metadata(reference, parts, merged.samples);
  return merged;
}

RenderResult merged_result(const MergedRender& merged, SamplerKind sampler, int replicates) {
  RenderResult r;
  r.film = merged.film;
  r.sums = merged.sums;
  r.spreads = merged.spreads;
  r.first_hits = merged.first_hits;
  r.sampler = sampler;
  r.replicates = replicates;
  complete_from_shares(merged.samples, r);
  return r;
}

}  // namespace rtiow
