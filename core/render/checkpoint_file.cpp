#include "core/render/checkpoint_file.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <utility>
#include <variant>
#include <vector>

#include "core/film/sum_validation.h"
#include "core/io/atomic_file.h"
#include "core/io/checksum.h"
#include "core/io/file_bytes.h"
#include "core/io/input_file.h"
#include "core/io/output_path.h"
#include "core/limits/error.h"
#include "core/limits/input_limits.h"
#include "core/limits/setting_name.h"
#include "core/scene_file/scene_digest.h"
#include "core/version.h"

namespace rtiow {
namespace {

constexpr char kMagicPrefix[] = "rtiow-checkpoint ";
constexpr char kMagic[] = "rtiow-checkpoint 4\n";
constexpr char kMagicFormat3[] = "rtiow-checkpoint 3\n";       // still read
constexpr char kMagicFixedRecords[] = "rtiow-checkpoint 2\n";  // still read
constexpr std::size_t kMaxHeaderBytes = 1 << 16;
constexpr std::size_t kChunkBytes = 1 << 20;
// A checkpoint's pixels take at most this many bytes each (version 2's fixed record is 160),
// so a file much larger than its pixels need is refused before it is read; the passes' seven
// sums add at most kMaxPassBytesPerPixel.
constexpr std::uint64_t kMaxBytesPerPixel = 4 * 3 * 19 + 3 * 10;
constexpr std::uint64_t kMaxPassBytesPerPixel = FirstHitSum::kChannels * 19;
// The longest a render can have run, in seconds (a century): beyond, a time is not one.
constexpr double kMaxRenderSeconds = 3.2e9;

// ---- Writing: variable-length integers (LEB128), seven bits a byte, low bits first.

void put_varint(std::vector<char>& out, uint128 v) {
  while (v >= 0x80) {
    out.push_back(char(std::uint8_t(v) | 0x80));
    v >>= 7;
  }
  out.push_back(char(std::uint8_t(v)));
}

// A signed difference, zigzagged so that small magnitudes take one byte.
void put_signed(std::vector<char>& out, std::int64_t v) {
  put_varint(out, (std::uint64_t(v) << 1) ^ std::uint64_t(v >> 63));
}

// A pixel's sums, group by group in the declaration's order (core/film/sum_channels.h): each
// channel a varint, a signed group's zigzagged over 128 bits.
void put_sums(std::vector<char>& out, const PixelSumsRef& sums) {
  for (const SumGroupDeclaration& d : kSumGroups) {
    for (std::size_t c = 0; sums.has(d.group) && c < d.channels; ++c) {
      const int128 v = sums.channel(d.group, c);
      put_varint(out, d.is_signed ? (uint128(v) << 1) ^ uint128(v >> 127) : uint128(v));
    }
  }
}

std::string exact(double v) {  // a double in text that reads back to the same bits
  char text[40];
  std::snprintf(text, sizeof text, "%a", v);
  return text;
}

std::string header_text(const RenderIdentity& id, const RenderState& state) {
  std::string h = kMagic;
  const auto line = [&](const char* key, const std::string& value) {
    h.append(key).append(" ").append(value).append("\n");
  };
  const auto& samples = state.pixels.samples;
  const auto [least, most] = std::minmax_element(samples.begin(), samples.end());
  for (const IdentityFieldDeclaration& d : kIdentityFields) line(d.key, id[d.field]);
  line("pixels", std::to_string(samples.size()));
  line("least_samples", std::to_string(samples.empty() ? 0 : *least));
  line("most_samples", std::to_string(samples.empty() ? 0 : *most));
  line("targets", state.targets.empty() ? "0" : "1");
  line("last_round", state.last_round ? "1" : "0");
  line("rays_traced", std::to_string(state.rays_traced));
  line("render_seconds", exact(state.render_seconds));
  line("judging_seconds", exact(state.judging_seconds));
  line("estimated_image_error", exact(state.estimated_image_error));
  line("pixels_above_target", std::to_string(state.pixels_above_target));
  h.append("end\n");
  return h;
}

// Writes `data` and adds it to the checksum; false (with `reason`) on failure.
bool write_summed(int fd, const char* data, std::size_t n, Checksum& checksum,
                  std::string& reason) {
  checksum.update(data, n);
  return write_all(fd, data, n, reason);
}

bool write_state(int fd, const RenderIdentity& identity, const RenderState& state,
                 std::string& reason) {
  Checksum checksum;
  const std::string header = header_text(identity, state);
  if (!write_summed(fd, header.data(), header.size(), checksum, reason)) return false;
  const PixelAccumulators& p = state.pixels;
  const bool targets = !state.targets.empty();
  std::vector<char> chunk;
  chunk.reserve(kChunkBytes + kMaxBytesPerPixel + kMaxPassBytesPerPixel);
  std::uint32_t previous_samples = 0;
  for (std::size_t i = 0; i < p.samples.size(); ++i) {
    put_signed(chunk, std::int64_t(p.samples[i]) - std::int64_t(previous_samples));
    previous_samples = p.samples[i];
    put_varint(chunk, p.rays[i]);
    if (targets) put_signed(chunk, std::int64_t(state.targets[i]) - std::int64_t(p.samples[i]));
    put_sums(chunk, p.sums.at(i));
    if (chunk.size() >= kChunkBytes || i + 1 == p.samples.size()) {
      if (!write_summed(fd, chunk.data(), chunk.size(), checksum, reason)) return false;
      chunk.clear();
    }
  }
  const std::uint64_t sum = checksum.value();
  return write_all(fd, &sum, sizeof sum, reason);
}

// ---- Reading.

InvalidInput bad_file(const std::string& path, const std::string& why) {
  return InvalidInput("checkpoint " + quote_value(path) + ": " + why +
                      " (not a checkpoint of this rtiow, or a damaged one: remove it)");
}

// Reads exactly n bytes; false at the end of the file or on an error.
bool read_exact(int fd, char* data, std::size_t n) {
  while (n > 0) {
    const ssize_t got = ::read(fd, data, n);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) return false;
    data += got;
    n -= std::size_t(got);
  }
  return true;
}

struct Header {
  int format = 4;
  bool fixed_records = false;  // format 2
  std::map<std::string, std::string> fields;
};

// The header's lines up to "end"; the bytes it took go to `checksum`.
Header read_header(int fd, const std::string& path, Checksum& checksum) {
  std::string text;
  char c = 0;
  while (text.size() < kMaxHeaderBytes && read_exact(fd, &c, 1)) {
    text.push_back(c);
    if (c == '\n' && text.size() >= 4 && text.compare(text.size() - 4, 4, "end\n") == 0) break;
  }
  Header header;
  header.fixed_records = text.rfind(kMagicFixedRecords, 0) == 0;
  header.format = header.fixed_records ? 2 : text.rfind(kMagicFormat3, 0) == 0 ? 3 : 4;
  if (text.rfind(kMagic, 0) != 0 && header.format == 4) {
    throw bad_file(path, text.rfind(kMagicPrefix, 0) == 0 ? "a checkpoint of another format"
                                                          : "no checkpoint header");
  }
  if (text.size() < 4 || text.compare(text.size() - 4, 4, "end\n") != 0) {
    throw bad_file(path, "the header does not end");
  }
  checksum.update(text.data(), text.size());
  std::size_t at = std::strlen(kMagic);
  while (at < text.size()) {
    const std::size_t end = text.find('\n', at);
    const std::string line = text.substr(at, end - at);
    at = end + 1;
    if (line == "end") break;
    const std::size_t space = line.find(' ');
    if (space == std::string::npos) throw bad_file(path, "a header line without a value");
    if (!header.fields.emplace(line.substr(0, space), line.substr(space + 1)).second) {
      throw bad_file(path, "header field " + quote_value(line.substr(0, space)) + " appears twice");
    }
  }
  return header;
}

std::uint64_t field_number(const Header& header, const char* key, const std::string& path,
                           std::uint64_t most) {
  const auto it = header.fields.find(key);
  std::uint64_t value = 0;
  if (it != header.fields.end()) {
    const std::string& t = it->second;
    const auto [end, error] = std::from_chars(t.data(), t.data() + t.size(), value);
    if (error == std::errc() && end == t.data() + t.size() && value <= most) return value;
  }
  throw bad_file(path, std::string("header field ") + key + " is missing or not a whole number " +
                           "from 0 to " + std::to_string(most));
}

double field_double(const Header& header, const char* key, const std::string& path, double most) {
  const auto it = header.fields.find(key);
  if (it != header.fields.end()) {
    char* end = nullptr;
    const double v = std::strtod(it->second.c_str(), &end);
    if (!it->second.empty() && *end == '\0' && std::isfinite(v) && v >= 0.0 && v <= most) return v;
  }
  throw bad_file(path, std::string("header field ") + key +
                           " is missing or not a finite number from 0 to " + exact(most));
}

std::string field_text(const Header& header, const char* key) {
  const auto it = header.fields.find(key);
  return it == header.fields.end() ? std::string("(none)") : it->second;
}

// Formats 2 and 3 named the sampling as the command line spelt it then ("--target-error
// 0.05 --min-spp 16 --spp 64") and folded the replicates and the roulette into the sampler
// ("sobol (one sequence) (no roulette)"). Read into the identity's words, so a render kept by
// an older rtiow still continues; what does not parse stays as it was, and so differs by name.
void read_older_identity(const Header& header, RenderIdentity& id) {
  using F = IdentityField;
  std::string sampler = field_text(header, "sampler");
  const auto take = [&](const std::string& suffix) {
    const std::size_t at = sampler.find(suffix);
    if (at == std::string::npos) return false;
    sampler.erase(at, suffix.size());
    return true;
  };
  id[F::Roulette] = roulette_name(!take(" (no roulette)"));
  id[F::Replicates] = take(" (one sequence)") ? "1" : std::to_string(kReplicates);
  id[F::Sampler] = sampler;
  const std::string mode = field_text(header, "mode");
  double error = 0.0;
  int least = 0, most = 0, used = 0;
  const char* m = mode.c_str();
  const auto whole = [&](int n, int expected) { return n == expected && m[used] == '\0'; };
  std::optional<SampleBudget> budget;
  if (mode == "uniform") {
    budget = FixedSamples{};
  } else if (whole(std::sscanf(m, "--target-error %lf --min-spp %d --spp %d%n", &error, &least,
                               &most, &used),
                   3)) {
    budget = PixelErrorTarget{error, most, least};
  } else if (whole(std::sscanf(m, "--image-error %lf --min-spp %d --spp %d%n", &error, &least,
                               &most, &used),
                   3)) {
    budget = ImageErrorTarget{error, most, least};
  } else if (whole(std::sscanf(m, "--adaptive --min-spp %d --spp %d%n", &least, &most, &used), 2)) {
    budget = AdaptiveBudget{most, least};
  } else if (whole(
                 std::sscanf(m, "--adaptive --min-spp %d (until the time limit)%n", &least, &used),
                 1)) {
    budget = AdaptiveBudget{std::nullopt, least};
  }
  id[F::Sampling] = budget ? sampling_words(*budget) : mode;
  // A checkpoint from before the passes keeps none.
  if (!header.fields.count("passes")) id[F::Passes] = "none";
}

RenderIdentity stored_identity(const Header& header) {
  RenderIdentity id;
  for (const IdentityFieldDeclaration& d : kIdentityFields) id[d.field] = field_text(header, d.key);
  if (header.format < 4) read_older_identity(header, id);
  return id;
}

// The most samples a pixel of this render may hold: its cap when adaptive; otherwise what its
// sample indices can name.
std::uint64_t most_samples(const RenderSettings& s) {
  if (const auto* t = std::get_if<PixelErrorTarget>(&s.samples)) return std::uint64_t(t->most);
  if (const auto* i = std::get_if<ImageErrorTarget>(&s.samples)) return std::uint64_t(i->most);
  if (std::holds_alternative<AdaptiveBudget>(s.samples)) return limits::kMostAdaptiveSamples;
  const std::uint64_t indices =
      s.first_sample < limits::kMaxSampleIndex ? limits::kMaxSampleIndex - s.first_sample : 0;
  return std::min<std::uint64_t>(indices, std::uint64_t(std::numeric_limits<int>::max()));
}

// The pixel records, in 1 MiB reads; every byte taken goes to the checksum.
class RecordReader {
 public:
  RecordReader(int fd, Checksum& checksum, const std::string& path)
      : fd_(fd), checksum_(checksum), path_(path), buffer_(kChunkBytes) {}

  std::uint8_t byte() {
    if (at_ == end_ && !refill()) {
      throw InvalidInput("checkpoint " + quote_value(path_) +
                         ": ends before its pixels do (a damaged file: remove it)");
    }
    return std::uint8_t(buffer_[at_++]);
  }
  template <typename T>
  T fixed() {  // little-endian, sizeof(T) bytes
    T value = 0;
    for (std::size_t i = 0; i < sizeof(T); ++i) value |= T(T(byte()) << (8 * i));
    return value;
  }
  uint128 varint() {
    uint128 value = 0;
    for (int shift = 0; shift < 128; shift += 7) {
      const std::uint8_t b = byte();
      if (shift == 126 && (b & 0x7c) != 0) break;  // beyond 128 bits
      value |= uint128(b & 0x7f) << shift;
      if ((b & 0x80) == 0) return value;
    }
    throw bad_file(path_, "a pixel holds a number too long to be one");
  }
  int128 signed_varint128() {
    const uint128 z = varint();
    return int128(z >> 1) ^ -int128(z & 1);
  }
  std::int64_t signed_varint() {
    const uint128 z = varint();
    if (z >> 64) throw bad_file(path_, "a pixel holds a difference too large to be one");
    const auto u = std::uint64_t(z);
    return std::int64_t(u >> 1) ^ -std::int64_t(u & 1);
  }
  // Whether the checksum of every byte taken follows, and nothing after it.
  bool ends_with_checksum() {
    sum_taken();
    const std::uint64_t expected = checksum_.value();
    std::uint64_t stored = 0;
    for (std::size_t i = 0; i < sizeof stored; ++i) {
      if (at_ == end_ && !refill()) {
        throw InvalidInput("checkpoint " + quote_value(path_) +
                           ": ends before its checksum (a damaged file: remove it)");
      }
      stored |= std::uint64_t(std::uint8_t(buffer_[at_++])) << (8 * i);
      summed_ = at_;  // the stored checksum is not part of what it sums
    }
    char extra = 0;
    return stored == expected && at_ == end_ && !read_exact(fd_, &extra, 1);
  }

 private:
  void sum_taken() {
    checksum_.update(buffer_.data() + summed_, at_ - summed_);
    summed_ = at_;
  }
  bool refill() {
    sum_taken();
    ssize_t got = 0;
    do {
      got = ::read(fd_, buffer_.data(), buffer_.size());
    } while (got < 0 && errno == EINTR);
    if (got <= 0) return false;
    at_ = summed_ = 0, end_ = std::size_t(got);
    return true;
  }

  int fd_;
  Checksum& checksum_;
  const std::string& path_;
  std::vector<char> buffer_;
  std::size_t at_ = 0, end_ = 0, summed_ = 0;
};

// A pixel's sums, group by group in the declaration's order, as put_sums wrote them; version
// 2's fixed records hold the colour's three groups as 16 bytes a channel.
void read_sums(RecordReader& in, bool fixed_records, const PixelSumsOut& sums) {
  for (const SumGroupDeclaration& d : kSumGroups) {
    for (std::size_t c = 0; sums.has(d.group) && c < d.channels; ++c) {
      if (fixed_records) {
        const auto low = in.fixed<std::uint64_t>(), high = in.fixed<std::uint64_t>();
        sums.set(d.group, c, int128((uint128(high) << 64) | low));
      } else {
        sums.set(d.group, c, d.is_signed ? in.signed_varint128() : int128(in.varint()));
      }
    }
  }
}

}  // namespace

std::string checkpoint_path(const std::string& output) {
  return output + kCheckpointSuffix;
}

void write_checkpoint(const std::string& path, const RenderIdentity& identity,
                      const RenderState& state) {
  try {
    write_atomically(path, [&](int fd, std::string& reason) {
      return write_state(fd, identity, state, reason);
    });
  } catch (const std::bad_alloc&) {
    throw std::runtime_error("cannot write the checkpoint " + quote_value(path) +
                             ": out of memory");
  } catch (const std::runtime_error& e) {
    // "cannot write 'path': why" as the checkpoint's own words
    const std::string text = e.what();
    const std::size_t colon = text.find("': ");
    throw std::runtime_error("cannot write the checkpoint " + quote_value(path) + ": " +
                             (colon == std::string::npos ? text : text.substr(colon + 3)));
  }
}

namespace {

// The file at `path`, opened as a checkpoint must be: rtiow's own state (never through a
// link, never a hard link, never another user's file), never blocking (a FIFO is refused), a
// regular file. Nothing when there is none.
std::optional<InputFile> open_checkpoint(const std::string& path) {
  return InputFile::open_if_present(path, std::numeric_limits<std::uint64_t>::max(), "checkpoint",
                                    InputKind::OwnState);
}

}  // namespace

std::optional<CheckpointSummary> read_checkpoint_summary(const std::string& path) {
  const std::optional<InputFile> file = open_checkpoint(path);
  if (!file) return std::nullopt;
  Checksum ignored;
  const Header header = read_header(file->fd(), path, ignored);
  CheckpointSummary summary{stored_identity(header), {}, {}};
  if (!header.fixed_records) {
    constexpr std::uint64_t kAny = std::numeric_limits<std::uint32_t>::max();
    summary.least_samples = field_number(header, "least_samples", path, kAny);
    summary.most_samples = field_number(header, "most_samples", path, kAny);
  }
  return summary;
}

namespace {

// What the header says of its pixels as a whole, checked against them once they are read.
struct StoredTotals {
  std::uint64_t rays_traced = 0;
  std::optional<std::uint64_t> least_samples, most_samples;
};

// The header's fields against the request and the limits, before anything is allocated: the
// state they describe, its pixels still to be read.
RenderState state_of_header(const Header& header, const InputFile& file, const std::string& path,
                            const RenderSettings& settings, StoredTotals& totals) {
  const std::uint64_t expected_pixels =
      std::uint64_t(film_width(settings)) * std::uint64_t(film_height(settings));
  const std::uint64_t pixels = field_number(header, "pixels", path, limits::kMaxPixels);
  if (pixels != expected_pixels) {
    throw bad_file(path, "holds " + std::to_string(pixels) + " pixels, not the image's " +
                             std::to_string(expected_pixels));
  }
  const bool first_hits = settings.passes.any();
  const std::uint64_t most_bytes = kMaxBytesPerPixel + (first_hits ? kMaxPassBytesPerPixel : 0);
  if (file.size() > pixels * most_bytes + kMaxHeaderBytes + 8) {
    throw bad_file(path, "is larger than its pixels can be");
  }
  const bool adaptive = is_adaptive(settings);
  const std::uint64_t most = most_samples(settings);
  const bool targets = field_number(header, "targets", path, adaptive ? 1 : 0) != 0;
  const bool last_round = field_number(header, "last_round", path, adaptive ? 1 : 0) != 0;
  totals.rays_traced =
      field_number(header, "rays_traced", path, std::numeric_limits<std::uint64_t>::max());
  const double seconds = field_double(header, "render_seconds", path, kMaxRenderSeconds);
  // Of them, the denoiser's judgements: absent from a checkpoint of an rtiow before it (none).
  const double judging = header.fields.count("judging_seconds")
                             ? field_double(header, "judging_seconds", path, seconds)
                             : 0.0;
  const double image_error = field_double(header, "estimated_image_error", path, 1e300);
  const std::uint64_t above = field_number(header, "pixels_above_target", path, pixels);
  if (!header.fixed_records) {
    totals.least_samples = field_number(header, "least_samples", path, most);
    totals.most_samples = field_number(header, "most_samples", path, most);
  }
  if (header.fixed_records && first_hits) {
    throw bad_file(path, "is of a version that kept no passes");
  }
  RenderState state{std::size_t(pixels), first_hits};
  if (targets) state.targets.resize(std::size_t(pixels));
  state.last_round = last_round;
  state.rays_traced = totals.rays_traced;
  state.render_seconds = seconds;
  state.judging_seconds = judging;
  state.estimated_image_error = image_error;
  state.pixels_above_target = above;
  return state;
}

// One pixel's record as stored: its sample count, rays and adaptive target, a count or target
// of -1 where its difference runs beyond the cap `most` (refused before it is added: no
// overflow). Its sums go into `sums`.
struct PixelRecord {
  std::int64_t samples = 0, target = 0;
  std::uint64_t rays = 0;
};

PixelRecord read_pixel_record(RecordReader& in, bool fixed_records, bool targets,
                              std::int64_t previous, std::uint64_t most, const PixelSumsOut& sums) {
  PixelRecord r;
  if (fixed_records) {
    read_sums(in, true, sums);
    r.samples = in.fixed<std::uint32_t>();
    r.rays = in.fixed<std::uint64_t>();
    if (targets) r.target = in.fixed<std::uint32_t>();
    return r;
  }
  const auto bounded = [&](std::int64_t d) {
    return d >= -std::int64_t(most) && d <= std::int64_t(most);
  };
  const std::int64_t difference = in.signed_varint();
  r.samples = bounded(difference) ? previous + difference : -1;
  const uint128 rays = in.varint();
  r.rays = rays >> 64 ? std::numeric_limits<std::uint64_t>::max() : std::uint64_t(rays);
  if (targets) {
    const std::int64_t beyond = in.signed_varint();
    r.target = bounded(beyond) ? r.samples + beyond : -1;
  }
  read_sums(in, false, sums);
  return r;
}

// Pixel i's record against what a render of `settings` can hold: a count and a target within
// the cap, one count for every pixel of a uniform render, rays no more than its samples can
// trace, sums within what its samples can add up to.
void check_pixel_record(const PixelRecord& r, std::size_t i, const RenderState& state,
                        const RenderSettings& settings, const std::string& path) {
  const auto bad_pixel = [&](const std::string& why) {
    return bad_file(path, "pixel " + std::to_string(i) + " " + why);
  };
  const std::uint64_t most = most_samples(settings);
  if (r.samples < 0 || std::uint64_t(r.samples) > most) {
    throw bad_pixel("has a sample count outside 0 to " + std::to_string(most));
  }
  if (!state.targets.empty() && (r.target < 0 || std::uint64_t(r.target) > most)) {
    throw bad_pixel("has an adaptive target outside 0 to " + std::to_string(most));
  }
  const auto n = std::uint64_t(r.samples);
  if (!is_adaptive(settings) && i > 0 && n != state.pixels.samples[0]) {
    throw bad_pixel("has another count than the first pixel's, in a uniform render");
  }
  const auto depth = std::uint64_t(std::max(settings.max_depth, 0));
  if (uint128(r.rays) > uint128(n) * depth) {
    throw bad_pixel("has more rays than its samples can trace at depth " + std::to_string(depth));
  }
  // Every pixel's samples start at the request's first sample.
  const std::string impossible =
      impossible_sums(std::as_const(state.pixels.sums).at(i), settings.first_sample, n);
  if (!impossible.empty()) throw bad_pixel("has sums no samples can add up to: " + impossible);
}

}  // namespace

std::optional<RenderState> read_checkpoint(const std::string& path, const RenderIdentity& expected,
                                           const RenderSettings& settings) {
  const std::optional<InputFile> file = open_checkpoint(path);
  if (!file) return std::nullopt;
  Checksum checksum;
  const Header header = read_header(file->fd(), path, checksum);
  const std::string differs =
      identity_mismatch(stored_identity(header), expected, "the checkpoint's");
  if (!differs.empty()) {
    throw InvalidInput("checkpoint " + quote_value(path) + " is of another render (" + differs +
                       "): remove it, or render with " + setting("restart") + " to replace it");
  }
  StoredTotals totals;
  RenderState state = state_of_header(header, *file, path, settings, totals);

  // Each pixel's record, checked as it is read.
  RecordReader in(file->fd(), checksum, path);
  PixelAccumulators& p = state.pixels;
  const std::uint64_t most = most_samples(settings);
  const bool targets = !state.targets.empty();
  std::uint64_t rays_sum = 0, least = most, most_seen = 0;
  std::int64_t previous = 0;
  for (std::size_t i = 0; i < p.samples.size(); ++i) {
    const PixelRecord r =
        read_pixel_record(in, header.fixed_records, targets, previous, most, p.sums.at(i));
    previous = r.samples;
    check_pixel_record(r, i, state, settings, path);
    const auto n = std::uint64_t(r.samples);
    p.samples[i] = std::uint32_t(n);
    p.rays[i] = r.rays;
    if (targets) state.targets[i] = std::uint32_t(r.target);
    rays_sum += r.rays;
    least = std::min(least, n), most_seen = std::max(most_seen, n);
  }
  if (!in.ends_with_checksum()) {
    throw InvalidInput("checkpoint " + quote_value(path) +
                       ": its checksum does not match its content (a damaged file: remove it)");
  }
  if (rays_sum != totals.rays_traced) {
    throw bad_file(path, "header field rays_traced is not the sum of its pixels' rays");
  }
  const std::uint64_t pixels = p.samples.size();
  if ((totals.least_samples && *totals.least_samples != (pixels ? least : 0)) ||
      (totals.most_samples && *totals.most_samples != most_seen)) {
    throw bad_file(path, "header fields least_samples and most_samples are not its pixels'");
  }
  return state;
}

}  // namespace rtiow
