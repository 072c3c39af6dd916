// libFuzzer target for the two files that hold a render's state, both untrusted input whose
// formats are public: the checkpoint reader (core/render/checkpoint_file.h) and the part-file
// reader (core/render/render_part.h). Any input must either be read or be refused with
// InvalidInput; any other exception, crash, leak, sanitizer report or oversized allocation is a
// finding. A state that is read must also hold what a render's state may hold.
//
// The first byte chooses the reader.
// - Checkpoint: the rest is the file before its checksum, and the harness appends the right
//   checksum (or, when the second byte is odd, the bytes as they are), so mutations of the
//   header and the records get past it.
// - Part file: the rest is "key=value" lines (a blank line ends them) that become the image's
//   attributes and its size, then the bytes of its 32-bit pixel words, cycled; the channels are
//   a part's, unless a "channels=" line names others.

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/io/checksum.h"
#include "core/io/image_file.h"
#include "core/limits/error.h"
#include "core/render/checkpoint_file.h"
#include "core/render/render_part.h"

namespace {

using rtiow::RenderIdentity;
using rtiow::RenderSettings;

// The request the fuzzed checkpoints are read for: a 5x3 cover, uniform or adaptive, with the
// passes or without, by bits of a byte.
RenderSettings request(bool adaptive, bool passes) {
  RenderSettings s;
  s.width = 5, s.height = 3, s.max_depth = 8;
  if (adaptive) s.samples = rtiow::PixelErrorTarget{0.05, 64, 4};
  if (passes) s.passes = {true, true, true};
  return s;
}

RenderIdentity identity(bool adaptive, bool passes) {
  RenderIdentity id;
  using F = rtiow::IdentityField;
  id[F::Version] = "0.3.0", id[F::Scene] = "fuzz-scene", id[F::Size] = "5x3";
  id[F::Depth] = "8", id[F::Seed] = "1", id[F::Sampler] = "sobol", id[F::Replicates] = "2";
  id[F::Roulette] = "on", id[F::FirstSample] = "0";
  id[F::Sampling] = adaptive ? "pixel error 0.05, 4 to 64 samples" : "uniform";
  id[F::Passes] = passes ? "albedo, normal and depth kept" : "none";
  return id;
}

void check_state(const rtiow::RenderState& state, const RenderSettings& s) {
  const std::size_t pixels = std::size_t(s.width) * std::size_t(s.height);
  if (state.pixels.samples.size() != pixels || state.pixels.sums.size() != pixels) __builtin_trap();
  if (state.pixels.sums.first_hits.size() != (s.passes.any() ? pixels : 0)) __builtin_trap();
  for (std::size_t p = 0; p < pixels; ++p) {
    if (state.pixels.samples[p] > 64 && rtiow::is_adaptive(s)) __builtin_trap();
    if (!state.targets.empty() && state.targets[p] > 64) __builtin_trap();
  }
  if (!(state.render_seconds >= 0.0)) __builtin_trap();
}

// The checkpoint the fuzz input becomes, in a directory of this process's own (mkdtemp: mode
// 0700, a name no one can predict or make first), removed with the file when the run ends.
std::string g_private_dir;

const std::string& private_checkpoint_path() {
  static const std::string path = [] {
    std::string dir = (std::filesystem::temp_directory_path() / "rtiow-fuzz-XXXXXX").string();
    if (!::mkdtemp(dir.data())) std::abort();
    g_private_dir = dir;
    std::atexit([] {
      ::unlink((g_private_dir + "/state.ckpt").c_str());
      ::rmdir(g_private_dir.c_str());
    });
    return dir + "/state.ckpt";
  }();
  return path;
}

void fuzz_checkpoint(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return;
  const bool adaptive = data[0] & 1, raw = data[0] & 2, passes = data[0] & 4;
  ++data, --size;
  std::string bytes(reinterpret_cast<const char*>(data), size);
  if (!raw) {
    rtiow::Checksum checksum;
    checksum.update(bytes.data(), bytes.size());
    const std::uint64_t sum = checksum.value();
    bytes.append(reinterpret_cast<const char*>(&sum), sizeof sum);
  }
  const std::string& path = private_checkpoint_path();
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_CLOEXEC, 0600);
  if (fd < 0) return;
  const bool written = ::write(fd, bytes.data(), bytes.size()) == ssize_t(bytes.size());
  ::close(fd);
  if (!written) return;
  const RenderSettings settings = request(adaptive, passes);
  try {
    const std::optional<rtiow::RenderState> state =
        rtiow::read_checkpoint(path, identity(adaptive, passes), settings);
    if (state) check_state(*state, settings);
    rtiow::read_checkpoint_summary(path);
  } catch (const rtiow::InvalidInput&) {
  }
}

// An image made of the fuzz input, as the part reader sees a file.
class FuzzImage final : public rtiow::ImageReader {
 public:
  FuzzImage(const std::uint8_t* data, std::size_t size) {
    std::size_t at = 0;
    std::string channels = "R,G,B";
    for (const char* group : {"sum", "odd", "squares"}) {
      for (const char* c : {"R", "G", "B"}) {
        for (int w = 0; w < 4; ++w) {
          channels += std::string(",") + group + "." + c + "." + std::to_string(w);
        }
      }
    }
    header_.width = header_.height = 2;
    while (at < size) {
      const auto* end = static_cast<const std::uint8_t*>(std::memchr(data + at, '\n', size - at));
      const std::size_t line_end = end ? std::size_t(end - data) : size;
      const std::string line(reinterpret_cast<const char*>(data + at), line_end - at);
      at = line_end + 1;
      if (line.empty()) break;
      const std::size_t eq = line.find('=');
      if (eq == std::string::npos) continue;
      const std::string key = line.substr(0, eq), value = line.substr(eq + 1);
      if (key == "width" || key == "height" || key == "x" || key == "depth") {
        const int v = std::atoi(value.c_str());
        (key == "width"    ? header_.width
         : key == "height" ? header_.height
         : key == "x"      ? header_.x
                           : header_.depth) = v;
      } else if (key == "channels") {
        channels = value;
      } else if (key.rfind("f:", 0) == 0) {
        header_.attributes.push_back({key.substr(2), float(std::atof(value.c_str()))});
      } else {
        header_.attributes.push_back({key, value});
      }
    }
    header_.full_width = header_.width, header_.full_height = header_.height;
    for (std::size_t from = 0; from <= channels.size();) {
      std::size_t comma = channels.find(',', from);
      if (comma == std::string::npos) comma = channels.size();
      header_.channel_names.push_back(channels.substr(from, comma - from));
      header_.channel_types.push_back(rtiow::PixelType::UInt32);
      from = comma + 1;
    }
    if (at < size) pixel_bytes_.assign(data + at, data + size);
  }
  const rtiow::ImageHeader& header() const override { return header_; }
  bool read_pixels(rtiow::PixelType type, void* pixels, std::string& reason) override {
    return read_rows(type, 0, header_.height, pixels, reason);
  }
  // The pixel bytes repeated from the image's first: row y begins where it would in the whole.
  bool read_rows(rtiow::PixelType, int y_begin, int y_end, void* pixels,
                 std::string& reason) override {
    if (pixel_bytes_.empty() || y_begin < 0 || y_end > header_.height || y_begin >= y_end) {
      reason = "no pixels";
      return false;
    }
    // Only a header that passed the reader's checks gets here: its size is bounded.
    const std::size_t row_words = std::size_t(header_.width) * header_.channel_names.size();
    const std::size_t first = std::size_t(y_begin) * row_words * 4;
    const std::size_t bytes = std::size_t(y_end - y_begin) * row_words * 4;
    auto* out = static_cast<unsigned char*>(pixels);
    for (std::size_t i = 0; i < bytes; ++i)
      out[i] = pixel_bytes_[(first + i) % pixel_bytes_.size()];
    return true;
  }

 private:
  rtiow::ImageHeader header_;
  std::vector<std::uint8_t> pixel_bytes_;
};

void fuzz_part(const std::uint8_t* data, std::size_t size) {
  FuzzImage image(data, size);
  // A header that claims more than a few thousand pixels is refused, or would take memory the
  // fuzzer's limit reports: only small images are read.
  if (std::int64_t(image.header().width) * image.header().height > 4096) return;
  try {
    rtiow::PartMerge merge;
    merge.add(image, "fuzz.exr");
    const rtiow::MergedRender merged = std::move(merge).finish();
    const std::size_t pixels =
        std::size_t(image.header().width) * std::size_t(image.header().height);
    if (merged.sums.size() != pixels || merged.film.pixels().size() != pixels) __builtin_trap();
  } catch (const rtiow::InvalidInput&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  if (data[0] & 0x80) {
    fuzz_part(data + 1, size - 1);
  } else {
    fuzz_checkpoint(data, size);
  }
  return 0;
}
